#include "brick_pose/roi/up_direction.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Eigen/Eigenvalues>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace
{

/// Small deterministic generator (the estimate must not vary run to run).
class SplitMix
{
public:
  explicit SplitMix(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next()
  {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }

private:
  std::uint64_t state_;
};

struct Sample
{
  Eigen::Vector3d point;
  double tolerance_m;
};

bool onPlane(const Sample& sample, const Eigen::Vector3d& normal, double offset)
{
  return std::abs(normal.dot(sample.point) + offset) <= sample.tolerance_m;
}
}  // namespace

void UpDirectionParams::validate() const
{
  const ParamCheck check("up direction");
  check.require(stride_px >= 1, "stride_px", "must be >= 1");
  check.require(iterations >= 1, "iterations", "must be >= 1");
  check.require(score_points >= 10, "score_points", "must be >= 10");
  check.require(inlier_distance_m > 0.0, "inlier_distance_m", "must be > 0");
  check.require(inlier_distance_per_m2 >= 0.0, "inlier_distance_per_m2", "must be >= 0");
  check.require(min_support_fraction > 0.0 && min_support_fraction <= 1.0, "min_support_fraction", "must be in (0, 1]");
  check.require(cluster_angle_deg > 0.0 && cluster_angle_deg < 90.0, "cluster_angle_deg", "must be in (0, 90)");
}

UpDirection estimateSupportPlaneUp(const RgbdFrame& frame, const UpDirectionParams& params)
{
  UpDirection result;
  std::vector<Sample> samples;
  for (int v = params.stride_px / 2; v < frame.height_px(); v += params.stride_px)
    for (int u = params.stride_px / 2; u < frame.width_px(); u += params.stride_px)
    {
      const float z = frame.depthAt(u, v);
      if (std::isnan(z) || z <= 0.0f) continue;
      samples.push_back({frame.camera.backProject(u, v, z),
                         std::max(params.inlier_distance_m, params.inlier_distance_per_m2 * z * z)});
    }
  if (samples.size() < 30) return result;

  SplitMix random(0x5EED5EEDULL);
  std::vector<std::size_t> scoring(std::min<std::size_t>(samples.size(), params.score_points));
  for (std::size_t& index : scoring) index = random.below(samples.size());
  int best_count = -1;
  Eigen::Vector3d best_normal = Eigen::Vector3d::UnitZ();
  double best_offset = 0.0;
  for (int iteration = 0; iteration < params.iterations; ++iteration)
  {
    const Eigen::Vector3d& a = samples[random.below(samples.size())].point;
    const Eigen::Vector3d& b = samples[random.below(samples.size())].point;
    const Eigen::Vector3d& c = samples[random.below(samples.size())].point;
    Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.norm() < 1e-9) continue;
    normal.normalize();
    const double offset = -normal.dot(a);
    int count = 0;
    for (const std::size_t index : scoring) count += onPlane(samples[index], normal, offset) ? 1 : 0;
    if (count > best_count)
    {
      best_count = count;
      best_normal = normal;
      best_offset = offset;
    }
  }
  if (best_count <= 0) return result;

  // Least-squares refit on every inlier of the best hypothesis.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::size_t inliers = 0;
  for (const Sample& sample : samples)
    if (onPlane(sample, best_normal, best_offset))
    {
      centroid += sample.point;
      ++inliers;
    }
  if (inliers < 3) return result;
  centroid /= static_cast<double>(inliers);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Sample& sample : samples)
    if (onPlane(sample, best_normal, best_offset))
      covariance += (sample.point - centroid) * (sample.point - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  Eigen::Vector3d normal = solver.eigenvectors().col(0);
  if (normal.dot(centroid) > 0.0) normal = -normal;  // toward the camera
  result.support_fraction = static_cast<double>(inliers) / samples.size();
  if (result.support_fraction < params.min_support_fraction) return result;
  result.up = normal.normalized();
  result.source = UpSource::kSupportPlane;
  result.has_support_plane = true;
  result.support_normal = result.up;
  result.support_offset_m = -result.up.dot(centroid);
  return result;
}

Eigen::Vector4d xyPlaneInCamera(const Eigen::Isometry3d& camera_T_frame)
{
  const Eigen::Vector3d normal = camera_T_frame.linear().col(2);
  Eigen::Vector4d plane;
  plane << normal, -normal.dot(camera_T_frame.translation());
  return plane;
}

UpDirection givenSupport(const Eigen::Vector4d& plane)
{
  UpDirection given;
  const double norm = plane.head<3>().norm();
  if (!plane.allFinite() || !(norm > 1e-9)) return given;
  given.up = plane.head<3>() / norm;
  given.source = UpSource::kGiven;
  given.has_support_plane = true;
  given.support_given = true;
  given.support_normal = given.up;
  given.support_offset_m = plane[3] / norm;
  given.support_fraction = 0.0;
  return given;
}

UpDirection withGivenSupport(UpDirection up, const Eigen::Vector4d& plane)
{
  const UpDirection given = givenSupport(plane);
  if (!given.known()) return up;
  if (!up.known()) return given;
  up.has_support_plane = true;
  up.support_given = true;
  up.support_normal = given.support_normal;
  up.support_offset_m = given.support_offset_m;
  up.support_fraction = 0.0;
  return up;
}

UpDirection dominantFaceNormal(const std::vector<Eigen::Vector3d>& normals, const std::vector<double>& weights,
                               const UpDirectionParams& params)
{
  UpDirection result;
  const double min_cos = std::cos(params.cluster_angle_deg * kDegToRad);
  double best_weight = 0.0;
  for (std::size_t i = 0; i < normals.size() && i < weights.size(); ++i)
  {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double weight = 0.0;
    for (std::size_t j = 0; j < normals.size() && j < weights.size(); ++j)
      if (normals[i].dot(normals[j]) >= min_cos)
      {
        sum += weights[j] * normals[j];
        weight += weights[j];
      }
    if (weight > best_weight && sum.norm() > 0.0)
    {
      best_weight = weight;
      result.up = sum.normalized();
      result.source = UpSource::kFaceNormals;
    }
  }
  return result;
}

std::string toString(UpSource source)
{
  switch (source)
  {
    case UpSource::kGiven: return "given (tf)";
    case UpSource::kSupportPlane: return "the supporting plane";
    case UpSource::kFaceNormals: return "the faces' dominant normal";
    case UpSource::kUnknown:
    default: return "unknown";
  }
}
}  // namespace brick_pose
