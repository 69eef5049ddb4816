#include "brick_pose/pose/brick_selection.h"

#include <algorithm>
#include <map>
#include <array>
#include <cmath>
#include <limits>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace
{
// Projected top faces must interpenetrate by more than this before one brick
// counts as resting on the other: bricks laid edge to edge in a row touch,
// and pose noise of a millimetre or two must not make them cover each other.
constexpr double kMinFootprintOverlapM = 0.005;
// A brick covers another when its top is higher by more than this fraction
// of the lower brick's height (a brick resting on it is a full height above).
constexpr double kCoverHeightFraction = 0.5;
// Shorter vectors have no usable direction.
constexpr double kTinyLength = 1e-9;

using Footprint = std::array<Eigen::Vector2d, 4>;

struct PolicyName
{
  SelectionPolicy policy;
  const char* name;
};

constexpr std::array<PolicyName, 4> kPolicyNames{{
    {SelectionPolicy::kNearest, "nearest"},
    {SelectionPolicy::kHighest, "highest"},
    {SelectionPolicy::kMostConfident, "most_confident"},
    {SelectionPolicy::kPickable, "pickable"},
}};

double heightAlongUp(const DetectedBrick& brick, const Eigen::Vector3d& unit_up)
{
  return unit_up.dot(brick.T_cam_brick.translation());
}

/// An orthonormal basis (u, v) of the plane perpendicular to `unit_up`.
std::pair<Eigen::Vector3d, Eigen::Vector3d> planeBasis(const Eigen::Vector3d& unit_up)
{
  // Any vector not parallel to up seeds the basis; pick the least aligned axis.
  Eigen::Index smallest = 0;
  unit_up.cwiseAbs().minCoeff(&smallest);
  const Eigen::Vector3d seed = Eigen::Vector3d::Unit(smallest);
  const Eigen::Vector3d u = unit_up.cross(seed).normalized();
  return {u, unit_up.cross(u)};
}

/// The brick's top-face rectangle projected along up onto the plane basis.
Footprint footprintOf(const DetectedBrick& brick, const std::pair<Eigen::Vector3d, Eigen::Vector3d>& basis)
{
  const double half_length_m = 0.5 * brick.dimensions_m.x();
  const double half_width_m = 0.5 * brick.dimensions_m.y();
  const std::array<Eigen::Vector2d, 4> corners_in_brick{
      {{half_length_m, half_width_m}, {-half_length_m, half_width_m}, {-half_length_m, -half_width_m},
       {half_length_m, -half_width_m}}};
  Footprint footprint;
  for (std::size_t k = 0; k < corners_in_brick.size(); ++k)
  {
    const Eigen::Vector3d corner_cam =
        brick.T_cam_brick * Eigen::Vector3d(corners_in_brick[k].x(), corners_in_brick[k].y(), 0.0);
    footprint[k] = Eigen::Vector2d(basis.first.dot(corner_cam), basis.second.dot(corner_cam));
  }
  return footprint;
}

/// Overlap length of the two footprints' projections onto `axis`.
double overlapAlong(const Footprint& a, const Footprint& b, const Eigen::Vector2d& axis)
{
  double a_min = std::numeric_limits<double>::max(), a_max = std::numeric_limits<double>::lowest();
  double b_min = a_min, b_max = a_max;
  for (const Eigen::Vector2d& corner : a)
  {
    a_min = std::min(a_min, axis.dot(corner));
    a_max = std::max(a_max, axis.dot(corner));
  }
  for (const Eigen::Vector2d& corner : b)
  {
    b_min = std::min(b_min, axis.dot(corner));
    b_max = std::max(b_max, axis.dot(corner));
  }
  return std::min(a_max, b_max) - std::max(a_min, b_min);
}

/// Separating-axis test of two convex quadrilaterals: the smallest overlap
/// over the edge normals of both (negative when they are apart). For convex
/// shapes a gap along any edge normal means no overlap at all.
double penetrationDepth(const Footprint& a, const Footprint& b)
{
  double depth_m = std::numeric_limits<double>::max();
  for (const Footprint* polygon : {&a, &b})
    for (std::size_t k = 0; k < polygon->size(); ++k)
    {
      const Eigen::Vector2d edge = (*polygon)[(k + 1) % polygon->size()] - (*polygon)[k];
      if (edge.norm() < kTinyLength) continue;  // a face seen edge-on along up
      const Eigen::Vector2d axis = Eigen::Vector2d(-edge.y(), edge.x()).normalized();
      depth_m = std::min(depth_m, overlapAlong(a, b, axis));
    }
  return depth_m;
}

bool restsOn(const DetectedBrick& upper, const DetectedBrick& lower, const Eigen::Vector3d& unit_up,
             const std::pair<Eigen::Vector3d, Eigen::Vector3d>& basis)
{
  const double rise_m = heightAlongUp(upper, unit_up) - heightAlongUp(lower, unit_up);
  if (rise_m <= kCoverHeightFraction * lower.dimensions_m.z()) return false;
  return penetrationDepth(footprintOf(upper, basis), footprintOf(lower, basis)) > kMinFootprintOverlapM;
}

bool matchesType(const DetectedBrick& brick, const std::string& type)
{
  return type.empty() || brick.type_name == type;
}

/// Sorts `indices` so that larger scores come first, ties in input order.
void sortByScoreDescending(std::vector<std::size_t>& indices, const std::vector<double>& score)
{
  std::stable_sort(indices.begin(), indices.end(),
                   [&score](std::size_t a, std::size_t b) { return score[a] > score[b]; });
}

/// Per-brick score for `policy`; larger is better.
std::vector<double> scoresFor(const std::vector<DetectedBrick>& bricks, SelectionPolicy policy,
                              const std::optional<Eigen::Vector3d>& up_in_camera)
{
  std::vector<double> score(bricks.size(), 0.0);
  if (policy == SelectionPolicy::kNearest)
  {
    for (std::size_t i = 0; i < bricks.size(); ++i) score[i] = -bricks[i].T_cam_brick.translation().norm();
    return score;
  }
  if (policy == SelectionPolicy::kMostConfident)
  {
    for (std::size_t i = 0; i < bricks.size(); ++i) score[i] = bricks[i].fitness;
    return score;
  }
  // kHighest and kPickable: height along up; kPickable ranks every pickable
  // brick above every covered one by an offset larger than any height span.
  const Eigen::Vector3d unit_up = resolveUpInCamera(bricks, up_in_camera);
  for (std::size_t i = 0; i < bricks.size(); ++i) score[i] = heightAlongUp(bricks[i], unit_up);
  if (policy == SelectionPolicy::kPickable)
  {
    const auto [lowest, highest] = std::minmax_element(score.begin(), score.end());
    const double covered_penalty = (*highest - *lowest) + 1.0;
    for (std::size_t i = 0; i < bricks.size(); ++i)
      if (isCovered(bricks, i, unit_up)) score[i] -= covered_penalty;
  }
  return score;
}
}  // namespace

