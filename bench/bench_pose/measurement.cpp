#include "bench_pose/measurement.h"

#include <cmath>
#include <map>
#include <optional>

namespace brick_pose
{
namespace pose_bench
{
namespace
{
constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;

double angleBetweenDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return std::atan2(a.cross(b).norm(), a.dot(b)) * kDegPerRad;
}

/// Length of the component of `offset_m` along the face (normal removed), mm.
double inPlaneMm(const Eigen::Vector3d& offset_m, const Eigen::Vector3d& unit_normal)
{
  return 1000.0 * (offset_m - unit_normal * unit_normal.dot(offset_m)).norm();
}

/// Centroid on the fitted plane of the area the segment's pixels cover. Each
/// pixel's ray is cut with the plane (no depth noise) and weighted by the
/// area it covers there, which grows as z^3 on a plane (z^2 for the solid
/// angle, z again for the foreshortening), so far parts of an oblique face
/// are not under-weighted as in a plain mean of the points.
std::optional<Eigen::Vector3d> maskAreaCentroid(const BrickCandidate& candidate, const PinholeCamera& camera)
{
  Eigen::Vector3d weighted_sum = Eigen::Vector3d::Zero();
  double weight_sum = 0.0;
  for (const int pixel : candidate.pixel_indices)
  {
    Eigen::Vector3d hit_m;
    if (!candidate.plane.intersectRay(camera.ray(pixel % camera.width_px, pixel / camera.width_px), hit_m)) continue;
    const double area_weight = hit_m.z() * hit_m.z() * hit_m.z();
    weighted_sum += area_weight * hit_m;
    weight_sum += area_weight;
  }
  if (!(weight_sum > 0.0)) return std::nullopt;
  return weighted_sum / weight_sum;
}
}  // namespace

const sim::BrickTruth* matchTruth(const BrickCandidate& candidate, const sim::SyntheticFrame& frame,
                                  std::string& reason)
{
  std::map<int, int> top_face_pixels;  // instance -> count
  const auto* instances = frame.instance_labels.ptr<std::uint16_t>(0);
  const auto* faces = frame.face_labels.ptr<std::uint8_t>(0);
  for (const int pixel : candidate.pixel_indices)
    if (instances[pixel] != 0 && faces[pixel] == static_cast<std::uint8_t>(sim::CuboidFace::kTop))
      ++top_face_pixels[instances[pixel]];
  int instance = 0, most = 0;
  for (const auto& [id, count] : top_face_pixels)
    if (count > most)
    {
      instance = id;
      most = count;
    }
  if (instance == 0 || 2 * most < static_cast<int>(candidate.pixel_indices.size()))
  {
    reason = "not mostly one top face";
    return nullptr;
  }
  const sim::BrickTruth& truth = frame.truth[static_cast<std::size_t>(instance - 1)];
  if (truth.type != candidate.type_name)
  {
    reason = "wrong type";
    return nullptr;
  }
  return &truth;
}

MeasurementError measurementErrorOf(const BrickCandidate& candidate, const sim::BrickTruth& truth,
                                    const PinholeCamera& camera)
{
  const Eigen::Vector3d true_x = truth.camera_T_brick.linear().col(0);
  const Eigen::Vector3d true_z = truth.camera_T_brick.linear().col(2);
  const Eigen::Vector3d true_centre = truth.camera_T_brick.translation();
  MeasurementError error;
  const double direction_deg = angleBetweenDeg(candidate.t2_m - candidate.t1_m, true_x);
  error.t1_t2_direction_deg = std::min(direction_deg, 180.0 - direction_deg);
  error.normal_deg = angleBetweenDeg(candidate.normal, true_z);
  const Eigen::Vector3d midpoint_offset = 0.5 * (candidate.t1_m + candidate.t2_m) - true_centre;
  error.midpoint_in_plane_mm = inPlaneMm(midpoint_offset, true_z);
  error.plane_offset_mm = 1000.0 * std::abs(true_z.dot(candidate.plane.centroid_m - true_centre));
  error.length_error_mm = 1000.0 * (candidate.length_m - truth.dimensions_m.x());
  error.width_error_mm = 1000.0 * (candidate.width_m - truth.dimensions_m.y());
  error.fill_ratio = candidate.fill_ratio;
  error.point_centroid_in_plane_mm = inPlaneMm(candidate.plane.centroid_m - true_centre, true_z);
  error.midpoint_camera_x_mm = 1000.0 * midpoint_offset.x();
  error.midpoint_camera_y_mm = 1000.0 * midpoint_offset.y();
  if (const auto area_centroid = maskAreaCentroid(candidate, camera))
    error.mask_area_centroid_in_plane_mm = inPlaneMm(*area_centroid - true_centre, true_z);
  return error;
}

std::string exclusionReason(const BrickCandidate& candidate, const sim::BrickTruth& truth, bool duplicate)
{
  if (duplicate) return "second candidate on the same brick";
  if (truth.visible_fraction < kMinVisibleFraction) return "top face less than 60% visible";
  if (!candidate.complete) return "front end flags the face incomplete (size off, or an edge cut by an occluder / the image border)";
  return "";
}
}  // namespace pose_bench
}  // namespace brick_pose
