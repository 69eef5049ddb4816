#include "brick_pose/registration/coplanar_base.h"

#include <algorithm>
#include <cmath>

namespace brick_pose
{
namespace registration
{
namespace
{
/// Indices whose score is at least `fraction` of the best score; drawing among
/// them instead of taking the best keeps bases wide without always landing on
/// the same extreme points (which the target may lack, e.g. eroded corners).
template <typename Score>
int drawNearBest(int count, double fraction, std::mt19937_64& rng, Score&& score)
{
  double best = 0.0;
  std::vector<std::pair<int, double>> scored;
  for (int i = 0; i < count; ++i)
  {
    const double s = score(i);
    if (s > 0.0)
    {
      scored.emplace_back(i, s);
      best = std::max(best, s);
    }
  }
  std::vector<int> near_best;
  for (const auto& [index, s] : scored)
    if (s >= fraction * best)
      near_best.push_back(index);
  if (near_best.empty())
    return -1;
  return near_best[std::uniform_int_distribution<std::size_t>(0, near_best.size() - 1)(rng)];
}

/// Whether some two of the base's normals differ by at least min_spread_rad
/// (always true without a requirement or without normals).
bool spansNormals(const CoplanarBase& base, double min_spread_rad)
{
  if (!(min_spread_rad > 0.0) || base.normals[0].squaredNorm() == 0.0)
    return true;
  const double max_cos = std::cos(min_spread_rad);
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (base.normals[i].dot(base.normals[j]) <= max_cos)
        return true;
  return false;
}
}  // namespace

double CoplanarBase::segmentAngle_rad() const
{
  const Eigen::Vector3d u = (points[1] - points[0]).normalized();
  const Eigen::Vector3d v = (points[3] - points[2]).normalized();
  return std::acos(std::clamp(u.dot(v), -1.0, 1.0));
}

bool crossingRatios(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& d, double& t1, double& t2)
{
  const Eigen::Vector3d u = b - a;
  const Eigen::Vector3d v = d - c;
  const Eigen::Vector3d w = a - c;
  const double uu = u.dot(u);
  const double uv = u.dot(v);
  const double vv = v.dot(v);
  const double uw = u.dot(w);
  const double vw = v.dot(w);
  const double denominator = uu * vv - uv * uv;
  if (!(denominator > 1e-12 * uu * vv))
    return false;
  t1 = (uv * vw - vv * uw) / denominator;
  t2 = (uu * vw - uv * uw) / denominator;
  return true;
}

std::optional<CoplanarBase> drawCoplanarBase(const PointSet& cloud, const BaseSelectionLimits& limits,
                                             std::mt19937_64& rng)
{
  const std::vector<Eigen::Vector3d>& p = cloud.points;
  const int n = static_cast<int>(p.size());
  if (n < 4)
    return std::nullopt;
  const double max_sq = limits.max_diameter_m * limits.max_diameter_m;
  const double lo = limits.min_crossing_ratio;
  const double hi = 1.0 - limits.min_crossing_ratio;
  std::uniform_int_distribution<int> pick(0, n - 1);

  for (int attempt = 0; attempt < limits.attempts; ++attempt)
  {
    const int a = pick(rng);
    const int b = drawNearBest(n, 0.75, rng, [&](int i) {
      const double d_sq = (p[i] - p[a]).squaredNorm();
      return d_sq <= max_sq ? std::sqrt(d_sq) : 0.0;
    });
    if (b < 0)
      continue;
    const Eigen::Vector3d ab = (p[b] - p[a]).normalized();
    const int c = drawNearBest(n, 0.6, rng, [&](int i) {
      if ((p[i] - p[a]).squaredNorm() > max_sq || (p[i] - p[b]).squaredNorm() > max_sq)
        return 0.0;
      return (p[i] - p[a]).cross(ab).norm();  // distance to the line a-b
    });
    if (c < 0)
      continue;
    const Eigen::Vector3d normal = (p[b] - p[a]).cross(p[c] - p[a]).normalized();
    const int d = drawNearBest(n, 0.6, rng, [&](int i) {
      if (i == a || i == b || i == c)
        return 0.0;
      if (std::abs((p[i] - p[a]).dot(normal)) > limits.coplanar_tolerance_m)
        return 0.0;
      if ((p[i] - p[a]).squaredNorm() > max_sq || (p[i] - p[b]).squaredNorm() > max_sq ||
          (p[i] - p[c]).squaredNorm() > max_sq)
        return 0.0;
      double t1 = 0.0;
      double t2 = 0.0;
      if (!crossingRatios(p[a], p[b], p[c], p[i], t1, t2) || t1 < lo || t1 > hi || t2 < lo || t2 > hi)
        return 0.0;
      return (p[i] - p[c]).norm();  // the longer the second diagonal, the better
    });
    if (d < 0)
      continue;

    CoplanarBase base;
    base.indices = {{a, b, c, d}};
    for (int k = 0; k < 4; ++k)
    {
      base.points[k] = p[base.indices[k]];
      base.normals[k] = cloud.hasNormals() ? cloud.normals[base.indices[k]].normalized() : Eigen::Vector3d::Zero();
    }
    if (!spansNormals(base, limits.min_normal_spread_rad))
      continue;
    crossingRatios(base.points[0], base.points[1], base.points[2], base.points[3], base.t1, base.t2);
    return base;
  }
  return std::nullopt;
}
}  // namespace registration
}  // namespace brick_pose
