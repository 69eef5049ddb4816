#include "brick_pose/roi/least_area_quad.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

namespace brick_pose
{
namespace
{
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Parameters (t, s) of the intersection a + t (b - a) = c + s (d - c);
/// false for parallel lines.
bool intersectLines(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    const Eigen::Vector2d& d, double& t, double& s)
{
  const Eigen::Vector2d r = b - a;
  const Eigen::Vector2d q = d - c;
  const double denominator = cross(r, q);
  if (std::abs(denominator) < 1e-12 * r.norm() * q.norm()) return false;
  t = cross(c - a, q) / denominator;
  s = cross(c - a, r) / denominator;
  return true;
}

constexpr std::size_t kExhaustiveEdgeCount = 12;

/// Replaces the polygon edge whose removal (extending its neighbouring
/// edges to their intersection) adds the least area; false when none can be.
bool removeLeastAreaEdge(std::vector<Eigen::Vector2d>& polygon)
{
  const int n = static_cast<int>(polygon.size());
  double best_area = std::numeric_limits<double>::max();
  int best_edge = -1;
  Eigen::Vector2d best_vertex;
  for (int i = 0; i < n; ++i)
  {
    // Removing edge (b, c): extend (a, b) beyond b and (d, c) beyond c.
    const Eigen::Vector2d& a = polygon[(i + n - 1) % n];
    const Eigen::Vector2d& b = polygon[i];
    const Eigen::Vector2d& c = polygon[(i + 1) % n];
    const Eigen::Vector2d& d = polygon[(i + 2) % n];
    double t = 0.0, s = 0.0;
    if (!intersectLines(a, b, d, c, t, s) || t < 1.0 || s < 1.0) continue;
    const Eigen::Vector2d vertex = a + t * (b - a);
    const double added_area = 0.5 * std::abs(cross(vertex - b, c - b));
    if (added_area < best_area)
    {
      best_area = added_area;
      best_edge = i;
      best_vertex = vertex;
    }
  }
  if (best_edge < 0) return false;
  polygon[best_edge] = best_vertex;
  polygon.erase(polygon.begin() + (best_edge + 1) % n);
  return true;
}

/// The least-area quadrilateral whose sides lie on four of the polygon's
/// edges. Every edge line of a convex polygon supports it, so four of them
/// enclose it whenever consecutive chosen edges turn by less than 180 deg.
std::optional<QuadCorners> leastAreaQuadOnEdges(const std::vector<Eigen::Vector2d>& polygon)
{
  const int n = static_cast<int>(polygon.size());
  double orientation = 0.0;
  for (int i = 0; i < n; ++i) orientation += cross(polygon[i], polygon[(i + 1) % n]);
  const double sign = orientation >= 0.0 ? 1.0 : -1.0;
  auto direction = [&](int i) -> Eigen::Vector2d { return polygon[(i + 1) % n] - polygon[i]; };
  auto corner = [&](int i, int j, Eigen::Vector2d& hit) {
    if (sign * cross(direction(i), direction(j)) <= 0.0) return false;  // no bounded corner
    double t = 0.0, s = 0.0;
    if (!intersectLines(polygon[i], polygon[(i + 1) % n], polygon[j], polygon[(j + 1) % n], t, s)) return false;
    hit = polygon[i] + t * direction(i);
    return true;
  };

  std::optional<QuadCorners> best;
  double best_area = std::numeric_limits<double>::max();
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k)
        for (int l = k + 1; l < n; ++l)
        {
          QuadCorners quad;
          if (!corner(i, j, quad[0]) || !corner(j, k, quad[1]) || !corner(k, l, quad[2]) || !corner(l, i, quad[3]))
            continue;
          double twice_area = 0.0;
          for (int m = 0; m < 4; ++m) twice_area += cross(quad[m], quad[(m + 1) % 4]);
          const double area = 0.5 * std::abs(twice_area);
          if (area < best_area)
          {
            best_area = area;
            best = quad;
          }
        }
  return best;
}

/// A line as a point and a unit direction.
struct Line2
{
  Eigen::Vector2d point;
  Eigen::Vector2d direction;
};

bool intersect(const Line2& first, const Line2& second, Eigen::Vector2d& hit)
{
  double t = 0.0, s = 0.0;
  if (!intersectLines(first.point, first.point + first.direction, second.point, second.point + second.direction, t, s))
    return false;
  hit = first.point + t * first.direction;
  return true;
}

/// Marks the outline points that lie inside convexity defects deeper than
/// `min_depth_px`: they belong to a notch or an occluder, not to an edge.
std::vector<bool> pointsInDeepDefects(const std::vector<cv::Point>& outline, double min_depth_px)
{
  std::vector<bool> in_defect(outline.size(), false);
  std::vector<int> hull_indices;
  cv::convexHull(outline, hull_indices, false, false);
  if (hull_indices.size() < 3) return in_defect;
  std::vector<cv::Vec4i> defects;
  try
  {
    cv::convexityDefects(outline, hull_indices, defects);
  }
  catch (const cv::Exception&)
  {
    return in_defect;  // self-intersecting outlines (1-pixel-wide parts); refine without the hint
  }
  const int count = static_cast<int>(outline.size());
  for (const cv::Vec4i& defect : defects)
  {
    if (defect[3] / 256.0 < min_depth_px) continue;
    // Keep the hull points at the defect's ends: they do lie on the edge.
    for (int i = (defect[0] + 1) % count; i != defect[1]; i = (i + 1) % count) in_defect[i] = true;
  }
  return in_defect;
}

/// Robust line through the outline points near side (from, to), moved
/// outwards by the half-pixel bias; false when too few points support it.
bool refineSide(const std::vector<cv::Point>& outline, const std::vector<bool>& excluded,
                const Eigen::Vector2d& from, const Eigen::Vector2d& to, const Eigen::Vector2d& inside_point,
                const QuadFitParams& params, Line2& side)
{
  const Eigen::Vector2d along = (to - from).normalized();
  const double length = (to - from).norm();
  Eigen::Vector2d outward(along.y(), -along.x());
  if (outward.dot(inside_point - from) > 0.0) outward = -outward;
  const double margin = std::max(params.min_corner_margin_px, params.corner_margin_fraction * length);

  std::vector<cv::Point2f> support;
  for (std::size_t i = 0; i < outline.size(); ++i)
  {
    if (excluded[i]) continue;
    const Eigen::Vector2d offset(outline[i].x - from.x(), outline[i].y - from.y());
    const double t = offset.dot(along);
    if (t < margin || t > length - margin) continue;
    if (std::abs(offset.dot(outward)) > params.side_band_px) continue;
    support.emplace_back(static_cast<float>(outline[i].x), static_cast<float>(outline[i].y));
  }

  Eigen::Vector2d point = from;
  Eigen::Vector2d direction = along;
  const bool refined = static_cast<int>(support.size()) >= params.min_side_points;
  if (refined)
  {
    cv::Vec4f fitted;
    cv::fitLine(support, fitted, cv::DIST_HUBER, 0.0, 0.01, 0.01);
    direction = Eigen::Vector2d(fitted[0], fitted[1]).normalized();
    point = Eigen::Vector2d(fitted[2], fitted[3]);
    outward = Eigen::Vector2d(direction.y(), -direction.x());
    if (outward.dot(inside_point - point) > 0.0) outward = -outward;
  }
  const double bias_px = params.edge_offset_px * std::max(std::abs(outward.x()), std::abs(outward.y()));
  side.point = point + bias_px * outward;
  side.direction = direction;
  return refined;
}
}  // namespace

