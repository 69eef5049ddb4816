// Unit tests of the brick selection policies on hand-made layouts.
//
// Layouts are written in a world frame (z up, ground z = 0) and seen by a
// camera above them looking down at an angle, as on the robot; the tests give
// the selection what the node would: poses in the camera optical frame.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "brick_pose/common/errors.h"
#include "brick_pose/pose/brick_selection.h"

namespace brick_pose
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kRadPerDeg = kPi / 180.0;
constexpr double kBrickHeightM = 0.20;
constexpr double kBrickWidthM = 0.20;

Eigen::Matrix3d rotX(double deg) { return Eigen::AngleAxisd(deg * kRadPerDeg, Eigen::Vector3d::UnitX()).toRotationMatrix(); }
Eigen::Matrix3d rotY(double deg) { return Eigen::AngleAxisd(deg * kRadPerDeg, Eigen::Vector3d::UnitY()).toRotationMatrix(); }
Eigen::Matrix3d rotZ(double deg) { return Eigen::AngleAxisd(deg * kRadPerDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

/// Camera 1.3 m above the ground, 0.9 m back along -y, looking down at the
/// origin 35 degrees off the vertical (optical z forward, y down in image).
Eigen::Isometry3d worldFromCamera()
{
  Eigen::Isometry3d world_T_camera = Eigen::Isometry3d::Identity();
  // Straight down: optical z = -world z, optical x = world x, optical y = -world y.
  world_T_camera.linear() = rotX(35.0) * rotX(180.0);
  world_T_camera.translation() = Eigen::Vector3d(0.0, -0.9, 1.3);
  return world_T_camera;
}

/// World up expressed in the camera frame (what tf gives the node).
Eigen::Vector3d worldUpInCamera()
{
  return worldFromCamera().linear().transpose() * Eigen::Vector3d::UnitZ();
}

/// A brick whose top-face centre is at `top_centre_world`, turned by
/// `yaw_deg` about the vertical and then by `world_tilt` (identity = level).
DetectedBrick brickAt(const std::string& type, double length_m, const Eigen::Vector3d& top_centre_world,
                      double yaw_deg, double fitness = 0.5, const Eigen::Matrix3d& world_tilt = Eigen::Matrix3d::Identity())
{
  Eigen::Isometry3d world_T_brick = Eigen::Isometry3d::Identity();
  world_T_brick.linear() = world_tilt * rotZ(yaw_deg);
  world_T_brick.translation() = top_centre_world;
  DetectedBrick brick;
  brick.type_name = type;
  brick.T_cam_brick = worldFromCamera().inverse() * world_T_brick;
  brick.dimensions_m = Eigen::Vector3d(length_m, kBrickWidthM, kBrickHeightM);
  brick.fitness = fitness;
  brick.complete_face = true;
  return brick;
}

/// Layer `layer` (0 = on the ground) of a pile: the top face at its height.
double topOfLayerM(int layer) { return kBrickHeightM * (layer + 1); }

/// A red brick resting on a green one (slightly shifted and turned, as a
/// dropped brick would be).
std::vector<DetectedBrick> stackOfTwo()
{
  return {brickAt("green", 0.60, {0.0, 0.0, topOfLayerM(0)}, 0.0),
          brickAt("red", 0.30, {0.05, 0.03, topOfLayerM(1)}, 20.0)};
}

TEST(SelectionPolicyTest, ParsesEveryNameAndRoundTrips)
{
  EXPECT_EQ(parseSelectionPolicy("nearest"), SelectionPolicy::kNearest);
  EXPECT_EQ(parseSelectionPolicy("highest"), SelectionPolicy::kHighest);
  EXPECT_EQ(parseSelectionPolicy("most_confident"), SelectionPolicy::kMostConfident);
  EXPECT_EQ(parseSelectionPolicy("pickable"), SelectionPolicy::kPickable);
  EXPECT_EQ(parseSelectionPolicy(""), SelectionPolicy::kNearest);
  for (const SelectionPolicy policy : {SelectionPolicy::kNearest, SelectionPolicy::kHighest,
                                       SelectionPolicy::kMostConfident, SelectionPolicy::kPickable})
    EXPECT_EQ(parseSelectionPolicy(toString(policy)), policy);
}

TEST(SelectionPolicyTest, UnknownNameIsConfigErrorListingTheValidNames)
{
  try
  {
    parseSelectionPolicy("tallest");
    FAIL() << "expected ConfigError";
  }
  catch (const ConfigError& error)
  {
    const std::string message = error.what();
    EXPECT_NE(message.find("'tallest'"), std::string::npos) << message;
    for (const char* name : {"nearest", "highest", "most_confident", "pickable"})
      EXPECT_NE(message.find(name), std::string::npos) << message;
  }
  EXPECT_THROW(parseSelectionPolicy("Nearest"), ConfigError);  // names are case-sensitive
}

TEST(BrickSelectionTest, EmptyListSelectsNothing)
{
  const std::vector<DetectedBrick> none;
  for (const SelectionPolicy policy : {SelectionPolicy::kNearest, SelectionPolicy::kHighest,
                                       SelectionPolicy::kMostConfident, SelectionPolicy::kPickable})
  {
    EXPECT_FALSE(selectBrick(none, policy).has_value()) << toString(policy);
    EXPECT_TRUE(orderBricks(none, policy).empty()) << toString(policy);
  }
  EXPECT_TRUE(pickableMask(none).empty());
}

TEST(BrickSelectionTest, BottomOfAStackIsCoveredAndTheTopIsPickable)
{
  const std::vector<DetectedBrick> bricks = stackOfTwo();
  const Eigen::Vector3d up = worldUpInCamera();
  EXPECT_TRUE(isCovered(bricks, 0, up));
  EXPECT_FALSE(isCovered(bricks, 1, up));
  EXPECT_EQ(pickableMask(bricks, up), (std::vector<bool>{false, true}));
  EXPECT_EQ(pickableMask(bricks), (std::vector<bool>{false, true}));  // up estimated from the plates
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kPickable, "", up), std::optional<std::size_t>(1));
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kHighest, "", up), std::optional<std::size_t>(1));
}

