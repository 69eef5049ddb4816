// What the tracker's static-pose smoothing removes: the frame-to-frame
// jitter of a static brick's published pose (issue 11).
//
//   bench_tracking [--frames N (60)] [--scenes N (6)] [--weight W (0.2)]
//
// Each scene (singles and piles of the synthetic D415 rig, 1280x720) is
// rendered N times with fresh sensor noise and run through the core's front
// end, Super4PCS and correction (the pipeline's defaults) and the
// BrickTracker, once with smoothing off (weight 1) and once at W. Jitter is
// the RMS distance of a track's published poses from their own mean, over
// the frames after the first ten (smoothing needs a few frames to settle);
// only tracks seen in every frame count.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include <Eigen/SVD>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/param_parsing.h"
#include "brick_pose/common/statistics.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/pose/brick_pose_estimator.h"
#include "brick_pose/pose/brick_tracker.h"
#include "brick_pose/sim/rig_config.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace
{
constexpr int kSettleFrames = 10;

struct Options
{
  int frames = 60;
  int scenes = 6;
  double weight = 0.2;
};

Options parseOptions(int argc, char** argv)
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--frames" && has_value) options.frames = std::atoi(argv[++i]);
    else if (arg == "--scenes" && has_value) options.scenes = std::atoi(argv[++i]);
    else if (arg == "--weight" && has_value) options.weight = std::atof(argv[++i]);
    else
    {
      std::fprintf(stderr, "usage: bench_tracking [--frames N (60)] [--scenes N (6)] [--weight W (0.2)]\n");
      std::exit(arg == "--help" ? 0 : 2);
    }
  }
  if (options.frames <= kSettleFrames + 2 || options.scenes < 1 || !(options.weight > 0.0 && options.weight <= 1.0))
  {
    std::fprintf(stderr, "bench_tracking: --frames must exceed %d, --scenes >= 1, --weight in (0, 1]\n",
                 kSettleFrames + 2);
    std::exit(2);
  }
  return options;
}

/// The observations of one rendered frame: every candidate the estimator
/// gives a pose for.
std::vector<TrackerObservation> observe(const FrontEnd& front_end, const BrickPoseEstimator& estimator,
                                        const sim::SyntheticFrame& rendered)
{
  const RgbdFrame frame = makeRgbdFrame(rendered.rgb, rendered.depth_mm, rendered.camera, FrameHeader{0, "camera"});
  std::vector<TrackerObservation> observations;
  for (const BrickCandidate& candidate : front_end.process(frame).candidates)
  {
    try
    {
      observations.push_back({candidate.type_name, estimator.estimate(candidate).pose});
    }
    catch (const std::exception&)
    {
      // No pose for this candidate in this frame: the track misses a frame.
    }
  }
  return observations;
}

struct Jitter
{
  std::vector<double> translation_mm;  ///< per track: RMS distance from the mean position
  std::vector<double> rotation_deg;    ///< per track: RMS angle from the mean orientation
};

/// Poses of the tracks seen in every frame after settling, by track id.
using TrackPoses = std::map<std::uint32_t, std::vector<Eigen::Isometry3d>>;

void addJitter(const TrackPoses& tracks, int frames_needed, Jitter& jitter)
{
  for (const auto& [id, poses] : tracks)
  {
    if (static_cast<int>(poses.size()) < frames_needed) continue;
    Eigen::Vector3d mean_position = Eigen::Vector3d::Zero();
    for (const Eigen::Isometry3d& pose : poses) mean_position += pose.translation();
    mean_position /= static_cast<double>(poses.size());
    // The chordal mean of the rotations: the nearest rotation to their sum.
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    for (const Eigen::Isometry3d& pose : poses) sum += pose.linear();
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Eigen::Matrix3d reference = svd.matrixU() * svd.matrixV().transpose();
    if (reference.determinant() < 0.0)
    {
      Eigen::Matrix3d flip = Eigen::Matrix3d::Identity();
      flip(2, 2) = -1.0;
      reference = svd.matrixU() * flip * svd.matrixV().transpose();
    }
    double sum_sq_m = 0.0, sum_sq_rad = 0.0;
    for (const Eigen::Isometry3d& pose : poses)
    {
      sum_sq_m += (pose.translation() - mean_position).squaredNorm();
      sum_sq_rad += std::pow(Eigen::AngleAxisd(reference.transpose() * pose.linear()).angle(), 2);
    }
    jitter.translation_mm.push_back(1000.0 * std::sqrt(sum_sq_m / poses.size()));
    jitter.rotation_deg.push_back(std::sqrt(sum_sq_rad / poses.size()) * kRadToDeg);
  }
}

