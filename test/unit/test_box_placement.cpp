#include <gtest/gtest.h>

#include <vector>

#include "brick_pose/registration/box_placement.h"

namespace brick_pose
{
namespace registration
{
namespace
{
/// A box centred at the model origin with the given half extents.
ModelSymmetries boxOf(const Eigen::Vector3d& half_extents_m)
{
  ModelSymmetries box;
  box.box_like = true;
  box.half_extents_m = half_extents_m;
  return box;
}

/// Points on the face across `axis` on the `sign` side of the box at the
/// identity pose, on a 1 cm grid.
void addFace(const Eigen::Vector3d& half, int axis, double sign, std::vector<Eigen::Vector3d>& points)
{
  const int u = (axis + 1) % 3;
  const int v = (axis + 2) % 3;
  for (double a = -half(u); a <= half(u) + 1e-9; a += 0.01)
    for (double b = -half(v); b <= half(v) + 1e-9; b += 0.01)
    {
      Eigen::Vector3d p;
      p(axis) = sign * half(axis);
      p(u) = a;
      p(v) = b;
      points.push_back(p);
    }
}

Eigen::Isometry3d shifted(const Eigen::Vector3d& offset_m)
{
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = offset_m;
  return pose;
}

/// Starts wherever a turn about the model's centre may leave the box: near
/// the scan, and a metre or more off along each axis.
std::vector<Eigen::Vector3d> startOffsets()
{
  std::vector<Eigen::Vector3d> offsets{Eigen::Vector3d(0.03, -0.04, 0.05)};
  for (int axis = 0; axis < 3; ++axis)
    for (const double offset_m : {-1.5, -0.5, 0.5, 1.5})
      offsets.push_back(offset_m * Eigen::Vector3d::Unit(axis));
  return offsets;
}
}  // namespace

// The red brick's 0.2 x 0.2 end face seen head-on from 1.5 m: along the
// line of sight the end meets the scan, across it the scan is centred.
TEST(BoxPlacement, AnEndFaceSeenHeadOnFixesTheBoxWhereverTheTurnLeftIt)
{
  const Eigen::Vector3d half(0.15, 0.1, 0.1);
  std::vector<Eigen::Vector3d> scan;
  addFace(half, 0, -1.0, scan);
  const Eigen::Vector3d viewpoint(-1.65, 0.02, 0.01);
  for (const Eigen::Vector3d& offset : startOffsets())
  {
    const Eigen::Isometry3d placed = anchoredToScanExtent(shifted(offset), boxOf(half), scan, viewpoint, 3);
    EXPECT_LT(placed.translation().norm(), 1e-9) << "start offset " << offset.transpose() << " ended at "
                                                 << placed.translation().transpose();
  }
}

// Seen from beyond a corner, the three faces' planes meet the scan's
// extremes towards the camera.
TEST(BoxPlacement, ACornerViewPutsEachSeenFaceOnTheScan)
{
  const Eigen::Vector3d half(0.2, 0.15, 0.1);
  std::vector<Eigen::Vector3d> scan;
  addFace(half, 0, -1.0, scan);
  addFace(half, 1, -1.0, scan);
  addFace(half, 2, 1.0, scan);
  const Eigen::Vector3d viewpoint(-0.8, -0.7, 0.9);
  for (const Eigen::Vector3d& offset : startOffsets())
    EXPECT_LT(anchoredToScanExtent(shifted(offset), boxOf(half), scan, viewpoint, 3).translation().norm(), 1e-9)
        << "start offset " << offset.transpose();
}

// A long face seen from in front of its middle, its ends cut off (0.6 m of
// the blue brick's 1.2 m): along it the scan is centred, not pushed to an end.
TEST(BoxPlacement, APartOfALongFaceIsCentredAlongIt)
{
  const Eigen::Vector3d half(0.6, 0.1, 0.1);
  std::vector<Eigen::Vector3d> scan;
  addFace(half, 1, -1.0, scan);
  std::vector<Eigen::Vector3d> middle;
  for (const Eigen::Vector3d& p : scan)
    if (std::abs(p.x() - 0.1) <= 0.3 + 1e-6)
      middle.push_back(p);
  const Eigen::Vector3d viewpoint(0.1, -1.5, 0.0);
  const Eigen::Isometry3d placed =
      anchoredToScanExtent(shifted(Eigen::Vector3d(0.02, 0.03, 0.0)), boxOf(half), middle, viewpoint, 0);
  EXPECT_NEAR(placed.translation().x(), 0.1, 1e-9);
  EXPECT_NEAR(placed.translation().y(), 0.0, 1e-9);
  EXPECT_NEAR(placed.translation().z(), 0.0, 1e-9);
}

TEST(BoxPlacement, LeavesAModelThatIsNoBoxWhereItWas)
{
  std::vector<Eigen::Vector3d> scan;
  addFace(Eigen::Vector3d(0.1, 0.1, 0.1), 0, -1.0, scan);
  const Eigen::Isometry3d start = shifted(Eigen::Vector3d(0.3, 0.0, 0.0));
  EXPECT_TRUE(anchoredToScanExtent(start, ModelSymmetries{}, scan, Eigen::Vector3d(-1.0, 0.0, 0.0), 3)
                  .isApprox(start));
}
}  // namespace registration
}  // namespace brick_pose
