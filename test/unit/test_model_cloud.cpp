#include <gtest/gtest.h>

#include <cmath>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/registration/brick_symmetry.h"
#include "brick_pose/registration/model_cloud.h"

namespace brick_pose
{
namespace registration
{
namespace
{
BrickType redBrick() { return BrickCatalogue::mbzirc2020().at("red"); }

Eigen::Isometry3d pose(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation)
{
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.linear() = rotation;
  result.translation() = translation;
  return result;
}

Eigen::Matrix3d rotationAbout(const Eigen::Vector3d& axis, double angle_deg)
{
  return Eigen::AngleAxisd(angle_deg * M_PI / 180.0, axis.normalized()).toRotationMatrix();
}
}  // namespace

TEST(BrickModelCloud, TopFaceSpansTheFaceWithUpwardNormals)
{
  const BrickType brick = redBrick();
  ModelCloudParams options;
  options.spacing_m = 0.01;
  const PointSet cloud = buildBrickModelCloud(brick, options);
  ASSERT_EQ(cloud.size(), 31u * 21u);  // 0.30 / 0.01 + 1 by 0.20 / 0.01 + 1
  ASSERT_EQ(cloud.normals.size(), cloud.size());
  Eigen::Vector3d lower = cloud.points.front();
  Eigen::Vector3d upper = lower;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < cloud.size(); ++i)
  {
    lower = lower.cwiseMin(cloud.points[i]);
    upper = upper.cwiseMax(cloud.points[i]);
    sum += cloud.points[i];
    EXPECT_TRUE(cloud.normals[i].isApprox(Eigen::Vector3d::UnitZ()));
  }
  EXPECT_TRUE(lower.isApprox(Eigen::Vector3d(-0.15, -0.10, 0.0), 1e-12));
  EXPECT_TRUE(upper.isApprox(Eigen::Vector3d(0.15, 0.10, 0.0), 1e-12));
  EXPECT_LT((sum / cloud.size()).norm(), 1e-12);  // origin at the face centre
}

TEST(BrickModelCloud, SideFacesHangBelowTheTopWithOutwardNormals)
{
  const BrickType brick = redBrick();
  ModelCloudParams options;
  options.spacing_m = 0.02;
  options.sides = {BrickSide::kPlusX, BrickSide::kMinusY};
  const PointSet cloud = buildBrickModelCloud(brick, options);
  int on_plus_x = 0;
  int on_minus_y = 0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
  {
    const Eigen::Vector3d& p = cloud.points[i];
    EXPECT_LE(p.z(), 1e-12);
    EXPECT_GE(p.z(), -brick.height_m - 1e-12);
    if (cloud.normals[i].isApprox(Eigen::Vector3d::UnitX()))
    {
      ++on_plus_x;
      EXPECT_NEAR(p.x(), 0.5 * brick.length_m, 1e-12);
    }
    if (cloud.normals[i].isApprox(-Eigen::Vector3d::UnitY()))
    {
      ++on_minus_y;
      EXPECT_NEAR(p.y(), -0.5 * brick.width_m, 1e-12);
    }
  }
  EXPECT_GT(on_plus_x, 0);
  EXPECT_GT(on_minus_y, 0);
}

TEST(BrickModelCloud, RejectsBadSpacing)
{
  ModelCloudParams options;
  options.spacing_m = 0.0;
  EXPECT_THROW(buildBrickModelCloud(redBrick(), options), ConfigError);
}

TEST(BrickModelCloud, VisibleSidesFaceTheCamera)
{
  const BrickType brick = redBrick();
  // Camera 1 m above the brick and 0.5 m off towards +x, -y in the brick frame.
  const Eigen::Vector3d camera_in_brick(0.5, -0.5, 1.0);
  Eigen::Isometry3d camera_from_brick = Eigen::Isometry3d::Identity();
  camera_from_brick.translation() = -camera_in_brick;
  const std::vector<BrickSide> sides = visibleSides(brick, camera_from_brick);
  ASSERT_EQ(sides.size(), 2u);
  EXPECT_EQ(sides[0], BrickSide::kPlusX);
  EXPECT_EQ(sides[1], BrickSide::kMinusY);
}

TEST(BrickSymmetry, HalfTurnAboutTheNormalIsNoError)
{
  const Eigen::Isometry3d truth = pose(rotationAbout({0.3, -0.2, 1.0}, 140.0), {0.1, -0.2, 1.3});
  const Eigen::Isometry3d turned = pose(truth.linear() * rotationAbout(Eigen::Vector3d::UnitZ(), 180.0),
                                        truth.translation() + Eigen::Vector3d(0.003, 0.0, -0.004));
  const PoseError error = poseErrorModuloSymmetry(turned, truth, ModelSymmetry::kHalfTurnZ);
  EXPECT_NEAR(error.rotation_deg, 0.0, 1e-6);
  EXPECT_NEAR(error.translation_mm(), 5.0, 1e-9);
  // Without the symmetry the same estimate is half a turn off.
  EXPECT_NEAR(poseErrorModuloSymmetry(turned, truth, ModelSymmetry::kNone).rotation_deg, 180.0, 1e-6);
}

TEST(BrickSymmetry, NormalFlipCountsOnlyForTheBareRectangle)
{
  const Eigen::Isometry3d truth = pose(rotationAbout({1.0, 0.4, 0.2}, 35.0), {0.0, 0.1, 0.8});
  const Eigen::Isometry3d flipped = pose(truth.linear() * rotationAbout(Eigen::Vector3d::UnitX(), 180.0),
                                         truth.translation());
  EXPECT_NEAR(poseErrorModuloSymmetry(flipped, truth, ModelSymmetry::kRectangle).rotation_deg, 0.0, 1e-6);
  EXPECT_NEAR(poseErrorModuloSymmetry(flipped, truth, ModelSymmetry::kHalfTurnZ).rotation_deg, 180.0, 1e-6);
}

TEST(BrickSymmetry, SmallErrorIsMeasuredAsIs)
{
  const Eigen::Isometry3d truth = pose(rotationAbout({0.0, 1.0, 0.3}, 200.0), {0.2, 0.0, 1.0});
  const Eigen::Isometry3d estimate =
      pose(truth.linear() * rotationAbout({1.0, 1.0, 0.0}, 3.0), truth.translation() + Eigen::Vector3d(0, 0.002, 0));
  const PoseError error = poseErrorModuloSymmetry(estimate, truth, ModelSymmetry::kRectangle);
  EXPECT_NEAR(error.rotation_deg, 3.0, 1e-6);
  EXPECT_NEAR(error.translation_m, 0.002, 1e-12);
}

TEST(BrickSymmetry, CanonicalPoseFacesTheCameraWithPositiveX)
{
  // A face seen from the camera: brick z towards the camera (camera z < 0).
  const Eigen::Isometry3d truth = pose(rotationAbout({1.0, 0.0, 0.0}, 160.0) * rotationAbout({0, 0, 1}, 30.0),
                                       {0.1, 0.05, 1.2});
  for (const Eigen::Matrix3d& symmetry : symmetryRotations(ModelSymmetry::kRectangle))
  {
    const Eigen::Isometry3d equivalent = pose(truth.linear() * symmetry, truth.translation());
    const Eigen::Isometry3d canonical = canonicalisePose(equivalent, ModelSymmetry::kRectangle);
    EXPECT_LT(canonical.linear()(2, 2), 0.0);  // brick z points towards the camera
    EXPECT_GE(canonical.linear()(0, 0), 0.0);  // brick x has a non-negative camera x
    EXPECT_TRUE(canonical.translation().isApprox(truth.translation()));
    // All members of the group land on the same representative.
    EXPECT_TRUE(canonical.linear().isApprox(canonicalisePose(truth, ModelSymmetry::kRectangle).linear(), 1e-12));
    EXPECT_NEAR(poseErrorModuloSymmetry(canonical, truth, ModelSymmetry::kRectangle).rotation_deg, 0.0, 1e-6);
  }
}

TEST(BrickSymmetry, CanonicalPoseBreaksTheXTieWithY)
{
  // Brick x along camera +y or -y (camera x component zero).
  const Eigen::Isometry3d along_minus_y =
      pose(rotationAbout({1, 0, 0}, 180.0) * rotationAbout({0, 0, 1}, 90.0), {0.0, 0.0, 1.0});
  const Eigen::Isometry3d canonical = canonicalisePose(along_minus_y, ModelSymmetry::kHalfTurnZ);
  EXPECT_NEAR(canonical.linear()(0, 0), 0.0, 1e-12);
  EXPECT_GT(canonical.linear()(1, 0), 0.0);
}
}  // namespace registration
}  // namespace brick_pose
