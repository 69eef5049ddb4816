#include "brick_pose/registration/box_view_checks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace registration
{
namespace
{

const char* axisName(int axis)
{
  static const char* const kNames[3] = {"first", "second", "third"};
  return kNames[axis];
}

std::string formatMetres(double value_m)
{
  std::ostringstream out;
  out.precision(3);
  out << value_m << " m";
  return out.str();
}

std::string formatDegrees(double value_deg)
{
  std::ostringstream out;
  out.precision(2);
  out << value_deg << " deg";
  return out.str();
}

/// Span of `values` without their `trim` smallest and largest (selected,
/// not sorted: the turn search calls this a hundred times per face).
double trimmedSpan(std::vector<double> values, int trim)
{
  if (values.size() <= static_cast<std::size_t>(2 * trim + 1))
    return 0.0;
  const auto low = values.begin() + trim;
  std::nth_element(values.begin(), low, values.end());
  const double lower = *low;
  const auto high = values.end() - 1 - trim;
  std::nth_element(low, high, values.end());
  return *high - lower;
}

/// Angle (degrees) between the least-squares plane of `points` and the
/// plane normal to `axis` (points in box coordinates).
double planeTiltDeg(const std::vector<Eigen::Vector3d>& points, int axis)
{
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points)
    mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points)
    covariance += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d normal = solver.eigenvectors().col(0);  // smallest variance
  return std::acos(std::min(1.0, std::abs(normal(axis)))) / kDegToRad;
}
/// Angle (degrees) by which the face's points (box coordinates, on the face
/// across `axis`) are turned within the face from the pose's face: the turn
/// within +-search_deg of the least-area rectangle around them (their
/// spans trimmed by `trim` points at each end). A rectangle's own turn is
/// the least-area one; a square's points give no axes by their spread, but
/// their bounding rectangle grows by (cos + sin) when turned.
double inPlaneTurnDeg(const std::vector<Eigen::Vector3d>& points, int axis, double search_deg, double step_deg,
                      int trim)
{
  const int u_axis = (axis + 1) % 3;
  const int v_axis = (axis + 2) % 3;
  std::vector<double> u(points.size());
  std::vector<double> v(points.size());
  double best_area = std::numeric_limits<double>::infinity();
  double best_deg = 0.0;
  const int steps = static_cast<int>(std::ceil(search_deg / step_deg));
  for (int step = -steps; step <= steps; ++step)
  {
    const double angle_rad = step * step_deg * kDegToRad;
    const double c = std::cos(angle_rad);
    const double s = std::sin(angle_rad);
    for (std::size_t k = 0; k < points.size(); ++k)
    {
      u[k] = c * points[k](u_axis) + s * points[k](v_axis);
      v[k] = -s * points[k](u_axis) + c * points[k](v_axis);
    }
    const double area = trimmedSpan(u, trim) * trimmedSpan(v, trim);
    // Ties (a coarse cloud) go to the smaller turn.
    if (area < best_area - 1e-12 || (area <= best_area + 1e-12 && std::abs(step) < std::abs(best_deg / step_deg)))
    {
      best_area = area;
      best_deg = step * step_deg;
    }
  }
  return best_deg;
}
}  // namespace

void BoxViewCheckParams::validate() const
{
  const ParamCheck check("BoxViewCheckParams");
  check.require(viewpoint_m.allFinite(), "viewpoint_m");
  check.require(min_facing_cos >= 0.0 && min_facing_cos <= 1.0, "min_facing_cos");
  check.require(face_normal_deg > 0.0 && face_normal_deg < 90.0, "face_normal_deg");
  check.require(max_face_distance_m > 0.0 && std::isfinite(max_face_distance_m), "max_face_distance_m");
  check.require(min_face_points >= 3, "min_face_points");
  check.require(min_turn_face_points >= 3, "min_turn_face_points");
  check.require(max_span_shortfall_m >= 0.0 && std::isfinite(max_span_shortfall_m), "max_span_shortfall_m");
  check.require(max_span_shortfall_fraction >= 0.0 && max_span_shortfall_fraction <= 1.0,
                "max_span_shortfall_fraction");
  check.require(span_trim_points >= 0, "span_trim_points");
  check.require(max_face_tilt_deg > 0.0 && max_face_tilt_deg < 90.0, "max_face_tilt_deg");
  check.require(turn_step_deg > 0.0 && turn_step_deg <= 10.0, "turn_step_deg");
  check.require(turn_search_deg >= turn_step_deg && turn_search_deg <= 45.0, "turn_search_deg");
  check.require(max_face_turn_deg > 0.0 && max_face_turn_deg < turn_search_deg, "max_face_turn_deg");
}

