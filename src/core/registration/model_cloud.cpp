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
void addFaceGrid(const Eigen::Vector3d& origin, const Eigen::Vector3d& u, double u_len, const Eigen::Vector3d& v,
                 double v_len, const Eigen::Vector3d& normal, double spacing_m, PointSet& cloud)
{
  const int u_steps = std::max(1, static_cast<int>(std::lround(u_len / spacing_m)));
  const int v_steps = std::max(1, static_cast<int>(std::lround(v_len / spacing_m)));
  for (int i = 0; i <= u_steps; ++i)
    for (int j = 0; j <= v_steps; ++j)
    {
      cloud.points.push_back(origin + (u_len * i / u_steps) * u + (v_len * j / v_steps) * v);
      cloud.normals.push_back(normal);
    }
}
}  // namespace

PointSet buildBrickModelCloud(const BrickType& brick, const ModelCloudParams& options)
{
  brick.validate();
  if (!(options.spacing_m > 0.0) || !std::isfinite(options.spacing_m))
    throw ConfigError("ModelCloudParams.spacing_m must be positive, got " + std::to_string(options.spacing_m));
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
