#include "brick_pose/registration/model_cloud.h"

#include <cmath>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace registration
{
namespace
{
/// Grid on the rectangle origin + s * u + t * v, s in [0, u_len], t in
/// [0, v_len]: the steps are stretched so both edges are sampled exactly.
/// The first and last rows (columns) are left out when skip_u_edges
/// (skip_v_edges) says an adjacent face already holds those edges.
void addFaceGridWithout(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, double u_len,
                        const Eigen::Vector3d& v, double v_len, const Eigen::Vector3d& normal, double spacing_m,
                        bool skip_u_edges, bool skip_v_edges, PointSet& cloud)
{
  const int u_steps = std::max(1, static_cast<int>(std::lround(u_len / spacing_m)));
  const int v_steps = std::max(1, static_cast<int>(std::lround(v_len / spacing_m)));
  const int u_margin = skip_u_edges ? 1 : 0;
  const int v_margin = skip_v_edges ? 1 : 0;
  for (int i = u_margin; i <= u_steps - u_margin; ++i)
    for (int j = v_margin; j <= v_steps - v_margin; ++j)
    {
      cloud.points.push_back(origin + (u_len * i / u_steps) * u + (v_len * j / v_steps) * v);
      cloud.normals.push_back(normal);
    }
}

void addFaceGrid(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, double u_len, const Eigen::Vector3d& v,
                 double v_len, const Eigen::Vector3d& normal, double spacing_m, PointSet& cloud)
{
  addFaceGridWithout(origin, u, u_len, v, v_len, normal, spacing_m, false, false, cloud);
}

void requireSpacing(double spacing_m)
{
  if (!(spacing_m > 0.0) || !std::isfinite(spacing_m))
    throw ConfigError("ModelCloudParams.spacing_m must be positive, got " + std::to_string(spacing_m));
}
}  // namespace

PointSet buildCuboidSurfaceCloud(const BrickType& brick, double spacing_m)
{
  brick.validate();
  requireSpacing(spacing_m);
  const double l = brick.length_m;
  const double w = brick.width_m;
  const double h = brick.height_m;
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d y = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  PointSet cloud;
  // Top and bottom hold all their edges; the +-y sides hold their vertical
  // edges but not the horizontal ones (top/bottom have them); the +-x ends
  // hold none of their edges.
  addFaceGridWithout({-0.5 * l, -0.5 * w, 0.0}, x, l, y, w, z, spacing_m, false, false, cloud);
  addFaceGridWithout({-0.5 * l, -0.5 * w, -h}, x, l, y, w, -z, spacing_m, false, false, cloud);
  addFaceGridWithout({-0.5 * l, 0.5 * w, -h}, x, l, z, h, y, spacing_m, false, true, cloud);
  addFaceGridWithout({-0.5 * l, -0.5 * w, -h}, x, l, z, h, -y, spacing_m, false, true, cloud);
  addFaceGridWithout({0.5 * l, -0.5 * w, -h}, y, w, z, h, x, spacing_m, true, true, cloud);
  addFaceGridWithout({-0.5 * l, -0.5 * w, -h}, y, w, z, h, -x, spacing_m, true, true, cloud);
  return cloud;
}

PointSet buildBrickModelCloud(const BrickType& brick, const ModelCloudParams& options)
{
  brick.validate();
  requireSpacing(options.spacing_m);
  const double half_l = 0.5 * brick.length_m;
  const double half_w = 0.5 * brick.width_m;
  const double h = brick.height_m;
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d y = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();

  PointSet cloud;
  addFaceGrid({-half_l, -half_w, 0.0}, x, brick.length_m, y, brick.width_m, z, options.spacing_m, cloud);
  // Side faces start one step below the top edge, which the top face has.
  const double step = std::min(options.spacing_m, h);
  for (BrickSide side : options.sides)
  {
    switch (side)
    {
      case BrickSide::kPlusX:
        addFaceGrid({half_l, -half_w, -step}, y, brick.width_m, -z, h - step, x, options.spacing_m, cloud);
        break;
      case BrickSide::kMinusX:
        addFaceGrid({-half_l, -half_w, -step}, y, brick.width_m, -z, h - step, -x, options.spacing_m, cloud);
        break;
      case BrickSide::kPlusY:
        addFaceGrid({-half_l, half_w, -step}, x, brick.length_m, -z, h - step, y, options.spacing_m, cloud);
        break;
      case BrickSide::kMinusY:
        addFaceGrid({-half_l, -half_w, -step}, x, brick.length_m, -z, h - step, -y, options.spacing_m, cloud);
        break;
    }
  }
  return cloud;
}

std::vector<BrickSide> visibleSides(const BrickType& brick, const Eigen::Isometry3d& camera_from_brick)
{
  const Eigen::Vector3d camera_in_brick = camera_from_brick.inverse().translation();
  const double half_l = 0.5 * brick.length_m;
  const double half_w = 0.5 * brick.width_m;
  std::vector<BrickSide> sides;
  if (camera_in_brick.x() > half_l)
    sides.push_back(BrickSide::kPlusX);
  if (camera_in_brick.x() < -half_l)
    sides.push_back(BrickSide::kMinusX);
  if (camera_in_brick.y() > half_w)
    sides.push_back(BrickSide::kPlusY);
  if (camera_in_brick.y() < -half_w)
    sides.push_back(BrickSide::kMinusY);
  return sides;
}
}  // namespace registration
}  // namespace brick_pose
