#include "brick_pose/registration/symmetric_icp.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>


#include "brick_pose/common/elapsed.h"
#include "brick_pose/registration/point_grid.h"
#include "brick_pose/registration/rigid_fit.h"

namespace brick_pose
{
namespace registration
{
namespace
{
// Offsets along the normal are outliers (kOutlierOffsetPerMedian) never
// below this fraction of the in-surface tolerance.
constexpr double kMinOutlierOffsetPerTolerance = 0.5;

/// (source index, target index) pairs; the source -> target ones first.
struct Correspondences
{
  std::vector<std::pair<int, int>> pairs;
  std::size_t forward_count = 0;  ///< pairs[0, forward_count) are source -> target
};

double rmsRadius(const std::vector<Eigen::Vector3d>& points)
{
  if (points.empty())
    return 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points)
    mean += p;
  mean /= static_cast<double>(points.size());
  double sum_sq = 0.0;
  for (const Eigen::Vector3d& p : points)
    sum_sq += (p - mean).squaredNorm();
  return std::sqrt(sum_sq / static_cast<double>(points.size()));
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v)
{
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// Sliding along a flat face converges geometrically and slowly: the interior
// correspondences, which dominate, pull towards the current pose and only the
// boundary pulls towards the solution. When two steps point the same way and
// shrink by a ratio rho, the remaining distance is rho / (1 - rho) steps
// (Besl & McKay's accelerated ICP uses the same observation).
double extrapolationFactor(const Twist& previous, const Twist& current, const SymmetricIcpParams& options)
{
  const double previous_norm = previous.norm();
  const double current_norm = current.norm();
  if (previous_norm <= 0.0 || current_norm <= 0.0)
    return 0.0;
  if (previous.dot(current) < options.min_extrapolation_cos * previous_norm * current_norm)
    return 0.0;
  const double rho = current_norm / previous_norm;
  if (rho >= 1.0)
    return 0.0;
  return std::min(rho / (1.0 - rho), options.max_extrapolation);
}

Eigen::Isometry3d scaledStep(const Eigen::Isometry3d& step, double factor)
{
  const Eigen::AngleAxisd rotation(step.linear());
  Eigen::Isometry3d scaled = Eigen::Isometry3d::Identity();
  scaled.linear() = Eigen::AngleAxisd(rotation.angle() * factor, rotation.axis()).toRotationMatrix();
  scaled.translation() = step.translation() * factor;
  return scaled;
}

/// Nearest neighbours both ways within radius_m. The source grid is built on
/// the unmoved source, so target points are taken into the source frame
/// instead of re-hashing the moved source every iteration.
Correspondences matchBothWays(const std::vector<Eigen::Vector3d>& moved_source,
                              const std::vector<Eigen::Vector3d>& target, const PointGrid& target_grid,
                              const PointGrid& source_grid, const Eigen::Isometry3d& source_to_target,
                              double radius_m)
{
  Correspondences matches;
  auto& pairs = matches.pairs;
  for (std::size_t i = 0; i < moved_source.size(); ++i)
  {
    const int nearest = target_grid.nearestWithin(moved_source[i], radius_m);
    if (nearest >= 0)
      pairs.emplace_back(static_cast<int>(i), nearest);
  }
  matches.forward_count = pairs.size();
  const Eigen::Isometry3d target_to_source = source_to_target.inverse();
  for (std::size_t j = 0; j < target.size(); ++j)
  {
    const int nearest = source_grid.nearestWithin(target_to_source * target[j], radius_m);
    if (nearest >= 0)
      pairs.emplace_back(nearest, static_cast<int>(j));
  }
  return matches;
}

/// Step (applied on the left of the current pose) of closed-form point-to-point.
std::optional<Eigen::Isometry3d> pointToPointStep(const std::vector<Eigen::Vector3d>& moved_source,
                                                  const std::vector<Eigen::Vector3d>& target,
                                                  const Correspondences& matches)
{
  const auto& pairs = matches.pairs;
  std::vector<Eigen::Vector3d> from;
  std::vector<Eigen::Vector3d> to;
  from.reserve(pairs.size());
  to.reserve(pairs.size());
  for (const auto& [i, j] : pairs)
  {
    from.push_back(moved_source[i]);
    to.push_back(target[j]);
  }
  const RigidFit fit = fitRigid(from, to);
  if (!fit.valid)
    return std::nullopt;
  return fit.transform;
}

/// One Gauss-Newton step of the hybrid point-to-plane / point-to-point cost,
/// linearised about the centroid of the moved source for conditioning.
std::optional<Eigen::Isometry3d> hybridStep(const std::vector<Eigen::Vector3d>& moved_source,
                                            const std::vector<Eigen::Vector3d>& moved_normals,
                                            const std::vector<Eigen::Vector3d>& target,
                                            const Correspondences& matches, double in_surface_tolerance_m,
                                            double reverse_in_surface_tolerance_m, bool forward_point_to_point)
{
  const auto& pairs = matches.pairs;
  if (pairs.size() < 3)
    return std::nullopt;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& [i, j] : pairs)
    centre += moved_source[i];
  centre /= static_cast<double>(pairs.size());

  // Stereo depth puts "flying pixels" between an edge and the background,
  // far off the surface; a robust scale of the offsets along the normal
  // (median absolute offset) drops them without a noise parameter.
  std::vector<double> normal_offsets;
  normal_offsets.reserve(pairs.size());
  for (const auto& [i, j] : pairs)
    normal_offsets.push_back(std::abs(moved_normals[i].dot(target[j] - moved_source[i])));
  std::nth_element(normal_offsets.begin(), normal_offsets.begin() + normal_offsets.size() / 2, normal_offsets.end());
  const double max_normal_offset_m =
      std::max(kMinOutlierOffsetPerTolerance * in_surface_tolerance_m,
               kOutlierOffsetPerMedian * normal_offsets[normal_offsets.size() / 2]);

  // Unknowns x = (dt, dw): a point p moves by dt + dw x (p - centre).
  Matrix6d normal_matrix = Matrix6d::Zero();
  Twist rhs = Twist::Zero();
  for (std::size_t k = 0; k < pairs.size(); ++k)
  {
    const auto [i, j] = pairs[k];
    const double tolerance_m = k < matches.forward_count ? in_surface_tolerance_m : reverse_in_surface_tolerance_m;
    const Eigen::Vector3d p = moved_source[i] - centre;
    const Eigen::Vector3d& n = moved_normals[i];
    const Eigen::Vector3d offset = target[j] - moved_source[i];
    const double along_normal = n.dot(offset);
    const bool has_normal = n.squaredNorm() > 0.5;  // estimated normals may be zero
    if (has_normal && std::abs(along_normal) > max_normal_offset_m)
      continue;
    if (has_normal && (offset - along_normal * n).norm() <= tolerance_m)
    {
      Twist row;
      row << n, p.cross(n);
      normal_matrix += row * row.transpose();
      rhs += row * along_normal;
    }
    else if (forward_point_to_point || k >= matches.forward_count || !has_normal)
    {
      Eigen::Matrix<double, 3, 6> jacobian;
      jacobian << Eigen::Matrix3d::Identity(), -skew(p);
      normal_matrix += jacobian.transpose() * jacobian;
      rhs += jacobian.transpose() * offset;
    }
  }
  // A face with no overhanging edge leaves the in-plane motion free; the
  // step's damping keeps it still.
  return solveRigidStep(normal_matrix, rhs, centre);
}
}  // namespace

Eigen::Isometry3d refineSymmetricIcp(const std::vector<Eigen::Vector3d>& source,
                                     const std::vector<Eigen::Vector3d>& source_normals,
                                     const std::vector<Eigen::Vector3d>& target, const Eigen::Isometry3d& start,
                                     const SymmetricIcpParams& options)
{
  const bool hybrid = !source_normals.empty() && source_normals.size() == source.size();
  const double start_radius_m = std::max(options.radius_m, options.final_radius_m);
  const double final_radius_m = std::min(options.radius_m, options.final_radius_m);
  const double shrink = options.max_iterations > 1
                            ? std::pow(final_radius_m / start_radius_m, 1.0 / (options.max_iterations - 1))
                            : 1.0;
  const double length_scale_m = rmsRadius(source);
  const double final_tolerance_m = std::min(options.in_surface_tolerance_m, options.final_in_surface_tolerance_m);
  const double tolerance_shrink =
      options.max_iterations > 1
          ? std::pow(final_tolerance_m / options.in_surface_tolerance_m, 1.0 / (options.max_iterations - 1))
          : 1.0;
  double in_surface_tolerance_m = options.in_surface_tolerance_m;
  double reverse_in_surface_tolerance_m = options.reverse_in_surface_tolerance_m > 0.0
                                              ? options.reverse_in_surface_tolerance_m
                                              : options.in_surface_tolerance_m;
  PointGrid target_grid(target, start_radius_m);
  PointGrid source_grid(source, start_radius_m);
  double radius_m = start_radius_m;
  Eigen::Isometry3d current = start;
  Twist previous_twist = Twist::Zero();
  bool have_previous = false;
  std::vector<Eigen::Vector3d> moved_source(source.size());
  std::vector<Eigen::Vector3d> moved_normals(hybrid ? source.size() : 0);

  const auto started = SteadyClock::now();
  for (int iteration = 0; iteration < options.max_iterations && secondsSince(started) < options.max_time_s;
       ++iteration)
  {
    target_grid.shrinkTo(radius_m);
    source_grid.shrinkTo(radius_m);
    for (std::size_t i = 0; i < source.size(); ++i)
    {
      moved_source[i] = current * source[i];
      if (hybrid)
        moved_normals[i] = current.linear() * source_normals[i];
    }
    const Correspondences pairs = matchBothWays(moved_source, target, target_grid, source_grid, current, radius_m);
    const bool hybrid_now = hybrid && iteration < options.max_iterations - options.point_to_point_iterations;
    if (hybrid && !hybrid_now && have_previous && iteration == options.max_iterations - options.point_to_point_iterations)
      have_previous = false;  // the step changes nature: no extrapolation across
    const std::optional<Eigen::Isometry3d> step =
        hybrid_now ? hybridStep(moved_source, moved_normals, target, pairs, in_surface_tolerance_m,
                                reverse_in_surface_tolerance_m, options.forward_point_to_point)
               : pointToPointStep(moved_source, target, pairs);
    if (!step)
      break;
    current = *step * current;
    radius_m = std::max(final_radius_m, radius_m * shrink);
    in_surface_tolerance_m = std::max(final_tolerance_m, in_surface_tolerance_m * tolerance_shrink);
    reverse_in_surface_tolerance_m = std::max(std::min(final_tolerance_m, reverse_in_surface_tolerance_m),
                                              reverse_in_surface_tolerance_m * tolerance_shrink);

    const Eigen::AngleAxisd step_rotation(step->linear());
    if (step->translation().norm() < options.min_step_m && step_rotation.angle() < options.min_step_rad)
    {
      if (!hybrid_now)
        break;
      // Converged in the hybrid phase: go on with the point-to-point phase.
      iteration = std::max(iteration, options.max_iterations - options.point_to_point_iterations - 1);
      have_previous = false;
      continue;
    }
    // Translation and rotation vector scaled by the cloud's size, so that both
    // parts are lengths and can be compared.
    Twist twist;
    twist << step->translation(), step_rotation.axis() * step_rotation.angle() * length_scale_m;
    const double factor = have_previous ? extrapolationFactor(previous_twist, twist, options) : 0.0;
    if (factor > 0.0)
    {
      current = scaledStep(*step, factor) * current;
      have_previous = false;  // measure the rate afresh after a jump
    }
    else
    {
      previous_twist = twist;
      have_previous = true;
    }
  }
  return current;
}
}  // namespace registration
}  // namespace brick_pose
