#include "brick_pose/registration/model_symmetry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "brick_pose/common/angles.h"
#include "brick_pose/registration/brick_symmetry.h"

namespace brick_pose
{
namespace registration
{
namespace
{
// Normals within this angle of an axis belong to it.
constexpr double kAxisToleranceDeg = 10.0;
// Fraction of the normals that must lie along the three axes for a box.
constexpr double kMinBoxNormalFraction = 0.9;

/// The direction (up to sign) that most normals lie along, among those with
/// |n . exclude| <= max_exclude_cos. Zero when there is none.
Eigen::Vector3d dominantAxis(const std::vector<Eigen::Vector3d>& normals, const Eigen::Vector3d& exclude,
                             double max_exclude_cos)
{
  const double min_cos = std::cos(kAxisToleranceDeg * kDegToRad);
  Eigen::Vector3d best = Eigen::Vector3d::Zero();
  int best_count = 0;
  // Every k-th normal as a candidate keeps this cheap on dense models.
  const std::size_t stride = std::max<std::size_t>(1, normals.size() / 200);
  for (std::size_t i = 0; i < normals.size(); i += stride)
  {
    if (std::abs(normals[i].dot(exclude)) > max_exclude_cos)
      continue;
    int count = 0;
    for (const Eigen::Vector3d& n : normals)
      count += std::abs(n.dot(normals[i])) >= min_cos ? 1 : 0;
    if (count > best_count)
    {
      best_count = count;
      best = normals[i];
    }
  }
  return best;
}

double selfOverlap(const Eigen::Isometry3d& motion, const PointSet& model, const PointGrid& grid, const PointSet& probe,
                   double radius_m, double min_cos)
{
  if (probe.empty())
    return 0.0;
  int matched = 0;
  for (std::size_t i = 0; i < probe.size(); ++i)
  {
    const Eigen::Vector3d p = motion * probe.points[i];
    const Eigen::Vector3d n = motion.linear() * probe.normals[i];
    bool hit = false;
    grid.forEachWithin(p, radius_m, [&](int m) { hit = hit || model.normals[m].dot(n) >= min_cos; });
    matched += hit ? 1 : 0;
  }
  return static_cast<double>(matched) / probe.size();
}

double rotationAngleDeg(const Eigen::Matrix3d& rotation)
{
  return std::acos(std::clamp(0.5 * (rotation.trace() - 1.0), -1.0, 1.0)) / kDegToRad;
}
}  // namespace

ModelSymmetries findModelSymmetries(const PointSet& model, const PointGrid& model_grid, const PointSet& probe,
                                    double match_radius_m, double max_normal_difference_deg,
                                    double min_self_overlap)
{
  ModelSymmetries result;
  if (!model.hasNormals() || !probe.hasNormals() || probe.empty())
    return result;
  const Eigen::Vector3d first = dominantAxis(probe.normals, Eigen::Vector3d::Zero(), 1.0).normalized();
  if (!first.allFinite() || first.squaredNorm() == 0.0)
    return result;
  // The second axis among the normals about perpendicular to the first.
  const Eigen::Vector3d second_raw = dominantAxis(probe.normals, first, std::sin(kAxisToleranceDeg * kDegToRad));
  if (second_raw.squaredNorm() == 0.0)
    return result;
  const Eigen::Vector3d second = (second_raw - second_raw.dot(first) * first).normalized();
  Eigen::Matrix3d axes;
  axes.col(0) = first;
  axes.col(1) = second;
  axes.col(2) = first.cross(second);

  const double axis_cos = std::cos(kAxisToleranceDeg * kDegToRad);
  int along_axes = 0;
  for (const Eigen::Vector3d& n : probe.normals)
    along_axes += (axes.transpose() * n).cwiseAbs().maxCoeff() >= axis_cos ? 1 : 0;
  if (along_axes < kMinBoxNormalFraction * probe.size())
    return result;

  Eigen::Vector3d lower = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d upper = -lower;
  for (const Eigen::Vector3d& p : model.points)
  {
    const Eigen::Vector3d local = axes.transpose() * p;
    lower = lower.cwiseMin(local);
    upper = upper.cwiseMax(local);
  }
  result.box_like = true;
  result.centre_m = axes * (0.5 * (lower + upper));
  result.axes = axes;
  result.half_extents_m = 0.5 * (upper - lower);

  const double min_cos = std::cos(max_normal_difference_deg * kDegToRad);
  std::vector<Eigen::Isometry3d> others;
  for (const Eigen::Matrix3d& box_rotation : axisAlignedRotations())
  {
    if (box_rotation.isIdentity())
      continue;
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    motion.linear() = axes * box_rotation * axes.transpose();
    motion.translation() = result.centre_m - motion.linear() * result.centre_m;
    if (selfOverlap(motion, model, model_grid, probe, match_radius_m, min_cos) >= min_self_overlap)
      result.symmetries.push_back(motion);
    else
      others.push_back(motion);
  }
  // One representative per class: a motion A is in the class of B when
  // B^-1 A is a symmetry.
  for (const Eigen::Isometry3d& motion : others)
  {
    bool known = false;
    for (const Eigen::Isometry3d& representative : result.alternatives)
      for (const Eigen::Isometry3d& symmetry : result.symmetries)
        known = known || rotationAngleDeg((representative * symmetry).linear().transpose() * motion.linear()) < 1.0;
    if (!known)
      result.alternatives.push_back(motion);
  }
  return result;
}

bool samePoseModuloSymmetry(const Eigen::Isometry3d& first, const Eigen::Isometry3d& second,
                            const ModelSymmetries& symmetries, double max_angle_deg, double max_offset_m)
{
  // Every symmetry fixes the centre, so the offset does not depend on it.
  if ((first * symmetries.centre_m - second * symmetries.centre_m).norm() > max_offset_m)
    return false;
  for (const Eigen::Isometry3d& symmetry : symmetries.symmetries)
    if (rotationAngleDeg((first * symmetry).linear().transpose() * second.linear()) <= max_angle_deg)
      return true;
  return false;
}
}  // namespace registration
}  // namespace brick_pose