void printRow(const char* label, const Jitter& jitter)
{
  std::printf("| %s | %zu | %.3f | %.3f | %.4f | %.4f |\n", label, jitter.translation_mm.size(),
              percentile(jitter.translation_mm, 0.5), percentile(jitter.translation_mm, 0.95),
              percentile(jitter.rotation_deg, 0.5), percentile(jitter.rotation_deg, 0.95));
}

int run(const Options& options)
{
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  const ParamLookup defaults = mapParamLookup({});
  const FrontEnd front_end(catalogue, frontEndParamsFrom(defaults));
  const BrickPoseEstimator estimator(catalogue, estimatorParamsFrom(defaults));
  const char* kinds[] = {"single", "organised_pile", "unorganised_pile"};
  Jitter off, on;
  for (int s = 0; s < options.scenes; ++s)
  {
    const std::string kind = kinds[s % 3];
    const sim::RigConfig rig =
        sim::rigConfigFrom(mapParamLookup({{"scene", kind}, {"seed", std::to_string(1 + s / 3)}}));
    const sim::Scene scene = sim::SceneGenerator(rig.catalogue, rig.scene).generate(rig.seed);
    const sim::SyntheticRig renderer(rig.camera, rig.sensor);
    BrickTrackerParams smoothing_off, smoothing_on;
    smoothing_on.smoothing_weight = options.weight;
    BrickTracker tracker_off(smoothing_off), tracker_on(smoothing_on);
    TrackPoses poses_off, poses_on;
    for (int f = 0; f < options.frames; ++f)
    {
      const std::vector<TrackerObservation> observations =
          observe(front_end, estimator, renderer.render(scene, 1000 * rig.seed + f));
      const double stamp_s = f / 30.0;
      const std::vector<TrackedBrick> tracked_off = tracker_off.update(observations, stamp_s);
      const std::vector<TrackedBrick> tracked_on = tracker_on.update(observations, stamp_s);
      if (f < kSettleFrames) continue;
      for (const TrackedBrick& brick : tracked_off) poses_off[brick.id].push_back(brick.pose);
      for (const TrackedBrick& brick : tracked_on) poses_on[brick.id].push_back(brick.pose);
    }
    const int frames_needed = options.frames - kSettleFrames;
    addJitter(poses_off, frames_needed, off);
    addJitter(poses_on, frames_needed, on);
    std::printf("scene %d (%s, seed %llu): %zu tracks\n", s, kind.c_str(),
                static_cast<unsigned long long>(rig.seed), poses_off.size());
  }
  std::printf("\nStatic-brick jitter over frames %d-%d (RMS from each track's mean; median / p95 over tracks)\n\n",
              kSettleFrames, options.frames - 1);
  std::printf("| smoothing | tracks | translation mm median | p95 | rotation deg median | p95 |\n|---|---|---|---|---|---|\n");
  printRow("off (weight 1)", off);
  char label[48];
  std::snprintf(label, sizeof(label), "on (weight %.2g)", options.weight);
  printRow(label, on);
  std::printf("\n{\"frames\": %d, \"scenes\": %d, \"smoothing_weight\": %.3g, \"jitter_off_mm\": %.4f, "
              "\"jitter_on_mm\": %.4f, \"jitter_off_deg\": %.5f, \"jitter_on_deg\": %.5f}\n",
              options.frames, options.scenes, options.weight, percentile(off.translation_mm, 0.5),
              percentile(on.translation_mm, 0.5), percentile(off.rotation_deg, 0.5), percentile(on.rotation_deg, 0.5));
  return off.translation_mm.empty() ? 1 : 0;
}
}  // namespace
}  // namespace brick_pose

int main(int argc, char** argv)
{
  return brick_pose::run(brick_pose::parseOptions(argc, argv));
}
