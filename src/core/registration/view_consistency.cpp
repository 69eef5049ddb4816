#include "brick_pose/registration/view_consistency.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace registration
{
namespace
{
// Angular search radius of a line of sight over the match radius at the
// point's range: about half a scan spacing, so that the nearest line of sight
// found belongs to the surface point the model point would hide.
constexpr double kSightRadiusPerMatchRadius = 0.6;

/// Rows: two directions across the mean line of sight, then along it.
Eigen::Matrix3d sightFrame(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& viewpoint)
{
  Eigen::Vector3d along = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points)
    along += (p - viewpoint).normalized();
  if (!(along.norm() > 0.0) || !along.allFinite())
    along = Eigen::Vector3d::UnitZ();
  along.normalize();
  const Eigen::Vector3d across = along.unitOrthogonal();
  Eigen::Matrix3d frame;
  frame.row(0) = across.transpose();
  frame.row(1) = along.cross(across).transpose();
  frame.row(2) = along.transpose();
  return frame;
}
}  // namespace

ViewConsistency::ViewConsistency(const PointSet& model, const PointSet& model_sample, const PointSet& target,
                                 std::vector<int> trusted, const ViewConsistencyParams& params)
  : model_(model),
    model_sample_(model_sample),
    target_(target),
    params_(params),
    seen_radius_m_(std::max(params.match_radius_m, params.seen_radius_m)),
    min_normal_cos_(std::cos(params.max_normal_difference_deg * kDegToRad)),
    trusted_(std::move(trusted)),
    model_grid_(model.points, params.match_radius_m)
{
  for (int i : trusted_)
    trusted_points_.push_back(target.points[i]);
  target_grid_ = PointGrid(target.points, seen_radius_m_);
  sight_frame_ = sightFrame(trusted_points_, params.viewpoint_m);
  std::vector<double> ranges;
  for (const Eigen::Vector3d& p : trusted_points_)
  {
    const Eigen::Vector3d local = sight_frame_ * (p - params.viewpoint_m);
    if (!(local.z() > 0.0))
      continue;  // behind the viewpoint: on no line of sight from it
    sight_points_.emplace_back(local.x() / local.z(), local.y() / local.z(), 0.0);
    sight_range_m_.push_back((p - params.viewpoint_m).norm());
    ranges.push_back(sight_range_m_.back());
  }
  if (!ranges.empty())
  {
    std::nth_element(ranges.begin(), ranges.begin() + ranges.size() / 2, ranges.end());
    const double median_range_m = ranges[ranges.size() / 2];
    if (median_range_m > 0.0)
      sight_radius_ = kSightRadiusPerMatchRadius * params.match_radius_m / median_range_m;
  }
  if (sight_radius_ > 0.0 && std::isfinite(sight_radius_))
    sight_grid_ = PointGrid(sight_points_, sight_radius_);
}

bool ViewConsistency::targetPointMatched(int target_index, const Eigen::Isometry3d& target_to_model) const
{
  const Eigen::Vector3d q = target_to_model * target_.points[target_index];
  const Eigen::Vector3d normal = target_to_model.linear() * target_.normals[target_index];
  bool matched = false;
  model_grid_.forEachWithin(q, params_.match_radius_m, [&](int m) {
    matched = matched || model_.normals[m].dot(normal) >= min_normal_cos_;
  });
  return matched;
}

double ViewConsistency::targetCoverage(const Eigen::Isometry3d& model_to_target, double score_to_beat,
                                       int max_points) const
{
  const int all = static_cast<int>(trusted_.size());
  if (all == 0)
    return 0.0;
  // Every stride-th point: the scan's order runs over its whole extent.
  const int stride = max_points > 0 ? std::max(1, all / max_points) : 1;
  const int n = (all + stride - 1) / stride;
  const Eigen::Isometry3d target_to_model = model_to_target.inverse();
  const double count_to_beat = score_to_beat * n;
  int matched = 0;
  for (int k = 0; k < n; ++k)
  {
    if (targetPointMatched(trusted_[k * stride], target_to_model))
      ++matched;
    else if (matched + (n - k - 1) <= count_to_beat)
      return static_cast<double>(matched) / n;
  }
  return static_cast<double>(matched) / n;
}

std::vector<int> ViewConsistency::facingModelPoints(const Eigen::Isometry3d& model_to_target, double min_cos) const
{
  std::vector<int> facing;
  for (std::size_t i = 0; i < model_sample_.size(); ++i)
  {
    const Eigen::Vector3d p = model_to_target * model_sample_.points[i];
    const Eigen::Vector3d to_viewpoint = (params_.viewpoint_m - p).normalized();
    if ((model_to_target.linear() * model_sample_.normals[i]).dot(to_viewpoint) >= min_cos)
      facing.push_back(static_cast<int>(i));
  }
  return facing;
}

double ViewConsistency::modelCoverage(const Eigen::Isometry3d& model_to_target, const std::vector<int>& expected) const
{
  if (expected.empty())
    return 0.0;
  int seen = 0;
  for (int i : expected)
  {
    const Eigen::Vector3d p = model_to_target * model_sample_.points[i];
    const Eigen::Vector3d normal = model_to_target.linear() * model_sample_.normals[i];
    bool matched = false;
    target_grid_.forEachWithin(p, seen_radius_m_, [&](int t) {
      matched = matched || target_.normals[t].dot(normal) >= min_normal_cos_;
    });
    seen += matched ? 1 : 0;
  }
  return static_cast<double>(seen) / expected.size();
}

double ViewConsistency::freeSpaceViolation(const Eigen::Isometry3d& model_to_target,
                                           const std::vector<int>& expected) const
{
  if (expected.empty() || !(sight_radius_ > 0.0))
    return 0.0;
  int violations = 0;
  for (int i : expected)
  {
    const Eigen::Vector3d p = model_to_target * model_sample_.points[i];
    const Eigen::Vector3d local = sight_frame_ * (p - params_.viewpoint_m);
    if (!(local.z() > 0.0))
      continue;
    const Eigen::Vector3d sight(local.x() / local.z(), local.y() / local.z(), 0.0);
    // The scan point on the nearest line of sight: what the camera saw there.
    int nearest = -1;
    double nearest_sq = std::numeric_limits<double>::infinity();
    sight_grid_.forEachWithin(sight, sight_radius_, [&](int s) {
      const double d_sq = (sight_points_[s] - sight).squaredNorm();
      if (d_sq < nearest_sq)
      {
        nearest_sq = d_sq;
        nearest = s;
      }
    });
    if (nearest >= 0 && sight_range_m_[nearest] > (p - params_.viewpoint_m).norm() + params_.free_space_margin_m)
      ++violations;
  }
  return static_cast<double>(violations) / expected.size();
}

ViewScore ViewConsistency::evaluate(const Eigen::Isometry3d& model_to_target) const
{
  ViewScore score;
  score.target_coverage = targetCoverage(model_to_target);
  const std::vector<int> expected = facingModelPoints(model_to_target, params_.min_visible_cos);
  score.expected_visible_points = static_cast<int>(expected.size());
  score.model_coverage = modelCoverage(model_to_target, expected);
  score.free_space_violation = freeSpaceViolation(model_to_target, expected);
  return score;
}
}  // namespace registration
}  // namespace brick_pose