std::optional<QuadCorners> reduceToLeastAreaQuad(const std::vector<Eigen::Vector2d>& convex_polygon)
{
  std::vector<Eigen::Vector2d> polygon = convex_polygon;
  if (polygon.size() < 4) return std::nullopt;
  // Greedy edge removal is cheap and harmless while the removed edges are the
  // tiny steps of a pixel outline; near the end it can pick a wrong edge
  // (e.g. short sides between chamfers), so the last few edges are chosen
  // exhaustively instead.
  while (polygon.size() > kExhaustiveEdgeCount)
  {
    if (!removeLeastAreaEdge(polygon)) return std::nullopt;
  }
  return leastAreaQuadOnEdges(polygon);
}

std::optional<QuadCorners> fitLeastAreaQuad(const std::vector<cv::Point>& outline, const QuadFitParams& params)
{
  return fitLeastAreaQuad(std::vector<std::vector<cv::Point>>{outline}, params);
}

std::optional<QuadCorners> fitLeastAreaQuad(const std::vector<std::vector<cv::Point>>& outlines,
                                            const QuadFitParams& params)
{
  std::vector<cv::Point> points;
  std::vector<bool> excluded;
  for (const auto& outline : outlines)
  {
    if (outline.empty()) continue;
    const std::vector<bool> in_defects = pointsInDeepDefects(outline, params.defect_depth_px);
    points.insert(points.end(), outline.begin(), outline.end());
    excluded.insert(excluded.end(), in_defects.begin(), in_defects.end());
  }
  if (points.size() < 4) return std::nullopt;
  std::vector<cv::Point> hull_points;
  cv::convexHull(points, hull_points);
  std::vector<Eigen::Vector2d> hull;
  hull.reserve(hull_points.size());
  for (const cv::Point& p : hull_points) hull.emplace_back(p.x, p.y);
  std::optional<QuadCorners> coarse = reduceToLeastAreaQuad(hull);
  if (!coarse) return std::nullopt;
  if (signedAreaPx(*coarse) < 0.0) std::reverse(coarse->begin(), coarse->end());

  Eigen::Vector2d inside = Eigen::Vector2d::Zero();
  for (const auto& corner : *coarse) inside += 0.25 * corner;

  std::array<Line2, 4> sides;
  for (int k = 0; k < 4; ++k)
    refineSide(points, excluded, (*coarse)[k], (*coarse)[(k + 1) % 4], inside, params, sides[k]);

  QuadCorners refined;
  for (int k = 0; k < 4; ++k)
  {
    // Corner k joins side k-1 (ending at it) and side k (starting at it).
    Eigen::Vector2d hit;
    const bool ok = intersect(sides[(k + 3) % 4], sides[k], hit);
    refined[k] = ok && (hit - (*coarse)[k]).norm() <= params.max_refinement_shift_px ? hit : (*coarse)[k];
  }
  if (signedAreaPx(refined) <= 0.0) return coarse;
  return refined;
}

