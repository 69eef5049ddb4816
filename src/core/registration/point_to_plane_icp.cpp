#include "brick_pose/registration/point_to_plane_icp.h"

#include <cmath>
#include <algorithm>
#include <limits>

#include "brick_pose/common/angles.h"
#include "brick_pose/registration/rigid_fit.h"

namespace brick_pose
{
namespace registration
{
namespace
{
constexpr double kTrimSigmas = 3.0;
constexpr double kMadToSigma = 1.4826;
}  // namespace

Eigen::Isometry3d refinePointToPlane(const PointSet& model, const PointGrid& model_grid, const PointSet& target,
                                     const std::vector<int>& target_indices, const Eigen::Isometry3d& model_to_target,
                                     const PointToPlaneParams& params)
{
  const double min_cos = std::cos(params.max_normal_difference_deg * kDegToRad);
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
        pairs.emplace_back(t, best);
    }
    if (pairs.size() < 6)
      break;
    // Trimmed: pairs whose offset from the plane exceeds a few robust
    // standard deviations (from the median absolute offset) do not pull. A
    // scan holds points a plane fit must not follow: grazing strips of a face
    // seen edge-on, flying pixels behind a silhouette.
    std::vector<double> residuals(pairs.size());
    for (std::size_t k = 0; k < pairs.size(); ++k)
    {
      const auto [t, m] = pairs[k];
      residuals[k] = (pose.linear() * model.normals[m]).dot(target.points[t] - pose * model.points[m]);
    }
    std::vector<double> magnitudes(residuals.size());
    for (std::size_t k = 0; k < residuals.size(); ++k)
      magnitudes[k] = std::abs(residuals[k]);
    std::nth_element(magnitudes.begin(), magnitudes.begin() + magnitudes.size() / 2, magnitudes.end());
    const double max_offset_m =
        std::max(params.min_trim_offset_m, kTrimSigmas * kMadToSigma * magnitudes[magnitudes.size() / 2]);
    centre = Eigen::Vector3d::Zero();
    int used = 0;
    for (std::size_t k = 0; k < pairs.size(); ++k)
      if (std::abs(residuals[k]) <= max_offset_m)
      {
        centre += pose * model.points[pairs[k].second];
        ++used;
      }
    if (used < 6)
      break;
    centre /= static_cast<double>(used);
    // The model moves by a small step (dt, dw) about `centre` in the target
    // frame; each pair's residual is the target point's offset along the
    // moved model normal.
    for (std::size_t k = 0; k < pairs.size(); ++k)
    {
      if (std::abs(residuals[k]) > max_offset_m)
        continue;
      const int m = pairs[k].second;
      const Eigen::Vector3d point = pose * model.points[m];
      const Eigen::Vector3d normal = pose.linear() * model.normals[m];
      Eigen::Matrix<double, 6, 1> jacobian;
      jacobian << normal, (point - centre).cross(normal);
      lhs += jacobian * jacobian.transpose();
      rhs += jacobian * residuals[k];
    }
    const std::optional<Eigen::Isometry3d> step = solveRigidStep(lhs, rhs, centre);
    if (!step)
      break;
    pose = *step * pose;
    if (step->translation().norm() < params.min_step_m && Eigen::AngleAxisd(step->linear()).angle() < 1e-6)
      break;
  }
  return pose;
}
}  // namespace registration
}  // namespace brick_pose