BoxViewCheck checkBoxView(const Eigen::Isometry3d& pose, const ModelBox& box, const PointSet& scan,
                          const std::vector<int>& trusted, const BoxViewCheckParams& params)
{
  params.validate();
  BoxViewCheck check;
  if (!scan.hasNormals() || !(box.half_extents_m.minCoeff() > 0.0))
    return check;
  const Eigen::Isometry3d target_to_model = pose.inverse();
  const Eigen::Matrix3d to_box = box.axes.transpose();
  const double min_normal_cos = std::cos(params.face_normal_deg * kDegToRad);

  std::vector<Eigen::Vector3d> local(trusted.size());
  std::vector<Eigen::Vector3d> local_normal(trusted.size());
  for (std::size_t k = 0; k < trusted.size(); ++k)
  {
    const int i = trusted[k];
    local[k] = to_box * (target_to_model * scan.points[i] - box.centre_m);
    local_normal[k] = to_box * (target_to_model.linear() * scan.normals[i]);
  }

  // Axes along which an edge of a facing face runs: the scan must span them.
  bool spanned[3] = {false, false, false};
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {-1.0, 1.0})
    {
      const Eigen::Vector3d face_centre = box.centre_m + sign * box.half_extents_m(axis) * box.axes.col(axis);
      const Eigen::Vector3d normal = pose.linear() * (sign * box.axes.col(axis));
      const Eigen::Vector3d to_viewpoint = (params.viewpoint_m - pose * face_centre).normalized();
      if (!(normal.dot(to_viewpoint) >= params.min_facing_cos))
        continue;
      for (int other = 0; other < 3; ++other)
        spanned[other] = spanned[other] || other != axis;

      // The face's own scan points: their plane against the pose's face.
      std::vector<Eigen::Vector3d> on_face;
      for (std::size_t k = 0; k < local.size(); ++k)
        if (sign * local_normal[k](axis) >= min_normal_cos &&
            std::abs(local[k](axis) - sign * box.half_extents_m(axis)) <= params.max_face_distance_m)
          on_face.push_back(local[k]);
      if (static_cast<int>(on_face.size()) < params.min_face_points)
        continue;
      const double turn_deg = std::abs(
          inPlaneTurnDeg(on_face, axis, params.turn_search_deg, params.turn_step_deg, params.span_trim_points));
      check.max_face_turn_deg = std::max(check.max_face_turn_deg, turn_deg);
      if (turn_deg > params.max_face_turn_deg && static_cast<int>(on_face.size()) >= params.min_turn_face_points)
        check.doubts.push_back("the scan's face across the box's " + std::string(axisName(axis)) +
                               " axis is turned " + formatDegrees(turn_deg) + " within its plane from the pose's (allowed " +
                               formatDegrees(params.max_face_turn_deg) + ")");
      const double tilt_deg = planeTiltDeg(on_face, axis);
      check.max_face_tilt_deg = std::max(check.max_face_tilt_deg, tilt_deg);
      if (tilt_deg > params.max_face_tilt_deg)
        check.doubts.push_back("the scan's face across the box's " + std::string(axisName(axis)) +
                               " axis is tilted " + formatDegrees(tilt_deg) + " from the pose's (allowed " +
                               formatDegrees(params.max_face_tilt_deg) + ")");
    }

  for (int axis = 0; axis < 3; ++axis)
  {
    if (!spanned[axis] || local.empty())
      continue;
    std::vector<double> along;
    along.reserve(local.size());
    for (const Eigen::Vector3d& p : local)
      along.push_back(p(axis));
    const double span_m = trimmedSpan(along, params.span_trim_points);
    const double edge_m = 2.0 * box.half_extents_m(axis);
    check.min_span_ratio = std::min(check.min_span_ratio, span_m / edge_m);
    const double shortfall_m = std::max(params.max_span_shortfall_m, params.max_span_shortfall_fraction * edge_m);
    if (span_m < edge_m - shortfall_m)
      check.doubts.push_back("the scan spans only " + formatMetres(span_m) + " along the box's " +
                             axisName(axis) + " axis, whose edge of a face the pose turns to the camera is " +
                             formatMetres(edge_m) + " long");
  }
  return check;
}
}  // namespace registration
}  // namespace brick_pose