std::vector<std::vector<cv::Point>> allOutlines(const cv::Mat& mask, const cv::Point& offset_px)
{
  std::vector<std::vector<cv::Point>> outlines;
  cv::Mat copy = mask.clone();  // findContours of OpenCV < 3.2 modified its input
  cv::findContours(copy, outlines, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE, offset_px);
  return outlines;
}

std::vector<cv::Point> largestOutline(const cv::Mat& mask, const cv::Point& offset_px)
{
  std::vector<std::vector<cv::Point>> outlines;
  cv::findContours(mask, outlines, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE, offset_px);
  if (outlines.empty()) return {};
  auto largest = std::max_element(outlines.begin(), outlines.end(), [](const auto& a, const auto& b) {
    return std::abs(cv::contourArea(a)) < std::abs(cv::contourArea(b));
  });
  return *largest;
}

double signedAreaPx(const QuadCorners& corners)
{
  double twice_area = 0.0;
  for (int k = 0; k < 4; ++k) twice_area += cross(corners[k], corners[(k + 1) % 4]);
  return 0.5 * twice_area;
}

Eigen::Vector2d diagonalIntersection(const QuadCorners& corners)
{
  double t = 0.0, s = 0.0;
  if (!intersectLines(corners[0], corners[2], corners[1], corners[3], t, s))
    return 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
  return corners[0] + t * (corners[2] - corners[0]);
}
}  // namespace brick_pose