SelectionPolicy parseSelectionPolicy(const std::string& name)
{
  if (name.empty()) return SelectionPolicy::kNearest;
  for (const PolicyName& entry : kPolicyNames)
    if (name == entry.name) return entry.policy;
  std::string valid;
  for (const PolicyName& entry : kPolicyNames) valid += std::string(valid.empty() ? "" : ", ") + "'" + entry.name + "'";
  throw ConfigError("unknown selection policy '" + name + "'; valid policies: " + valid);
}

const char* toString(SelectionPolicy policy)
{
  for (const PolicyName& entry : kPolicyNames)
    if (entry.policy == policy) return entry.name;
  return "unknown";
}

Eigen::Vector3d resolveUpInCamera(const std::vector<DetectedBrick>& bricks,
                                  const std::optional<Eigen::Vector3d>& up_in_camera)
{
  if (up_in_camera)
  {
    if (!up_in_camera->allFinite() || up_in_camera->norm() < kTinyLength)
      throw InputError("brick selection: the given up vector must be finite and non-zero");
    return up_in_camera->normalized();
  }
  Eigen::Vector3d sum_of_z_axes = Eigen::Vector3d::Zero();
  for (const DetectedBrick& brick : bricks) sum_of_z_axes += brick.T_cam_brick.linear().col(2);
  if (!sum_of_z_axes.allFinite() || sum_of_z_axes.norm() < kTinyLength)
    throw InputError("brick selection: cannot estimate up from the bricks' z axes (no bricks, or they cancel out); "
                     "pass up_in_camera");
  return sum_of_z_axes.normalized();
}

