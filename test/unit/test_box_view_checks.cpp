#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Geometry>

#include "brick_pose/common/errors.h"
#include "brick_pose/registration/box_view_checks.h"

namespace
{
using namespace brick_pose::registration;

// A 0.4 x 0.3 x 0.2 m box centred at the origin, seen from 1 m above its
// 0.4 x 0.3 top face: the scan is that face, with its normals.
ModelBox cardboardBox()
{
  ModelBox box;
  box.half_extents_m = Eigen::Vector3d(0.2, 0.15, 0.1);
  return box;
}

PointSet topFaceScan()
{
  PointSet scan;
  for (double x = -0.2; x <= 0.2 + 1e-9; x += 0.01)
    for (double y = -0.15; y <= 0.15 + 1e-9; y += 0.01)
    {
      scan.points.emplace_back(x, y, 0.1);
      scan.normals.emplace_back(0.0, 0.0, 1.0);
    }
  return scan;
}

std::vector<int> all(const PointSet& scan)
{
  std::vector<int> indices;
  for (std::size_t i = 0; i < scan.size(); ++i)
    indices.push_back(static_cast<int>(i));
  return indices;
}

BoxViewCheckParams fromAbove()
{
  BoxViewCheckParams params;
  params.viewpoint_m = Eigen::Vector3d(0.0, 0.0, 1.0);
  return params;
}
}  // namespace

TEST(BoxViewChecks, TheRightPosePasses)
{
  const PointSet scan = topFaceScan();
  const BoxViewCheck check = checkBoxView(Eigen::Isometry3d::Identity(), cardboardBox(), scan, all(scan), fromAbove());
  EXPECT_TRUE(check.doubts.empty()) << check.doubts.front();
  EXPECT_LT(check.max_face_tilt_deg, 0.1);
  EXPECT_GT(check.min_span_ratio, 0.9);
}

// A quarter turn puts the box's 0.4 m edge where the scan spans 0.3 m: the
// points are all covered, but the face is too short.
TEST(BoxViewChecks, AQuarterTurnOfARectangularFaceIsTooShort)
{
  const PointSet scan = topFaceScan();
  Eigen::Isometry3d turned = Eigen::Isometry3d::Identity();
  turned.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const BoxViewCheck check = checkBoxView(turned, cardboardBox(), scan, all(scan), fromAbove());
  ASSERT_EQ(check.doubts.size(), 1u);
  EXPECT_NE(check.doubts.front().find("spans only"), std::string::npos) << check.doubts.front();
  EXPECT_NEAR(check.min_span_ratio, 0.75, 0.03);
}

TEST(BoxViewChecks, AFaceTiltedAgainstThePoseIsNotTrusted)
{
  const PointSet scan = topFaceScan();
  Eigen::Isometry3d tilted = Eigen::Isometry3d::Identity();
  tilted.linear() = Eigen::AngleAxisd(6.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const BoxViewCheck check = checkBoxView(tilted, cardboardBox(), scan, all(scan), fromAbove());
  EXPECT_NEAR(check.max_face_tilt_deg, 6.0, 0.1);
  ASSERT_FALSE(check.doubts.empty());
  EXPECT_NE(check.doubts.front().find("tilted"), std::string::npos) << check.doubts.front();
}

TEST(BoxViewChecks, RejectsBadParameters)
{
  const PointSet scan = topFaceScan();
  BoxViewCheckParams params = fromAbove();
  params.max_face_tilt_deg = 0.0;
  EXPECT_THROW(checkBoxView(Eigen::Isometry3d::Identity(), cardboardBox(), scan, all(scan), params),
               brick_pose::ConfigError);
}

// A face turned within its plane keeps its plane and nearly all its coverage;
// the rectangle around its points is least at the scan's own turn.
TEST(BoxViewChecks, AFaceTurnedWithinItsPlaneIsNotTrusted)
{
  const PointSet scan = topFaceScan();
  Eigen::Isometry3d turned = Eigen::Isometry3d::Identity();
  turned.linear() = Eigen::AngleAxisd(6.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const BoxViewCheck check = checkBoxView(turned, cardboardBox(), scan, all(scan), fromAbove());
  EXPECT_NEAR(check.max_face_turn_deg, 6.0, 0.6);
  EXPECT_LT(check.max_face_tilt_deg, 0.1);
  ASSERT_FALSE(check.doubts.empty());
  EXPECT_NE(check.doubts.front().find("turned"), std::string::npos) << check.doubts.front();

  const BoxViewCheck right = checkBoxView(Eigen::Isometry3d::Identity(), cardboardBox(), scan, all(scan), fromAbove());
  EXPECT_LT(right.max_face_turn_deg, 0.6);
}
