#include "brick_pose/registration/boundary_icp.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <Eigen/Eigenvalues>

#include "brick_pose/common/elapsed.h"
#include "brick_pose/registration/point_grid.h"
#include "brick_pose/registration/rigid_fit.h"

namespace brick_pose
{
namespace registration
{
namespace
{
// Point-to-plane outliers (kOutlierOffsetPerMedian) lie never nearer than
// this fraction of the final plane radius.
constexpr double kMinOutlierOffsetPerRadius = 0.25;
// Boundary pairs: the outward directions of the two points agree to 60 deg.
constexpr double kMinOutwardCos = 0.5;

/// The normal equations of one Gauss-Newton step, linearised about `centre`:
/// a point p moves by dt + dw x (p - centre).
struct NormalEquations
{
  Matrix6d lhs = Matrix6d::Zero();
  Twist rhs = Twist::Zero();
  int rows = 0;

  /// One residual: the offset of the target along `direction` from the moved
  /// source point `p`.
  void add(const Eigen::Vector3d& p, const Eigen::Vector3d& direction, double offset, const Eigen::Vector3d& centre)
  {
    Twist row;
    row << direction, (p - centre).cross(direction);
    lhs += row * row.transpose();
    rhs += row * offset;
    ++rows;
  }
};

/// Normal of the neighbourhood (smallest principal axis), zero when flat
/// in no direction.
Eigen::Vector3d principalNormal(const Eigen::Matrix3d& covariance)
{
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(covariance);
  const Eigen::Vector3d normal = solver.eigenvectors().col(0);
  return normal.allFinite() ? normal : Eigen::Vector3d::Zero();
}

double medianAbs(std::vector<double> values)
{
  if (values.empty())
    return 0.0;
  const std::size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  return values[middle];
}

/// Source -> target point-to-plane residuals within radius_m; offsets of
/// outliers along the normal (MAD rule) are left out.
void addPlanePairs(const std::vector<Eigen::Vector3d>& moved_source, const std::vector<Eigen::Vector3d>& moved_normals,
                   const std::vector<Eigen::Vector3d>& target, const PointGrid& target_grid, double radius_m,
                   double min_outlier_offset_m, const Eigen::Vector3d& centre, NormalEquations& equations)
{
  std::vector<std::pair<int, double>> offsets;  // (source index, offset along its normal)
  offsets.reserve(moved_source.size());
  for (std::size_t i = 0; i < moved_source.size(); ++i)
  {
    const int nearest = target_grid.nearestWithin(moved_source[i], radius_m);
    if (nearest >= 0)
      offsets.emplace_back(static_cast<int>(i), moved_normals[i].dot(target[nearest] - moved_source[i]));
  }
  std::vector<double> magnitudes;
  magnitudes.reserve(offsets.size());
  for (const auto& pair : offsets)
    magnitudes.push_back(std::abs(pair.second));
  const double max_offset_m = std::max(min_outlier_offset_m, kOutlierOffsetPerMedian * medianAbs(magnitudes));
  for (const auto& [i, offset] : offsets)
    if (std::abs(offset) <= max_offset_m)
      equations.add(moved_source[i], moved_normals[i], offset, centre);
}

/// Index of the nearest source boundary point within radius_m of `query`
/// (in the source frame) whose outward direction agrees with
/// `query_outward` (also in the source frame), or -1.
int nearestAgreeing(const SurfaceBoundary& source_boundary, const PointGrid& boundary_grid,
                    const Eigen::Vector3d& query, const Eigen::Vector3d& query_outward, double radius_m)
{
  int nearest = -1;
  double nearest_sq = std::numeric_limits<double>::infinity();
  boundary_grid.forEachWithin(query, radius_m, [&](int k) {
    if (source_boundary.outward[k].dot(query_outward) < kMinOutwardCos)
      return;
    const double d_sq = (source_boundary.points[k] - query).squaredNorm();
    if (d_sq < nearest_sq)
    {
      nearest_sq = d_sq;
      nearest = k;
    }
  });
  return nearest;
}

/// Target boundary -> source boundary point-to-line residuals within
/// radius_m. The source grid is on the unmoved boundary, so the target points
/// are taken into the source frame. Pairs far off the source surface
/// (flying pixels) are left out.
void addBoundaryPairs(const SurfaceBoundary& source_boundary, const PointGrid& boundary_grid,
                      const std::vector<Eigen::Vector3d>& source_normals_at_boundary,
                      const SurfaceBoundary& target_boundary, const Eigen::Isometry3d& current, double radius_m,
                      double max_normal_offset_m, const Eigen::Vector3d& centre, NormalEquations& equations)
{
  const Eigen::Isometry3d target_to_source = current.inverse();
  for (std::size_t j = 0; j < target_boundary.size(); ++j)
  {
    const int nearest = nearestAgreeing(source_boundary, boundary_grid, target_to_source * target_boundary.points[j],
                                        target_to_source.linear() * target_boundary.outward[j], radius_m);
    if (nearest < 0)
      continue;
    const Eigen::Vector3d moved = current * source_boundary.points[nearest];
    const Eigen::Vector3d offset = target_boundary.points[j] - moved;
    if (std::abs((current.linear() * source_normals_at_boundary[nearest]).dot(offset)) > max_normal_offset_m)
      continue;
    const Eigen::Vector3d outward = current.linear() * source_boundary.outward[nearest];
    equations.add(moved, outward, outward.dot(offset), centre);
  }
}

/// The rigid step of the solved normal equations, or nothing when singular.
std::optional<Eigen::Isometry3d> solveStep(const NormalEquations& equations, const Eigen::Vector3d& centre)
{
  if (equations.rows < 3)
    return std::nullopt;
  return solveRigidStep(equations.lhs, equations.rhs, centre);
}

/// The normal at each source boundary point, for the flying-pixel check of
/// the boundary pairs: that of its nearest source point within radius_m
/// (zero, no check, when there is none).
std::vector<Eigen::Vector3d> normalsAtBoundary(const std::vector<Eigen::Vector3d>& source,
                                               const std::vector<Eigen::Vector3d>& source_normals,
                                               const SurfaceBoundary& source_boundary, double radius_m)
{
  std::vector<Eigen::Vector3d> normals(source_boundary.size(), Eigen::Vector3d::Zero());
  if (source_boundary.points.empty())
    return normals;
  const PointGrid source_grid(source, radius_m);
  for (std::size_t k = 0; k < source_boundary.size(); ++k)
  {
    const int nearest = source_grid.nearestWithin(source_boundary.points[k], radius_m);
    if (nearest >= 0)
      normals[k] = source_normals[nearest];
  }
  return normals;
}

double shrinkFactor(double start, double final, int iterations)
{
  if (iterations <= 1 || !(start > final))
    return 1.0;
  return std::pow(final / start, 1.0 / (iterations - 1));
}
}  // namespace

SurfaceBoundary findSurfaceBoundary(const std::vector<Eigen::Vector3d>& points,
                                    const std::vector<Eigen::Vector3d>& normals, double radius_m,
                                    double min_centroid_offset, int min_neighbours)
{
  SurfaceBoundary boundary;
  if (points.empty() || !(radius_m > 0.0) || !std::isfinite(radius_m))
    return boundary;
  const bool have_normals = normals.size() == points.size();
  const PointGrid grid(points, radius_m);
  const double min_offset_m = min_centroid_offset * radius_m;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d sum_outer = Eigen::Matrix3d::Zero();  // only to estimate a normal
    int count = 0;
    grid.forEachWithin(points[i], radius_m, [&](int j) {
      if (static_cast<std::size_t>(j) == i)
        return;
      const Eigen::Vector3d d = points[j] - points[i];  // centred on i for precision
      sum += d;
      if (!have_normals)
        sum_outer += d * d.transpose();
      ++count;
    });
    if (count < min_neighbours)
      continue;
    const Eigen::Vector3d mean = sum / count;
    Eigen::Vector3d normal = have_normals ? normals[i] : principalNormal(sum_outer / count - mean * mean.transpose());
    if (!(normal.squaredNorm() > 0.0))
      continue;
    normal.normalize();
    const Eigen::Vector3d in_plane = mean - normal.dot(mean) * normal;
    const double offset_m = in_plane.norm();
    if (offset_m > min_offset_m)
    {
      boundary.points.push_back(points[i]);
      boundary.outward.push_back(-in_plane / offset_m);
    }
  }
  return boundary;
}

double neighbourhoodRadius(const std::vector<Eigen::Vector3d>& points, int neighbours, std::mt19937_64& rng,
                          int probes)
{
  if (neighbours < 1 || points.size() <= static_cast<std::size_t>(neighbours))
    return 0.0;
  std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
  std::vector<double> distances_sq(points.size());
  std::vector<double> radii;
  for (int probe = 0; probe < probes; ++probe)
  {
    const Eigen::Vector3d& centre = points[pick(rng)];
    for (std::size_t j = 0; j < points.size(); ++j)
      distances_sq[j] = (points[j] - centre).squaredNorm();
    // Index `neighbours` skips the probe itself (distance 0).
    std::nth_element(distances_sq.begin(), distances_sq.begin() + neighbours, distances_sq.end());
    radii.push_back(std::sqrt(distances_sq[neighbours]));
  }
  return medianAbs(radii);
}

OrientedPoints pointsOnSurface(const std::vector<Eigen::Vector3d>& source,
                               const std::vector<Eigen::Vector3d>& source_normals,
                               const std::vector<Eigen::Vector3d>& target, const Eigen::Isometry3d& source_to_target,
                               double near_m, double reach_m, double max_sigmas, double min_offset_m)
{
  OrientedPoints on_surface;
  if (source.empty() || source_normals.size() != source.size() || !(reach_m > 0.0) || !std::isfinite(reach_m))
    return on_surface;
  near_m = std::min(near_m, reach_m);
  if (!(near_m > 0.0))
    near_m = reach_m;
  // The grids are on the unmoved source: target points go into its frame.
  const PointGrid near_grid(source, near_m);
  const PointGrid far_grid(source, reach_m);
  const Eigen::Isometry3d target_to_source = source_to_target.inverse();
  std::vector<int> nearest_source(target.size(), -1);
  std::vector<double> offsets(target.size(), 0.0);
  std::vector<double> magnitudes;
  magnitudes.reserve(target.size());
  for (std::size_t j = 0; j < target.size(); ++j)
  {
    const Eigen::Vector3d in_source = target_to_source * target[j];
    int nearest = near_grid.nearestWithin(in_source, near_m);
    if (nearest < 0)
      nearest = far_grid.nearestWithin(in_source, reach_m);
    if (nearest < 0 || !(source_normals[nearest].squaredNorm() > 0.0))
      continue;
    nearest_source[j] = nearest;
    offsets[j] = source_normals[nearest].dot(in_source - source[nearest]);
    magnitudes.push_back(std::abs(offsets[j]));
  }
  // 1.4826 * median |offset| estimates the standard deviation of Gaussian noise.
  const double max_offset_m = std::max(min_offset_m, max_sigmas * 1.4826 * medianAbs(magnitudes));
  for (std::size_t j = 0; j < target.size(); ++j)
    if (nearest_source[j] >= 0 && std::abs(offsets[j]) <= max_offset_m)
    {
      on_surface.points.push_back(target[j]);
      on_surface.normals.push_back(source_to_target.linear() * source_normals[nearest_source[j]]);
    }
  return on_surface;
}

Eigen::Isometry3d refineBoundaryIcp(const std::vector<Eigen::Vector3d>& source,
                                    const std::vector<Eigen::Vector3d>& source_normals,
                                    const SurfaceBoundary& source_boundary, const std::vector<Eigen::Vector3d>& target,
                                    const SurfaceBoundary& target_boundary, const Eigen::Isometry3d& start,
                                    const BoundaryIcpParams& options)
{
  if (source.empty() || target.empty() || source_normals.size() != source.size() || options.max_iterations <= 0)
    return start;
  const double plane_radius_start_m = std::max(options.plane_radius_m, options.final_plane_radius_m);
  const double boundary_radius_start_m = std::max(options.boundary_radius_m, options.final_boundary_radius_m);
  const double plane_shrink = shrinkFactor(plane_radius_start_m, options.final_plane_radius_m, options.max_iterations);
  const double boundary_shrink =
      shrinkFactor(boundary_radius_start_m, options.final_boundary_radius_m, options.max_iterations);
  const double min_outlier_offset_m = kMinOutlierOffsetPerRadius * options.final_plane_radius_m;

  const std::vector<Eigen::Vector3d> boundary_normals =
      normalsAtBoundary(source, source_normals, source_boundary, boundary_radius_start_m);
  PointGrid target_grid(target, plane_radius_start_m);
  PointGrid boundary_grid(source_boundary.points, boundary_radius_start_m);
  double plane_radius_m = plane_radius_start_m;
  double boundary_radius_m = boundary_radius_start_m;
  Eigen::Isometry3d current = start;
  std::vector<Eigen::Vector3d> moved_source(source.size());
  std::vector<Eigen::Vector3d> moved_normals(source.size());
  const auto started = SteadyClock::now();
  for (int iteration = 0; iteration < options.max_iterations && secondsSince(started) < options.max_time_s;
       ++iteration)
  {
    target_grid.shrinkTo(plane_radius_m);
    boundary_grid.shrinkTo(boundary_radius_m);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < source.size(); ++i)
    {
      moved_source[i] = current * source[i];
      moved_normals[i] = current.linear() * source_normals[i];
      centre += moved_source[i];
    }
    centre /= static_cast<double>(source.size());

    NormalEquations equations;
    addPlanePairs(moved_source, moved_normals, target, target_grid, plane_radius_m, min_outlier_offset_m, centre,
                  equations);
    addBoundaryPairs(source_boundary, boundary_grid, boundary_normals, target_boundary, current, boundary_radius_m,
                     plane_radius_m, centre, equations);
    const std::optional<Eigen::Isometry3d> step = solveStep(equations, centre);
    if (!step)
      break;
    current = *step * current;
    plane_radius_m = std::max(options.final_plane_radius_m, plane_radius_m * plane_shrink);
    boundary_radius_m = std::max(options.final_boundary_radius_m, boundary_radius_m * boundary_shrink);
    const Eigen::AngleAxisd step_rotation(step->linear());
    if (step->translation().norm() < options.min_step_m && step_rotation.angle() < options.min_step_rad)
    {
      const bool radii_final = plane_radius_m <= options.final_plane_radius_m &&
                               boundary_radius_m <= options.final_boundary_radius_m;
      if (radii_final)
        break;
      // Converged with wide radii, which may still pair what does not
      // overlap: finish at the final radii.
      plane_radius_m = options.final_plane_radius_m;
      boundary_radius_m = options.final_boundary_radius_m;
    }
  }
  return current;
}
}  // namespace registration
}  // namespace brick_pose
