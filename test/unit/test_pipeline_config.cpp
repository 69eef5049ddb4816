// The pipeline's parameters: one source of defaults (the params structs),
// config/pipeline.yaml agreeing with it, user files read over it, and the
// stages' summaries of what they did.

#include <cmath>
#include <cstdio>
#include <fstream>

#include <gtest/gtest.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/common/yaml_document.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/pipeline/stage_stats.h"

namespace brick_pose
{
namespace
{
const std::string kPipelineYaml = std::string(BRICK_POSE_SOURCE_DIR) + "/config/pipeline.yaml";

ParamLookup nothingSet()
{
  return [](const std::string&) { return std::optional<std::string>(); };
}

std::string writeTemporaryFile(const std::string& text)
{
  char path[] = "/tmp/brick_pose_params_XXXXXX";
  const int fd = mkstemp(path);
  EXPECT_GE(fd, 0);
  std::ofstream(path) << text;
  return path;
}
}  // namespace

TEST(PipelineConfig, ShippedYamlAgreesWithTheStructDefaults)
{
  const std::map<std::string, std::string> yaml = readYamlParamFile(kPipelineYaml);
  ASSERT_FALSE(yaml.empty());
  const auto defaults = pipelineParamsInEffect(nothingSet());
  const auto from_yaml = pipelineParamsInEffect(mapParamLookup(yaml));
  for (const auto& [name, value] : yaml)
  {
    ASSERT_TRUE(defaults.count(name)) << "pipeline.yaml sets '" << name << "', which no stage reads";
    EXPECT_EQ(from_yaml.at(name), defaults.at(name))
        << "pipeline.yaml sets " << name << ": " << value << " but the struct default is " << defaults.at(name);
  }
}

TEST(PipelineConfig, UserFileOverridesOnlyWhatItSets)
{
  const std::string path = writeTemporaryFile("max_time_s: 0.05\nmode: region_growing\nqueue_size: 4\n");
  const ParamLookup lookup = overlayParamLookup(mapParamLookup(readYamlParamFile(path)),
                                                mapParamLookup(readYamlParamFile(kPipelineYaml)));
  const auto effect = pipelineParamsInEffect(lookup);
  EXPECT_EQ(effect.at("max_time_s"), "0.05");
  EXPECT_EQ(effect.at("mode"), "region_growing");
  EXPECT_EQ(effect.at("queue_size"), "4");
  EXPECT_EQ(effect.at("delta_m"), pipelineParamsInEffect(nothingSet()).at("delta_m"));
  std::remove(path.c_str());
}

TEST(PipelineConfig, BadUserFilesNameTheProblem)
{
  const auto errorOf = [](const std::string& text) {
    const std::string path = writeTemporaryFile(text);
    std::string message;
    try
    {
      pipelineParamsInEffect(mapParamLookup(readYamlParamFile(path)));
    }
    catch (const ConfigError& e)
    {
      message = e.what();
    }
    std::remove(path.c_str());
    return message;
  };
  EXPECT_NE(errorOf("registration:\n  max_frame_registration_ms: 10\n").find("'registration' is a map"),
            std::string::npos);
  EXPECT_NE(errorOf("queue_size: 0\n").find("queue_size"), std::string::npos);
  EXPECT_NE(errorOf("max_latency_ms: fast\n").find("max_latency_ms"), std::string::npos);
  EXPECT_NE(errorOf("- 1\n- 2\n").find("root must be a map"), std::string::npos);
  EXPECT_THROW(readYamlParamFile("/nonexistent/params.yaml"), ConfigError);
}

TEST(StageStats, SummaryCountsDropsByReasonLargestFirst)
{
  StageStats stats("roi_filter", "segments", "candidates");
  for (int i = 0; i < 4; ++i)
  {
    stats.frameIn();
    stats.frameOut(10.0 + i, 20.0 + i);
  }
  stats.frameIn();
  stats.frameDropped("over the latency budget");
  stats.items(14, 3);
  stats.itemDropped("too small", 4);
  stats.itemDropped("cut by the border", 6);
  stats.itemDropped("not flat");
  const StageReport report = stats.report(2.0);
  EXPECT_DOUBLE_EQ(report.input_rate_hz, 2.5);
  EXPECT_DOUBLE_EQ(report.output_rate_hz, 2.0);
  EXPECT_DOUBLE_EQ(report.processing_p50_ms, 11.5);
  EXPECT_TRUE(report.hasDrops());
  const std::string line = report.summary();
  EXPECT_NE(line.find("dropped 1 frames: 1 over the latency budget"), std::string::npos) << line;
  EXPECT_NE(line.find("14 segments -> 3 candidates: 6 cut by the border, 4 too small, 1 not flat"), std::string::npos)
      << line;
  // Counts restart with each report; the timing window keeps its samples.
  const StageReport next = stats.report(1.0);
  EXPECT_EQ(next.frames_in, 0);
  EXPECT_FALSE(next.hasDrops());
  EXPECT_DOUBLE_EQ(next.processing_p50_ms, 11.5);
}

TEST(StageStats, WindowKeepsTheLatestSamplesAndIgnoresNonFinite)
{
  SampleWindow window(3);
  for (double value : {100.0, 1.0, 2.0, 3.0, std::nan("")}) window.add(value);
  EXPECT_EQ(window.size(), 3u);
  EXPECT_DOUBLE_EQ(window.percentile(1.0), 3.0);
  EXPECT_TRUE(std::isnan(SampleWindow().percentile(0.5)));
}
}  // namespace brick_pose
