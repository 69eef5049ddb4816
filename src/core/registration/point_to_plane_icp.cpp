#include "brick_pose/registration/point_to_plane_icp.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "brick_pose/registration/rigid_fit.h"

namespace brick_pose
{
namespace registration
{
Eigen::Isometry3d refinePointToPlane(const PointSet& model, const PointGrid& model_grid, const PointSet& target,
                                     const std::vector<int>& target_indices, const Eigen::Isometry3d& model_to_target,
                                     const PointToPlaneParams& params)
{
  const double min_cos = std::cos(params.max_normal_difference_deg * M_PI / 180.0);
  const double radius_m = std::min(params.radius_m, model_grid.maxRadius());
  Eigen::Isometry3d pose = model_to_target;
  for (int iteration = 0; iteration < params.iterations; ++iteration)
  {
    const Eigen::Isometry3d target_to_model = pose.inverse();
    Eigen::Matrix<double, 6, 6> lhs = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    std::vector<std::pair<int, int>> pairs;  // (target, model)
    for (int t : target_indices)
    {
      const Eigen::Vector3d q = target_to_model * target.points[t];
      const Eigen::Vector3d normal = target_to_model.linear() * target.normals[t];
      int best = -1;
      double best_sq = std::numeric_limits<double>::infinity();
      model_grid.forEachWithin(q, radius_m, [&](int m) {
        const double d_sq = (model.points[m] - q).squaredNorm();
        if (d_sq < best_sq && model.normals[m].dot(normal) >= min_cos)
        {
          best_sq = d_sq;
          best = m;
        }
      });
      if (best >= 0)
      {
        pairs.emplace_back(t, best);
        centre += pose * model.points[best];
      }
    }
    if (pairs.size() < 6)
      break;
    centre /= static_cast<double>(pairs.size());
    // The model moves by a small step (dt, dw) about `centre` in the target
    // frame; each pair's residual is the target point's offset along the
    // moved model normal.
    for (const auto& [t, m] : pairs)
    {
      const Eigen::Vector3d point = pose * model.points[m];
      const Eigen::Vector3d normal = pose.linear() * model.normals[m];
      Eigen::Matrix<double, 6, 1> jacobian;
      jacobian << normal, (point - centre).cross(normal);
      const double residual = normal.dot(target.points[t] - point);
      lhs += jacobian * jacobian.transpose();
      rhs += jacobian * residual;
    }
    const std::optional<Eigen::Isometry3d> step = solveRigidStep(lhs, rhs, centre);
    if (!step)
      break;
    pose = *step * pose;
    if (std::getenv("BP_ICP_DEBUG"))
      std::fprintf(stderr, "ICP it %d pairs %zu/%zu step t %.4f r %.4f\n", iteration, pairs.size(), target_indices.size(),
                   step->translation().norm(), Eigen::AngleAxisd(step->linear()).angle());
    if (step->translation().norm() < params.min_step_m && Eigen::AngleAxisd(step->linear()).angle() < 1e-6)
      break;
  }
  return pose;
}
}  // namespace registration
}  // namespace brick_pose
