// Scene kinds that model real piles (touching rows, pallet layers and stacks,
// boxes on a table) and the ground truth that judges "complete face" claims.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "brick_pose/common/errors.h"
#include "brick_pose/sim/box_layouts.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"
#include "brick_pose/sim/touching.h"

namespace brick_pose
{
namespace sim
{
namespace
{
/// Two plain box sizes like a pallet recording's, without the rig needing a file.
BrickCatalogue twoBoxCatalogue()
{
  BrickType large;
  large.name = "box_large";
  large.length_m = 0.40;
  large.width_m = 0.30;
  large.height_m = 0.25;
  BrickType small = large;
  small.name = "box_small";
  small.length_m = 0.30;
  small.width_m = 0.20;
  small.height_m = 0.15;
  return BrickCatalogue({large, small});
}

PinholeCamera vgaCamera()
{
  PinholeCamera camera;
  camera.width_px = 640;
  camera.height_px = 480;
  camera.fx_px = camera.fy_px = 613.3;
  camera.cx_px = 320.0;
  camera.cy_px = 240.0;
  return camera;
}

double lowestCornerZ(const PlacedBrick& brick)
{
  double lowest = 1e9;
  for (const Eigen::Vector3d& corner : cuboidCornersInBrick(brick.type))
    lowest = std::min(lowest, (brick.world_T_brick * corner).z());
  return lowest;
}

double highestCornerZ(const PlacedBrick& brick)
{
  double highest = -1e9;
  for (const Eigen::Vector3d& corner : cuboidCornersInBrick(brick.type))
    highest = std::max(highest, (brick.world_T_brick * corner).z());
  return highest;
}

/// Every brick rests on the ground or on the top of another brick.
void expectEveryBrickSupported(const Scene& scene, const std::string& what)
{
  for (const PlacedBrick& brick : scene.bricks)
  {
    const double bottom = lowestCornerZ(brick);
    bool supported = std::abs(bottom) < 1e-9;
    for (const PlacedBrick& other : scene.bricks)
      supported |= &other != &brick && std::abs(highestCornerZ(other) - bottom) < 1e-9;
    EXPECT_TRUE(supported) << what << ": a " << brick.type.name << " floats at " << bottom << " m";
  }
}

/// Probes half a millimetre inside each side face: inside another brick only
/// when the two interpenetrate.
void expectNoInterpenetration(const Scene& scene, const std::string& what)
{
  for (int count : touchingNeighbourCounts(scene, -0.0005))
    EXPECT_EQ(count, 0) << what << ": bricks overlap";
}

SceneGenerator generatorFor(SceneKind kind, const BrickCatalogue& catalogue = BrickCatalogue::mbzirc2020())
{
  return SceneGenerator(catalogue, SceneParams::defaultsFor(kind));
}
}  // namespace

TEST(SceneLayouts, TouchingRowsTouchWithSeamsOfAtMostThreeMillimetres)
{
  const SceneGenerator generator = generatorFor(SceneKind::kTouchingRows);
  int closed_seams_seen = 0;
  for (std::uint64_t seed = 0; seed < 30; ++seed)
  {
    const Scene scene = generator.generate(seed);
    const std::string what = "seed " + std::to_string(seed);
    ASSERT_GE(scene.bricks.size(), 2u) << what;
    std::set<std::string> types;
    for (const PlacedBrick& brick : scene.bricks)
      types.insert(brick.type.name);
    EXPECT_EQ(types.size(), 1u) << what << ": one type per pile";
    for (int count : touchingNeighbourCounts(scene, 0.0031))
      EXPECT_GE(count, 1) << what << ": every brick has a neighbour within 3 mm";
    for (int count : touchingNeighbourCounts(scene, 0.0002))
      closed_seams_seen += count;
    expectNoInterpenetration(scene, what);
    expectEveryBrickSupported(scene, what);
  }
  EXPECT_GT(closed_seams_seen, 0) << "some seams are closed (zero gap)";
}

TEST(SceneLayouts, PalletLayerPacksMixedSizesMostlyTouching)
{
  const SceneGenerator generator = generatorFor(SceneKind::kPalletLayer, twoBoxCatalogue());
  int boxes = 0, touching = 0, mixed_layers = 0;
  for (std::uint64_t seed = 0; seed < 20; ++seed)
  {
    const Scene scene = generator.generate(seed);
    const std::string what = "seed " + std::to_string(seed);
    std::set<std::string> types;
    for (const PlacedBrick& brick : scene.bricks)
    {
      types.insert(brick.type.name);
      EXPECT_NEAR(lowestCornerZ(brick), 0.0, 1e-9) << what << ": one layer on the ground";
      EXPECT_LT(brick.world_T_brick.translation().head<2>().norm(), 1.0) << what << ": on the pallet";
    }
    mixed_layers += types.size() > 1 ? 1 : 0;
    for (int count : touchingNeighbourCounts(scene))
    {
      ++boxes;
      touching += count > 0 ? 1 : 0;
    }
    expectNoInterpenetration(scene, what);
  }
  EXPECT_GT(boxes, 20 * 4) << "a 1.2 x 0.8 m pallet holds more than four of these boxes";
  EXPECT_GT(static_cast<double>(touching) / boxes, 0.8) << "most boxes touch a neighbour";
  EXPECT_GT(mixed_layers, 5) << "layers mix box sizes";
}

TEST(SceneLayouts, PalletStackLayersRestOnTheLayerBelow)
{
  const SceneGenerator generator = generatorFor(SceneKind::kPalletStack, twoBoxCatalogue());
  int stacked = 0;
  for (std::uint64_t seed = 0; seed < 15; ++seed)
  {
    const Scene scene = generator.generate(seed);
    const std::string what = "seed " + std::to_string(seed);
    for (const PlacedBrick& brick : scene.bricks)
      stacked += lowestCornerZ(brick) > 0.1 ? 1 : 0;
    expectEveryBrickSupported(scene, what);
    expectNoInterpenetration(scene, what);
  }
  EXPECT_GT(stacked, 15) << "upper layers exist";
}

TEST(SceneLayouts, TableBoxesStandUprightOnTheTable)
{
  const SceneGenerator generator = generatorFor(SceneKind::kTableBoxes, twoBoxCatalogue());
  int upright = 0, flat = 0;
  for (std::uint64_t seed = 0; seed < 30; ++seed)
  {
    const Scene scene = generator.generate(seed);
    const std::string what = "seed " + std::to_string(seed);
    for (const PlacedBrick& brick : scene.bricks)
    {
      const double up = brick.world_T_brick.linear()(2, 2);
      upright += std::abs(up) < 1e-9 ? 1 : 0;
      flat += std::abs(up - 1.0) < 1e-9 ? 1 : 0;
    }
    expectEveryBrickSupported(scene, what);
    expectNoInterpenetration(scene, what);
    // Seen obliquely: 30-70 degrees from the vertical.
    const double down = -scene.world_T_camera.linear().col(2).z();
    const double from_vertical_deg = std::acos(down) * 180.0 / M_PI;
    EXPECT_GE(from_vertical_deg, 30.0 - 1e-9) << what;
    EXPECT_LE(from_vertical_deg, 70.0 + 1e-9) << what;
  }
  EXPECT_GT(upright, flat) << "most table boxes stand on a side or an end";
  EXPECT_GT(flat, 0);
}

TEST(SceneLayouts, SameSeedSameLayout)
{
  for (SceneKind kind : {SceneKind::kTouchingRows, SceneKind::kPalletLayer, SceneKind::kPalletStack,
                         SceneKind::kTableBoxes})
  {
    const SceneGenerator generator = generatorFor(kind, twoBoxCatalogue());
    const Scene a = generator.generate(11), b = generator.generate(11);
    ASSERT_EQ(a.bricks.size(), b.bricks.size()) << toString(kind);
    for (std::size_t i = 0; i < a.bricks.size(); ++i)
      EXPECT_TRUE(a.bricks[i].world_T_brick.isApprox(b.bricks[i].world_T_brick, 0.0)) << toString(kind);
    EXPECT_TRUE(a.world_T_camera.isApprox(b.world_T_camera, 0.0));
    EXPECT_EQ(sceneKindFromString(toString(kind)), kind);
  }
}

TEST(SceneLayouts, ValidationNamesTheParameter)
{
  SceneParams params = SceneParams::defaultsFor(SceneKind::kPalletLayer);
  params.max_gap_m = -0.001;
  try
  {
    SceneGenerator generator(BrickCatalogue::mbzirc2020(), params);
    FAIL() << "negative gap accepted";
  }
  catch (const ConfigError& e)
  {
    EXPECT_NE(std::string(e.what()).find("max_gap_m"), std::string::npos) << e.what();
  }
  params = SceneParams::defaultsFor(SceneKind::kTableBoxes);
  params.upright_probability = 1.5;
  EXPECT_THROW(SceneGenerator(BrickCatalogue::mbzirc2020(), params), ConfigError);
}

// --- ground truth: is the top face complete in view? -----------------------

namespace
{
Scene boxSeenFromAbove(double distance_m, const Eigen::Vector2d& box_xy = Eigen::Vector2d::Zero())
{
  Scene scene;
  PlacedBrick box{twoBoxCatalogue().at("box_large"), Eigen::Isometry3d::Identity()};
  box.world_T_brick.translation() = Eigen::Vector3d(box_xy.x(), box_xy.y(), box.type.height_m);
  scene.bricks.push_back(box);
  scene.world_T_camera = lookAt(Eigen::Vector3d(0.0, 0.0, box.type.height_m), distance_m, 89.0, 0.0);
  return scene;
}

SyntheticFrame renderVga(const Scene& scene)
{
  return SyntheticRig(vgaCamera(), SensorModel()).render(scene, 1);
}
}  // namespace

TEST(TopFaceTruth, WholeFaceInViewIsComplete)
{
  const SyntheticFrame frame = renderVga(boxSeenFromAbove(1.2));
  const BrickTruth& truth = frame.truth[0];
  EXPECT_TRUE(truth.top_face_complete);
  EXPECT_FALSE(truth.top_face.cut_by_border);
  EXPECT_FALSE(truth.top_face.occluded);
  for (double fraction : truth.top_face.edge_visible_fraction)
    EXPECT_DOUBLE_EQ(fraction, 1.0);
  EXPECT_EQ(truth.top_face.up_face, CuboidFace::kTop);
  EXPECT_NEAR(truth.top_face.tilt_deg, 0.0, 1e-6);
}

TEST(TopFaceTruth, FaceCutByTheImageBorderIsNotComplete)
{
  // The box sits so far to the side that part of its top leaves the image,
  // while most of it stays in view.
  const SyntheticFrame frame = renderVga(boxSeenFromAbove(1.2, Eigen::Vector2d(0.0, 0.6)));
  const BrickTruth& truth = frame.truth[0];
  ASSERT_GT(truth.visible_top_pixels, 1000) << "the box is mostly in view";
  EXPECT_FALSE(truth.top_face_complete);
  EXPECT_TRUE(truth.top_face.cut_by_border);
  EXPECT_FALSE(truth.top_face.occluded);
  const auto& edges = truth.top_face.edge_visible_fraction;
  EXPECT_LT(*std::min_element(edges.begin(), edges.end()), 1.0);
}

TEST(TopFaceTruth, FaceUnderAnotherBoxIsNotComplete)
{
  Scene scene = boxSeenFromAbove(1.5);
  // A small box on one corner of the large one.
  PlacedBrick cover{twoBoxCatalogue().at("box_small"), Eigen::Isometry3d::Identity()};
  cover.world_T_brick.translation() = Eigen::Vector3d(0.15, 0.1, 0.25 + 0.15);
  scene.bricks.push_back(cover);
  const SyntheticFrame frame = renderVga(scene);
  EXPECT_FALSE(frame.truth[0].top_face_complete);
  EXPECT_TRUE(frame.truth[0].top_face.occluded);
  EXPECT_TRUE(frame.truth[1].top_face_complete) << "the box on top is whole";
}

TEST(TopFaceTruth, TouchingNeighboursOfOneHeightLeaveTopsComplete)
{
  Scene scene = boxSeenFromAbove(1.6);
  PlacedBrick neighbour = scene.bricks[0];
  neighbour.world_T_brick.translation().y() += neighbour.type.width_m;  // zero gap
  scene.bricks.push_back(neighbour);
  const SyntheticFrame frame = renderVga(scene);
  for (const BrickTruth& truth : frame.truth)
  {
    EXPECT_TRUE(truth.top_face_complete) << truth.instance_id;
    EXPECT_EQ(truth.touching_neighbours, 1);
  }
}

TEST(TopFaceTruth, TallerNeighbourSeenObliquelyHidesTheSharedEdge)
{
  Scene scene;
  const BrickCatalogue catalogue = twoBoxCatalogue();
  PlacedBrick low{catalogue.at("box_small"), Eigen::Isometry3d::Identity()};
  low.world_T_brick.translation() = Eigen::Vector3d(0.0, 0.0, low.type.height_m);
  PlacedBrick tall{catalogue.at("box_large"), Eigen::Isometry3d::Identity()};
  // Touching the low box's +y side, 10 cm taller.
  tall.world_T_brick.translation() = Eigen::Vector3d(0.0, 0.5 * (0.20 + 0.30), tall.type.height_m);
  scene.bricks = {low, tall};
  // Looking from the tall box's side (camera beyond +y), 45 deg down.
  scene.world_T_camera = lookAt(Eigen::Vector3d(0.0, 0.0, 0.2), 1.2, 45.0, 90.0);
  const SyntheticFrame frame = renderVga(scene);
  EXPECT_FALSE(frame.truth[0].top_face_complete);
  EXPECT_TRUE(frame.truth[0].top_face.occluded);
  EXPECT_TRUE(frame.truth[1].top_face_complete);
}

TEST(TopFaceTruth, TableViewsShowLargeSideFacesAndNoUprightTopIsComplete)
{
  SceneParams params = SceneParams::defaultsFor(SceneKind::kTableBoxes);
  params.upright_probability = 1.0;
  const SceneGenerator generator(twoBoxCatalogue(), params);
  const SyntheticRig rig(vgaCamera(), SensorModel());
  int large_vertical_tops = 0;
  for (std::uint64_t seed = 0; seed < 4; ++seed)
    for (const BrickTruth& truth : rig.render(generator.generate(seed), seed).truth)
    {
      EXPECT_NEAR(truth.top_face.tilt_deg, 90.0, 1e-6);
      EXPECT_FALSE(truth.top_face_complete) << "seed " << seed << " box " << truth.instance_id;
      large_vertical_tops += truth.visible_top_pixels > 2000 ? 1 : 0;
    }
  EXPECT_GT(large_vertical_tops, 0) << "the catalogue top faces, vertical, are in plain view";
}

TEST(TopFaceTruth, UprightBoxFacingTheCameraIsNotACompleteTop)
{
  Scene scene;
  PlacedBrick box{twoBoxCatalogue().at("box_large"), Eigen::Isometry3d::Identity()};
  // Standing on its long side with the catalogue top face toward the camera.
  box.world_T_brick.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  restBrickOn(box, 0.0);
  scene.bricks.push_back(box);
  const Eigen::Vector3d body = box.world_T_brick * Eigen::Vector3d(0.0, 0.0, -0.5 * box.type.height_m);
  scene.world_T_camera = lookAt(body, 1.0, 35.0, -90.0);
  const SyntheticFrame frame = renderVga(scene);
  const BrickTruth& truth = frame.truth[0];
  ASSERT_GT(truth.visible_top_pixels, 5000) << "the catalogue top face is in plain view";
  EXPECT_NEAR(truth.top_face.tilt_deg, 90.0, 1e-6);
  EXPECT_NE(truth.top_face.up_face, CuboidFace::kTop);
  EXPECT_FALSE(truth.top_face_complete) << "a vertical face is not a top";
}
}  // namespace sim
}  // namespace brick_pose