TEST(BrickSelectionTest, BricksEdgeToEdgeDoNotCoverEachOther)
{
  // Two bricks touching along their long edges, one on a second layer next
  // to (not over) a ground brick: nothing rests on anything.
  const std::vector<DetectedBrick> bricks = {
      brickAt("red", 0.30, {0.0, 0.0, topOfLayerM(0)}, 0.0),
      brickAt("red", 0.30, {0.0, kBrickWidthM, topOfLayerM(0)}, 0.0),
      brickAt("blue", 1.20, {0.0, -kBrickWidthM, topOfLayerM(1)}, 0.0),
  };
  EXPECT_EQ(pickableMask(bricks, worldUpInCamera()), (std::vector<bool>{true, true, true}));
}

TEST(BrickSelectionTest, SlightlyHigherOverlappingBrickDoesNotCover)
{
  // Footprints overlap but the second top is only a quarter height higher:
  // a tilted neighbour, not a brick resting on the first one.
  const std::vector<DetectedBrick> bricks = {
      brickAt("red", 0.30, {0.0, 0.0, topOfLayerM(0)}, 0.0),
      brickAt("red", 0.30, {0.1, 0.05, topOfLayerM(0) + 0.25 * kBrickHeightM}, 30.0),
  };
  EXPECT_EQ(pickableMask(bricks, worldUpInCamera()), (std::vector<bool>{true, true}));
}

TEST(BrickSelectionTest, EachPolicyPicksItsOwnBrick)
{
  // The stack is far from the camera; a blue brick lies on the ground almost
  // under the camera, and the green (covered) brick has the best fitness.
  std::vector<DetectedBrick> bricks = stackOfTwo();
  bricks[0].fitness = 0.95;
  bricks[1].fitness = 0.80;
  bricks.push_back(brickAt("blue", 1.20, {0.0, -0.85, topOfLayerM(0)}, 90.0, 0.60));
  const Eigen::Vector3d up = worldUpInCamera();
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kNearest, "", up), std::optional<std::size_t>(2));
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kHighest, "", up), std::optional<std::size_t>(1));
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kMostConfident, "", up), std::optional<std::size_t>(0));
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kPickable, "", up), std::optional<std::size_t>(1));
}

TEST(BrickSelectionTest, TypeFilterRestrictsTheChoiceButNotTheCovering)
{
  std::vector<DetectedBrick> bricks = stackOfTwo();
  bricks.push_back(brickAt("green", 0.60, {0.9, 0.0, topOfLayerM(0)}, 0.0));
  const Eigen::Vector3d up = worldUpInCamera();
  // The two green bricks are equally high; "pickable" must take the free one.
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kPickable, "green", up), std::optional<std::size_t>(2));
  EXPECT_EQ(orderBricks(bricks, SelectionPolicy::kPickable, "green", up), (std::vector<std::size_t>{2, 0}));
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kHighest, "red", up), std::optional<std::size_t>(1));
  EXPECT_FALSE(selectBrick(bricks, SelectionPolicy::kNearest, "orange", up).has_value());

  // With only the covered green brick left there is nothing pickable of that
  // type, although "highest" still names it.
  bricks.pop_back();
  EXPECT_FALSE(selectBrick(bricks, SelectionPolicy::kPickable, "green", up).has_value());
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kHighest, "green", up), std::optional<std::size_t>(0));
}

TEST(BrickSelectionTest, OrderBricksRanksEveryBrickBestFirst)
{
  const std::vector<DetectedBrick> bricks = {
      brickAt("red", 0.30, {0.0, 0.3, topOfLayerM(0)}, 0.0, 0.2),
      brickAt("red", 0.30, {0.0, 0.0, topOfLayerM(2)}, 0.0, 0.9),
      brickAt("red", 0.30, {0.0, -0.3, topOfLayerM(1)}, 0.0, 0.5),
  };
  const Eigen::Vector3d up = worldUpInCamera();
  EXPECT_EQ(orderBricks(bricks, SelectionPolicy::kHighest, "", up), (std::vector<std::size_t>{1, 2, 0}));
  EXPECT_EQ(orderBricks(bricks, SelectionPolicy::kMostConfident, "", up), (std::vector<std::size_t>{1, 2, 0}));
  // Distances from the camera: 1.63 m, 1.14 m, 1.08 m.
  EXPECT_EQ(orderBricks(bricks, SelectionPolicy::kNearest, "", up), (std::vector<std::size_t>{2, 1, 0}));
}

