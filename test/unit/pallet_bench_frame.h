#pragma once
// bench_frontend's pallet-layer frames, rendered and run colour-free as the
// benchmark runs them, for the tests that pin what a change found there.

#include <cstdint>
#include <string>

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
/// Whole tops in view and found, of bench_frontend's pallet-layer frame
/// `frame` run colour-free as the benchmark runs it (seed, lighting, the
/// ground given as the support), with no face found complete that is not.
struct WholeTops
{
  int whole = 0;
  int found = 0;
};

inline WholeTops palletLayerBenchFrame(int frame, const std::string& resolution)
{
  const BrickCatalogue boxes = BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/boxes.yaml");
  const int index = frame - 125;
  const std::uint64_t seed = 1000003ULL + 5000000ULL + static_cast<std::uint64_t>(index);
  const sim::Scene scene =
      sim::SceneGenerator(boxes, sim::SceneParams::defaultsFor(sim::SceneKind::kPalletLayer)).generate(seed);
  sim::SensorModel sensor = sim::SensorModel::d4xx();
  const sim::Lighting lightings[3] = {sim::Lighting::kNormal, sim::Lighting::kSunlight, sim::Lighting::kLowLight};
  sensor.lighting = lightings[index % 3];
  const sim::SyntheticFrame synthetic = sim::SyntheticRig(sim::d415ColourMode(resolution), sensor).render(scene, seed);
  FrameHeader header;
  header.stamp_ns = 1;
  const RgbdFrame rgbd = makeRgbdFrame(synthetic.rgb, synthetic.depth_mm, synthetic.camera, header);
  FrontEndParams params;
  params.mode = SegmentationMode::kColourFree;
  const Eigen::Vector3d up = scene.world_T_camera.linear().transpose() * Eigen::Vector3d::UnitZ();
  params.roi.up_direction = up;
  params.roi.support_plane = Eigen::Vector4d(up.x(), up.y(), up.z(), scene.world_T_camera.translation().z());
  const FrontEndResult result = FrontEnd(boxes, params).process(rgbd);
  const eval::FrameMatch match = eval::matchCandidates(result.candidates, eval::rigSceneTruth(synthetic, up), synthetic.camera);
  WholeTops tops;
  for (const eval::TopMatch& top : match.tops)
  {
    tops.whole += top.whole_in_view ? 1 : 0;
    tops.found += top.whole_in_view && top.found ? 1 : 0;
  }
  for (const eval::CandidateMatch& candidate : match.candidates) EXPECT_FALSE(candidate.false_complete);
  return tops;
}
}  // namespace test
}  // namespace brick_pose
