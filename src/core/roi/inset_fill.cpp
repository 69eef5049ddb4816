#include "brick_pose/roi/inset_fill.h"

#include <algorithm>
#include <climits>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace brick_pose
{
namespace
{
double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Fixed-point corners for cv::fillConvexPoly (8 fractional bits), relative to `origin`.
constexpr int kShiftBits = 8;
std::vector<cv::Point> fixedPoint(const QuadCorners& quad, const cv::Point& origin)
{
  std::vector<cv::Point> points;
  for (const Eigen::Vector2d& corner : quad)
    points.emplace_back(static_cast<int>(std::lround((corner.x() - origin.x) * (1 << kShiftBits))),
                        static_cast<int>(std::lround((corner.y() - origin.y) * (1 << kShiftBits))));
  return points;
}
}  // namespace

std::optional<QuadCorners> insetQuad(const QuadCorners& quad, double inset_px)
{
  const double orientation = signedAreaPx(quad) >= 0.0 ? 1.0 : -1.0;
  // Each side's line moved inward: point and direction.
  std::array<Eigen::Vector2d, 4> points, directions;
  for (int k = 0; k < 4; ++k)
  {
    const Eigen::Vector2d along = quad[(k + 1) % 4] - quad[k];
    if (!(along.norm() > 1e-9)) return std::nullopt;
    directions[k] = along.normalized();
    // With a positive signed area the interior lies on the side of
    // (-dy, dx) (the direction turned by +90 degrees), in any axes.
    const Eigen::Vector2d inward = orientation * Eigen::Vector2d(-directions[k].y(), directions[k].x());
    points[k] = quad[k] + inset_px * inward;
  }
  QuadCorners inset;
  for (int k = 0; k < 4; ++k)
  {
    // Corner k joins side k-1 and side k.
    const int before = (k + 3) % 4;
    const double denominator = cross2(directions[before], directions[k]);
    if (std::abs(denominator) < 1e-9) return std::nullopt;
    const double t = cross2(points[k] - points[before], directions[k]) / denominator;
    inset[k] = points[before] + t * directions[before];
  }
  // Every side keeps its direction (none passed its opposite) and the quad
  // its orientation.
  for (int k = 0; k < 4; ++k)
    if ((inset[(k + 1) % 4] - inset[k]).dot(directions[k]) <= 0.0) return std::nullopt;
  if (orientation * signedAreaPx(inset) <= 0.0) return std::nullopt;
  return inset;
}

bool shortfallFitsARim(double outline_area_px, const QuadCorners& quad, double rim_px)
{
  double perimeter_px = 0.0;
  for (int k = 0; k < 4; ++k) perimeter_px += (quad[(k + 1) % 4] - quad[k]).norm();
  return std::abs(signedAreaPx(quad)) - outline_area_px <= rim_px * perimeter_px;
}

double insetFillRatio(const std::vector<std::vector<cv::Point>>& outlines, const QuadCorners& quad, double inset_px)
{
  const std::optional<QuadCorners> inner = insetQuad(quad, inset_px);
  if (!inner) return 0.0;
  double u_min = 1e18, v_min = 1e18, u_max = -1e18, v_max = -1e18;
  for (const Eigen::Vector2d& corner : *inner)
  {
    u_min = std::min(u_min, corner.x());
    v_min = std::min(v_min, corner.y());
    u_max = std::max(u_max, corner.x());
    v_max = std::max(v_max, corner.y());
  }
  const cv::Point origin(static_cast<int>(std::floor(u_min)) - 1, static_cast<int>(std::floor(v_min)) - 1);
  const cv::Size size(static_cast<int>(std::ceil(u_max)) + 2 - origin.x, static_cast<int>(std::ceil(v_max)) + 2 - origin.y);
  cv::Mat inside_quad = cv::Mat::zeros(size, CV_8UC1), inside_outline = cv::Mat::zeros(size, CV_8UC1);
  cv::fillConvexPoly(inside_quad, fixedPoint(*inner, origin), cv::Scalar(255), cv::LINE_8, kShiftBits);
  cv::drawContours(inside_outline, outlines, -1, cv::Scalar(255), cv::FILLED, cv::LINE_8, cv::noArray(), INT_MAX,
                   -origin);
  const int quad_px = cv::countNonZero(inside_quad);
  if (quad_px == 0) return 0.0;
  cv::Mat both;
  cv::bitwise_and(inside_quad, inside_outline, both);
  return static_cast<double>(cv::countNonZero(both)) / quad_px;
}
}  // namespace brick_pose