TEST(BrickSelectionTest, EstimatedUpIsTheMeanPlateNormal)
{
  // Level bricks with small random-looking tilts: the estimate is close to
  // the true vertical.
  const std::vector<DetectedBrick> bricks = {
      brickAt("red", 0.30, {0.0, 0.0, topOfLayerM(0)}, 10.0, 0.5, rotX(4.0)),
      brickAt("red", 0.30, {0.5, 0.0, topOfLayerM(0)}, 50.0, 0.5, rotY(-5.0)),
      brickAt("red", 0.30, {0.0, 0.5, topOfLayerM(0)}, 80.0, 0.5, rotX(-3.0) * rotY(2.0)),
  };
  const Eigen::Vector3d estimated = resolveUpInCamera(bricks);
  EXPECT_NEAR(estimated.norm(), 1.0, 1e-12);
  EXPECT_LT(std::acos(std::min(1.0, estimated.dot(worldUpInCamera()))) / kRadPerDeg, 3.0);
  // An explicit vector is only normalised.
  const Eigen::Vector3d given = resolveUpInCamera(bricks, Eigen::Vector3d(0.0, -2.0, 0.0));
  EXPECT_TRUE(given.isApprox(Eigen::Vector3d(0.0, -1.0, 0.0)));
}

TEST(BrickSelectionTest, ExplicitUpDecidesWhenBricksLieOnASlope)
{
  // Two bricks side by side on a 40-degree slope rising along +y, the second
  // one further up the slope but sunk 1 cm into it. Measured along their own
  // plate normals (the estimated up) the first is higher; along the robot's
  // up the second is higher by about 19 cm.
  const Eigen::Matrix3d slope = rotX(40.0);
  const Eigen::Vector3d down_slope_top = Eigen::Vector3d(0.0, 0.0, topOfLayerM(0));
  const Eigen::Vector3d up_slope_top = down_slope_top + slope * Eigen::Vector3d(0.0, 0.3, -0.01);
  const std::vector<DetectedBrick> bricks = {
      brickAt("red", 0.30, down_slope_top, 0.0, 0.5, slope),
      brickAt("red", 0.30, up_slope_top, 0.0, 0.5, slope),
  };
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kHighest, "", worldUpInCamera()), std::optional<std::size_t>(1));
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kHighest), std::optional<std::size_t>(0));
}

TEST(BrickSelectionTest, UnusableUpVectorIsInputError)
{
  const std::vector<DetectedBrick> bricks = stackOfTwo();
  EXPECT_THROW(selectBrick(bricks, SelectionPolicy::kHighest, "", Eigen::Vector3d::Zero()), InputError);
  EXPECT_THROW(pickableMask(bricks, Eigen::Vector3d(std::nan(""), 0.0, 1.0)), InputError);
  // Policies that do not use up ignore it.
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kMostConfident, "", Eigen::Vector3d::Zero()),
            std::optional<std::size_t>(0));
}
}  // namespace

TEST(BrickSelection, APartialFaceIsNeverChosenButStillCoversOthers)
{
  const Eigen::Vector3d up = worldUpInCamera();
  // A partly hidden green brick lies across a complete red one.
  std::vector<DetectedBrick> bricks = {brickAt("red", 0.30, Eigen::Vector3d(0.0, 0.0, 0.20), 0.0),
                                       brickAt("green", 0.60, Eigen::Vector3d(0.0, 0.0, 0.40), 90.0)};
  bricks[1].complete_face = false;
  EXPECT_FALSE(selectBrick(bricks, SelectionPolicy::kPickable, "", up).has_value())
      << "the red brick is covered and the green one only partly measured";
  EXPECT_EQ(selectBrick(bricks, SelectionPolicy::kHighest, "", up), std::optional<std::size_t>(0));
  try
  {
    chooseBrick(bricks, SelectionPolicy::kPickable, "", up);
    FAIL() << "chooseBrick must throw";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("that nothing rests on"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1 green partial, 1 red complete"), std::string::npos) << e.what();
  }
}

TEST(BrickSelection, FindsABrickByItsId)
{
  std::vector<DetectedBrick> bricks = {brickAt("red", 0.30, Eigen::Vector3d(0.0, 0.0, 0.20), 0.0),
                                       brickAt("red", 0.30, Eigen::Vector3d(0.5, 0.0, 0.20), 0.0)};
  bricks[0].id = 7;
  bricks[1].id = 3;
  EXPECT_EQ(findBrickById(bricks, 3), 1u);
  try
  {
    findBrickById(bricks, 5);
    FAIL() << "findBrickById must throw";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("ids: 7, 3"), std::string::npos) << e.what();
  }
}
}  // namespace brick_pose
