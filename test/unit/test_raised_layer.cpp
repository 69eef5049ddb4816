// A colour-free plane is tiled into bricks only when it is a raised layer:
// judged by its quad's sides, or, where the quad is no rectangle around it,
// by what lies around its outline.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "brick_pose/eval/candidate_matching.h"
#include "brick_pose/eval/rig_truth.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/roi/raised_layer.h"
#include "brick_pose/segmentation/segment.h"
#include "brick_pose/sim/d415_modes.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"
#include "touching_plates_scene.h"

namespace brick_pose
{
namespace
{
/// Three red plates in an L, 25 cm in front of the background, at VGA.
test::TouchingPlatesScene lOfPlates()
{
  test::TouchingPlatesScene scene;
  scene.camera = sim::d415ColourMode("640x480");
  scene.rotation = test::TouchingPlatesScene::facingCamera(0.3, 0.2);
  scene.plates = {{{-0.3, 0.0}, {0.0, 0.2}}, {{0.0, 0.0}, {0.3, 0.2}}, {{-0.3, -0.3}, {-0.1, 0.0}}};
  return scene;
}

/// The pixels whose depth lies nearer (`nearer`) or farther than `split_z_m`.
Segment segmentByDepth(const RgbdFrame& frame, double split_z_m, bool nearer)
{
  cv::Mat mask = cv::Mat::zeros(frame.height_px(), frame.width_px(), CV_8UC1);
  for (int v = 0; v < frame.height_px(); ++v)
    for (int u = 0; u < frame.width_px(); ++u)
    {
      const float z = frame.depthAt(u, v);
      if (z > 0.0f && (z < split_z_m) == nearer) mask.at<std::uint8_t>(v, u) = 255;
    }
  return segmentFromMask(mask, cv::Rect(0, 0, frame.width_px(), frame.height_px()), frame.depth_m, "");
}

/// The plane through `origin_m` with unit normal `normal`, turned toward the camera.
PlaneFit planeThrough(const Eigen::Vector3d& origin_m, Eigen::Vector3d normal)
{
  PlaneFit plane;
  plane.centroid_m = origin_m;
  plane.normal = normal.dot(origin_m) < 0.0 ? normal : -normal;
  plane.valid = true;
  return plane;
}
/// The ring 4-12 px out, with a 1 cm step (what RoiFilter reads at VGA).
OutlineSurroundings ringAround(const RgbdFrame& frame, const Segment& segment, const PlaneFit& plane,
                               int inner_px = 4, int outer_px = 12)
{
  return measureOutlineSurroundings(frame, segment, plane, 0.01, inner_px, outer_px);
}
}  // namespace

TEST(RaisedLayer, AroundALayerOfPlatesTheSurfaceFallsAway)
{
  const test::TouchingPlatesScene scene = lOfPlates();
  const RgbdFrame frame = scene.frame();
  const Segment layer = segmentByDepth(frame, scene.origin_m.z() + 0.1, true);
  ASSERT_GT(layer.area_px, 1000);
  const OutlineSurroundings around = ringAround(frame, layer, planeThrough(scene.origin_m, scene.rotation.col(2)));
  EXPECT_GT(around.below, 500);
  EXPECT_EQ(around.above, 0);
  EXPECT_TRUE(around.fallsAway());
}

TEST(RaisedLayer, AroundTheFloorUnderALayerObjectsStandOnIt)
{
  const test::TouchingPlatesScene scene = lOfPlates();
  const RgbdFrame frame = scene.frame();
  // The background plane, and the hole the plates leave in it.
  const Segment floor = segmentByDepth(frame, scene.origin_m.z() + 0.1, false);
  ASSERT_GT(floor.area_px, 1000);
  const PlaneFit floor_plane =
      planeThrough(Eigen::Vector3d(0.0, 0.0, scene.origin_m.z() + scene.background_offset_m), Eigen::Vector3d::UnitZ());
  const OutlineSurroundings around = ringAround(frame, floor, floor_plane);
  EXPECT_GT(around.above, 500);
  EXPECT_EQ(around.below, 0);
  EXPECT_FALSE(around.fallsAway());
}

TEST(RaisedLayer, NothingToReadIsNoLayer)
{
  const test::TouchingPlatesScene scene = lOfPlates();
  const RgbdFrame frame = scene.frame();
  const PlaneFit plane = planeThrough(scene.origin_m, scene.rotation.col(2));
  EXPECT_FALSE(ringAround(frame, Segment(), plane).fallsAway());
  const Segment layer = segmentByDepth(frame, scene.origin_m.z() + 0.1, true);
  EXPECT_FALSE(ringAround(frame, layer, PlaneFit()).fallsAway()) << "no plane";
  EXPECT_FALSE(ringAround(frame, layer, plane, 12, 4).fallsAway()) << "an empty ring";
}

// bench_frontend's pallet-layer frame 149 (normal light, colour-free, VGA):
// seven boxes touching in a U, the pallet seen in its notch. The sides of
// the U's least-area quad run across the notch and past the layer's ends,
// not along its outline, and did not read as three real edges, so the
// layer was never tiled: 0 of its 7 whole tops were found. Its outline
// stands up from the pallet all round.
TEST(RaisedLayer, ALayerOfBoxesInNoRectangleIsTiledIntoWholeBoxes)
{
  const BrickCatalogue boxes = BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/boxes.yaml");
  const std::uint64_t seed = 1000003ULL + 5000000ULL + 24;
  const sim::Scene scene =
      sim::SceneGenerator(boxes, sim::SceneParams::defaultsFor(sim::SceneKind::kPalletLayer)).generate(seed);
  const sim::SyntheticFrame synthetic =
      sim::SyntheticRig(sim::d415ColourMode("640x480"), sim::SensorModel::d4xx()).render(scene, seed);
  FrameHeader header;
  header.stamp_ns = 1;
  const RgbdFrame frame = makeRgbdFrame(synthetic.rgb, synthetic.depth_mm, synthetic.camera, header);
  FrontEndParams params;
  params.mode = SegmentationMode::kColourFree;
  params.roi.up_direction = scene.world_T_camera.linear().transpose() * Eigen::Vector3d::UnitZ();
  const FrontEndResult result = FrontEnd(boxes, params).process(frame);
  const eval::FrameMatch match =
      eval::matchCandidates(result.candidates, eval::rigSceneTruth(synthetic, params.roi.up_direction), synthetic.camera);
  int whole = 0, found = 0;
  for (const eval::TopMatch& top : match.tops)
  {
    whole += top.whole_in_view ? 1 : 0;
    found += top.whole_in_view && top.found ? 1 : 0;
  }
  for (const eval::CandidateMatch& candidate : match.candidates) EXPECT_FALSE(candidate.false_complete);
  ASSERT_GE(whole, 6) << "the frame's layout";
  EXPECT_GE(2 * found, whole) << found << " of " << whole << " whole tops found";
}
}  // namespace brick_pose
