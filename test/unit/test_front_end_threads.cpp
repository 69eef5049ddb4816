// Issue 14: the front end filters a pile's segments, searches the colours and
// measures the bricks cut from a merged face on several threads, and gives
// exactly what one thread gives, in the same order.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace
{
RgbdFrame sceneFrame(sim::SceneKind kind, std::uint64_t seed, const std::vector<std::string>& types = {})
{
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  sim::SceneParams params = sim::SceneParams::defaultsFor(kind);
  if (!types.empty()) params.types = types;
  const sim::Scene scene = sim::SceneGenerator(catalogue, params).generate(seed);
  const sim::SyntheticRig rig(PinholeCamera::d415Color1280x720(), sim::SensorModel());
  const sim::SyntheticFrame rendered = rig.render(scene, seed);
  return makeRgbdFrame(rendered.rgb, rendered.depth_mm, rendered.camera, FrameHeader{0, "camera"});
}

void expectSameResults(const FrontEndResult& one, const FrontEndResult& two)
{
  ASSERT_EQ(two.candidates.size(), one.candidates.size());
  for (std::size_t i = 0; i < one.candidates.size(); ++i)
  {
    EXPECT_EQ(two.candidates[i].type_name, one.candidates[i].type_name) << "candidate " << i;
    EXPECT_EQ(two.candidates[i].complete, one.candidates[i].complete) << "candidate " << i;
    EXPECT_EQ((two.candidates[i].centroid_m - one.candidates[i].centroid_m).norm(), 0.0) << "candidate " << i;
    EXPECT_EQ(two.candidates[i].pixel_indices, one.candidates[i].pixel_indices) << "candidate " << i;
  }
  ASSERT_EQ(two.rejections.size(), one.rejections.size());
  for (std::size_t i = 0; i < one.rejections.size(); ++i)
    EXPECT_EQ(two.rejections[i].reason, one.rejections[i].reason) << "rejection " << i;
}

FrontEndResult processWith(int threads, const RgbdFrame& frame)
{
  FrontEndParams params;
  params.worker_threads = threads;
  return FrontEnd(BrickCatalogue::mbzirc2020(), params).process(frame);
}

TEST(FrontEndThreads, PileGivesTheSameCandidatesAndRejectionsOnTwoThreads)
{
  // The first seeded pile with enough segments to share between threads.
  RgbdFrame frame;
  FrontEndResult one;
  for (std::uint64_t seed = 0; seed < 20 && one.candidates.size() + one.rejections.size() < 4; ++seed)
  {
    frame = sceneFrame(sim::SceneKind::kUnorganisedPile, seed);
    one = processWith(1, frame);
  }
  ASSERT_GE(one.candidates.size() + one.rejections.size(), 4u)
      << "no pile in 20 seeds gave several segments to share between threads";
  const FrontEndResult two = processWith(2, frame);
  expectSameResults(one, two);
  // The stage profile still adds up to the work done, not to twice it.
  EXPECT_GE(two.timings.roi_ms, 0.0);
  EXPECT_GE(two.timings.cloud.total(), 0.0);
}

TEST(FrontEndThreads, RowOfTouchingBricksGivesTheSameBricksOnTwoThreads)
{
  // One red segment of touching bricks, cut by tiling: its bricks are
  // measured on both threads.
  RgbdFrame frame;
  FrontEndResult one;
  for (std::uint64_t seed = 10; seed < 30 && one.candidates.size() < 3; ++seed)
  {
    frame = sceneFrame(sim::SceneKind::kTouchingRows, seed, {"red"});
    one = processWith(1, frame);
  }
  ASSERT_GE(one.candidates.size(), 3u) << "no row of touching reds in 20 seeds was cut into bricks";
  expectSameResults(one, processWith(2, frame));
}
}  // namespace
}  // namespace brick_pose
