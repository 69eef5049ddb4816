#pragma once
// bench_frontend's frames of its extra scene classes (touching rows, pallet
// layers), rendered and run colour-free as the benchmark runs them, for the
// tests that pin what a change found there.

#include <cstdint>
#include <string>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/eval/candidate_matching.h"
#include "brick_pose/eval/rig_truth.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/sim/d415_modes.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace test
{
/// A scene class as bench_frontend numbers it: frame j of the class with
/// index c (its place in the benchmark's class list) has the seed
/// 1000003 + 10^6 (c + 1) + j and is printed as frame first_frame + j.
struct BenchClass
{
  sim::SceneKind kind;
  int class_index;
  int first_frame;
};
constexpr BenchClass kTouchingRowsClass{sim::SceneKind::kTouchingRows, 3, 100};
constexpr BenchClass kPalletLayerClass{sim::SceneKind::kPalletLayer, 4, 125};
constexpr BenchClass kPalletStackClass{sim::SceneKind::kPalletStack, 5, 150};
constexpr BenchClass kTableBoxesClass{sim::SceneKind::kTableBoxes, 6, 175};

/// One bench frame run colour-free with the up direction and the ground
/// given (as the benchmark gives them).
struct BenchFrameRun
{
  sim::Scene scene;
  sim::SyntheticFrame rendered;
  Eigen::Vector3d up_in_camera;
  FrontEndResult result;
};

inline BenchFrameRun runBenchFrame(const BrickCatalogue& catalogue, const BenchClass& bench_class, int frame,
                                   const std::string& resolution)
{
  BenchFrameRun run;
  const int index = frame - bench_class.first_frame;
  const std::uint64_t seed =
      1000003ULL + 1000000ULL * static_cast<std::uint64_t>(bench_class.class_index + 1) + static_cast<std::uint64_t>(index);
  run.scene = sim::SceneGenerator(catalogue, sim::SceneParams::defaultsFor(bench_class.kind)).generate(seed);
  sim::SensorModel sensor = sim::SensorModel::d4xx();
  const sim::Lighting lightings[3] = {sim::Lighting::kNormal, sim::Lighting::kSunlight, sim::Lighting::kLowLight};
  sensor.lighting = lightings[index % 3];
  const PinholeCamera camera = sim::d415ColourMode(resolution);
  run.rendered = sim::SyntheticRig(camera, sensor).render(run.scene, seed);
  FrontEndParams params;
  params.mode = SegmentationMode::kColourFree;
  run.up_in_camera = run.scene.world_T_camera.linear().transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d& up = run.up_in_camera;
  params.roi.up_direction = up;
  params.roi.support_plane = Eigen::Vector4d(up.x(), up.y(), up.z(), run.scene.world_T_camera.translation().z());
  run.result = FrontEnd(catalogue, params)
                   .process(makeRgbdFrame(run.rendered.rgb, run.rendered.depth_mm, camera, FrameHeader{1, "camera"}));
  return run;
}

/// Whole tops in view and found, of a bench_frontend frame of boxes, with
/// no face found complete that is not.
struct WholeTops
{
  int whole = 0;
  int found = 0;
  int found_complete = 0;  ///< found and marked complete (pickable)
};

inline WholeTops boxesBenchFrame(const BenchClass& bench_class, int frame, const std::string& resolution)
{
  const BrickCatalogue boxes = BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/boxes.yaml");
  const BenchFrameRun run = runBenchFrame(boxes, bench_class, frame, resolution);
  const eval::FrameMatch match = eval::matchCandidates(
      run.result.candidates, eval::rigSceneTruth(run.rendered, run.up_in_camera), run.rendered.camera);
  WholeTops tops;
  for (const eval::TopMatch& top : match.tops)
  {
    tops.whole += top.whole_in_view ? 1 : 0;
    tops.found += top.whole_in_view && top.found ? 1 : 0;
    tops.found_complete += top.whole_in_view && top.found_complete ? 1 : 0;
  }
  for (const eval::CandidateMatch& candidate : match.candidates) EXPECT_FALSE(candidate.false_complete);
  return tops;
}

/// boxesBenchFrame of the pallet-layer class.
inline WholeTops palletLayerBenchFrame(int frame, const std::string& resolution)
{
  return boxesBenchFrame(kPalletLayerClass, frame, resolution);
}
}  // namespace test
}  // namespace brick_pose
