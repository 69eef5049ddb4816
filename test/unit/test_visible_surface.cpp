#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/registration/model_cloud.h"
#include "brick_pose/registration/model_symmetry.h"
#include "brick_pose/registration/visible_surface.h"

namespace brick_pose
{
namespace registration
{
namespace
{
constexpr double kSpacingM = 0.01;

/// The orange brick's box as the whole-view search finds it:
/// buildCuboidSurfaceCloud spans x +-0.9, y +-0.1, z -0.2..0.
ModelSymmetries orangeBox()
{
  ModelSymmetries box;
  box.box_like = true;
  box.centre_m = Eigen::Vector3d(0.0, 0.0, -0.1);
  box.half_extents_m = Eigen::Vector3d(0.9, 0.1, 0.1);
  return box;
}

/// 1.8 m in front of the brick's -x end face, level with its centre: the
/// camera sees that 0.2 x 0.2 face alone (view 33 of bench_registration).
const Eigen::Vector3d kEndViewpointM(-2.7, 0.0, -0.1);

struct Extent
{
  Eigen::Vector3d lower = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d upper = -Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
};

Extent extentOf(const PointSet& cloud)
{
  Extent extent;
  for (const Eigen::Vector3d& p : cloud.points)
  {
    extent.lower = extent.lower.cwiseMin(p);
    extent.upper = extent.upper.cwiseMax(p);
  }
  return extent;
}
}  // namespace

// The model's end faces hold none of their edges (the sides and the top do):
// selected by their own normals, the end face would stop 1 cm short of each
// edge, and the polish would pair the scan's edges with it on one side only.
TEST(VisibleSurface, ALoneBoxFaceReachesItsEdgesWithItsOwnNormal)
{
  const PointSet model = buildCuboidSurfaceCloud(BrickCatalogue::mbzirc2020().at("orange"), kSpacingM);
  const PointSet visible =
      visibleModelSurface(model, Eigen::Isometry3d::Identity(), orangeBox(), kEndViewpointM, 0.5 * kSpacingM, 0.2);
  ASSERT_GT(visible.size(), 300u);
  for (const Eigen::Vector3d& normal : visible.normals)
    EXPECT_TRUE(normal.isApprox(-Eigen::Vector3d::UnitX())) << normal.transpose();
  const Extent extent = extentOf(visible);
  EXPECT_NEAR(extent.lower.x(), -0.9, 1e-9);
  EXPECT_NEAR(extent.upper.x(), -0.9, 1e-9);
  EXPECT_NEAR(extent.lower.y(), -0.1, 1e-9);
  EXPECT_NEAR(extent.upper.y(), 0.1, 1e-9);
  EXPECT_NEAR(extent.lower.z(), -0.2, 1e-9);
  EXPECT_NEAR(extent.upper.z(), 0.0, 1e-9);
}

// Seen from above and the -x end, the top and that end are visible; the
// edge they share is in both, the bottom and the far end are not.
TEST(VisibleSurface, TwoFacesTurnedToTheViewpointAndNothingBehind)
{
  const PointSet model = buildCuboidSurfaceCloud(BrickCatalogue::mbzirc2020().at("orange"), kSpacingM);
  const Eigen::Vector3d viewpoint(-2.0, 0.0, 1.5);
  const PointSet visible =
      visibleModelSurface(model, Eigen::Isometry3d::Identity(), orangeBox(), viewpoint, 0.5 * kSpacingM, 0.2);
  int top = 0;
  int end = 0;
  for (std::size_t i = 0; i < visible.size(); ++i)
  {
    top += visible.normals[i].isApprox(Eigen::Vector3d::UnitZ()) ? 1 : 0;
    end += visible.normals[i].isApprox(-Eigen::Vector3d::UnitX()) ? 1 : 0;
  }
  EXPECT_EQ(top + end, static_cast<int>(visible.size()));
  EXPECT_GT(top, 3000);
  EXPECT_GT(end, 300);
  const Extent extent = extentOf(visible);
  EXPECT_NEAR(extent.lower.z(), -0.2, 1e-9);  // the end face's lower edge
  EXPECT_LT(extent.upper.x(), 0.9 + 1e-9);
}

// A model that is no box keeps the points whose own normals face the camera.
TEST(VisibleSurface, WithoutABoxOwnNormalsDecide)
{
  const PointSet model = buildCuboidSurfaceCloud(BrickCatalogue::mbzirc2020().at("orange"), kSpacingM);
  const PointSet visible = visibleModelSurface(model, Eigen::Isometry3d::Identity(), ModelSymmetries{},
                                               kEndViewpointM, 0.5 * kSpacingM, 0.2);
  ASSERT_GT(visible.size(), 0u);
  const Extent extent = extentOf(visible);
  // The end face without its edges.
  EXPECT_NEAR(extent.lower.y(), -0.09, 1e-9);
  EXPECT_NEAR(extent.upper.y(), 0.09, 1e-9);
}
}  // namespace registration
}  // namespace brick_pose
