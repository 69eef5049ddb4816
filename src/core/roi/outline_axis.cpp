#include "brick_pose/roi/outline_axis.h"

#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/angles.h"

namespace brick_pose
{
namespace
{

/// A straight stretch of the outline on the plane: its angle modulo a
/// quarter turn, in [0, pi/2), and its length.
struct Stretch
{
  double angle_rad = 0.0;
  double length_m = 0.0;
};

/// The angle (modulo a quarter turn) `stretches` agree on within
/// `agree_rad` of each other: the window holding most length, refined to
/// the length-weighted circular mean of its members.
double peakAngle(const std::vector<Stretch>& stretches, double agree_rad, double& held_m)
{
  held_m = 0.0;
  double best_angle = 0.0;
  for (const Stretch& centre : stretches)
  {
    // Angles modulo a quarter turn are points on a circle at 4x the angle.
    double held = 0.0, sum_cos = 0.0, sum_sin = 0.0;
    for (const Stretch& other : stretches)
    {
      const double wrapped = std::remainder(other.angle_rad - centre.angle_rad, 0.5 * kPi);
      if (std::abs(wrapped) > agree_rad) continue;
      held += other.length_m;
      sum_cos += other.length_m * std::cos(4.0 * other.angle_rad);
      sum_sin += other.length_m * std::sin(4.0 * other.angle_rad);
    }
    if (held > held_m)
    {
      held_m = held;
      best_angle = 0.25 * std::atan2(sum_sin, sum_cos);
    }
  }
  return best_angle;
}
}  // namespace

std::optional<OutlineAxis> dominantOutlineAxis(const RgbdFrame& frame, const Segment& segment,
                                               const PlaneFit& plane, const OutlineAxisParams& params)
{
  if (!plane.valid || segment.mask.empty()) return std::nullopt;
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(segment.mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
  // Any unit vector on the plane as the angles' zero.
  const Eigen::Vector3d& normal = plane.normal;
  Eigen::Vector3d zero = normal.unitOrthogonal();
  const Eigen::Vector3d quarter = normal.cross(zero).normalized();
  std::vector<Stretch> stretches;
  double total_m = 0.0;
  const cv::Point offset = segment.bounding_box_px.tl();
  // A side along the image border is where the view ends, not a brick's
  // edge: a layer cut off at an image corner would otherwise vote for the
  // image's axes.
  auto onBorder = [&](const cv::Point& p) {
    return p.x <= 1 || p.y <= 1 || p.x >= frame.width_px() - 2 || p.y >= frame.height_px() - 2;
  };
  for (const auto& contour : contours)
  {
    std::vector<cv::Point> polygon;
    cv::approxPolyDP(contour, polygon, params.simplify_px, true);
    for (std::size_t k = 0; polygon.size() >= 2 && k < polygon.size(); ++k)
    {
      const cv::Point a = polygon[k] + offset, b = polygon[(k + 1) % polygon.size()] + offset;
      if (onBorder(a) && onBorder(b)) continue;
      if (cv::norm(b - a) < params.min_stretch_px) continue;
      Eigen::Vector3d a_m, b_m;
      if (!plane.intersectRay(frame.camera.ray(a.x, a.y), a_m) || !plane.intersectRay(frame.camera.ray(b.x, b.y), b_m))
        continue;
      const Eigen::Vector3d along = b_m - a_m;
      const double length_m = along.norm();
      if (!(length_m > 0.0)) continue;
      double angle = std::atan2(along.dot(quarter), along.dot(zero));
      angle = std::fmod(angle + 2.0 * kPi, 0.5 * kPi);
      stretches.push_back({angle, length_m});
      total_m += length_m;
    }
  }
  if (stretches.empty() || !(total_m > 0.0)) return std::nullopt;
  double held_m = 0.0;
  const double angle = peakAngle(stretches, params.agree_deg * kDegToRad, held_m);
  OutlineAxis axis;
  axis.support = held_m / total_m;
  if (axis.support < params.min_support) return std::nullopt;
  axis.direction = (std::cos(angle) * zero + std::sin(angle) * quarter).normalized();
  return axis;
}
}  // namespace brick_pose