bool isCovered(const std::vector<DetectedBrick>& bricks, std::size_t index, const Eigen::Vector3d& unit_up)
{
  const auto basis = planeBasis(unit_up);
  for (std::size_t other = 0; other < bricks.size(); ++other)
    if (other != index && restsOn(bricks[other], bricks[index], unit_up, basis)) return true;
  return false;
}

std::vector<bool> pickableMask(const std::vector<DetectedBrick>& bricks,
                               const std::optional<Eigen::Vector3d>& up_in_camera)
{
  if (bricks.empty()) return {};
  const Eigen::Vector3d unit_up = resolveUpInCamera(bricks, up_in_camera);
  std::vector<bool> pickable(bricks.size());
  for (std::size_t i = 0; i < bricks.size(); ++i) pickable[i] = !isCovered(bricks, i, unit_up);
  return pickable;
}

std::vector<std::size_t> orderBricks(const std::vector<DetectedBrick>& bricks, SelectionPolicy policy,
                                     const std::string& type, const std::optional<Eigen::Vector3d>& up_in_camera)
{
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < bricks.size(); ++i)
    if (matchesType(bricks[i], type)) order.push_back(i);
  if (order.empty()) return order;
  sortByScoreDescending(order, scoresFor(bricks, policy, up_in_camera));
  return order;
}

std::optional<std::size_t> selectBrick(const std::vector<DetectedBrick>& bricks, SelectionPolicy policy,
                                       const std::string& type, const std::optional<Eigen::Vector3d>& up_in_camera)
{
  const std::vector<std::size_t> order = orderBricks(bricks, policy, type, up_in_camera);
  if (order.empty()) return std::nullopt;
  const bool pickable_only = policy == SelectionPolicy::kPickable;
  const Eigen::Vector3d unit_up = pickable_only ? resolveUpInCamera(bricks, up_in_camera) : Eigen::Vector3d::Zero();
  for (const std::size_t index : order)
    if (bricks[index].complete_face && (!pickable_only || !isCovered(bricks, index, unit_up))) return index;
  return std::nullopt;
}

std::size_t chooseBrick(const std::vector<DetectedBrick>& bricks, SelectionPolicy policy, const std::string& type,
                        const std::optional<Eigen::Vector3d>& up_in_camera)
{
  if (const std::optional<std::size_t> chosen = selectBrick(bricks, policy, type, up_in_camera)) return *chosen;
  throw InputError("no " + (type.empty() ? std::string() : type + " ") + "brick" +
                   (policy == SelectionPolicy::kPickable ? " that nothing rests on" : "") +
                   " with its whole top face in view in the latest frame (seen: " + describeBricks(bricks) + ")");
}

std::size_t findBrickById(const std::vector<DetectedBrick>& bricks, std::uint32_t id)
{
  std::string ids;
  for (std::size_t i = 0; i < bricks.size(); ++i)
  {
    if (bricks[i].id == id) return i;
    ids += (ids.empty() ? "" : ", ") + std::to_string(bricks[i].id);
  }
  throw InputError("no brick with id " + std::to_string(id) + " in the latest frame (ids: " +
                   (ids.empty() ? "none" : ids) + ")");
}

std::string describeBricks(const std::vector<DetectedBrick>& bricks)
{
  std::map<std::string, int> counts;
  for (const DetectedBrick& brick : bricks)
    ++counts[brick.type_name + (brick.complete_face ? " complete" : " partial")];
  std::string text;
  for (const auto& [kind, count] : counts) text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + kind;
  return text.empty() ? "none" : text;
}
}  // namespace brick_pose
