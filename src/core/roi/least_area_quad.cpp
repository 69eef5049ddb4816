#include "brick_pose/roi/least_area_quad.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
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

/// A side of the coarse quad: where its outline points are looked for.
struct CoarseSide
{
  Eigen::Vector2d from;
  Eigen::Vector2d along;    ///< Unit, from -> to.
  Eigen::Vector2d outward;  ///< Unit, away from the quad's inside.
  double length_px = 0.0;
};

CoarseSide coarseSide(const Eigen::Vector2d& from, const Eigen::Vector2d& to, const Eigen::Vector2d& inside_point)
{
  CoarseSide side;
  side.from = from;
  side.length_px = (to - from).norm();
  side.along = (to - from) / std::max(side.length_px, 1e-12);
  side.outward = Eigen::Vector2d(side.along.y(), -side.along.x());
  if (side.outward.dot(inside_point - from) > 0.0) side.outward = -side.outward;
  return side;
}

/// Outline points that may lie on `side`: away from its corners (morphology
/// rounds them) and at most side_search_px inside it. The coarse side is an
/// outer envelope: one spur or one noisy edge pixel puts it (or tilts it) a
/// few pixels outside the true edge, whose points then lie that far inside.
std::vector<Eigen::Vector2d> sideCandidates(const std::vector<cv::Point>& outline, const CoarseSide& side,
                                            const QuadFitParams& params)
{
  const double margin = std::max(params.min_corner_margin_px, params.corner_margin_fraction * side.length_px);
  std::vector<Eigen::Vector2d> candidates;
  for (const cv::Point& p : outline)
  {
    const Eigen::Vector2d offset = Eigen::Vector2d(p.x, p.y) - side.from;
    const double t = offset.dot(side.along);
    const double out = offset.dot(side.outward);
    if (t < margin || t > side.length_px - margin) continue;
    if (out < -params.side_search_px || out > params.side_band_px) continue;
    candidates.emplace_back(p.x, p.y);
  }
  return candidates;
}

std::size_t countNear(const std::vector<Eigen::Vector2d>& points, const Line2& line, double band_px)
{
  const Eigen::Vector2d normal(-line.direction.y(), line.direction.x());
  std::size_t count = 0;
  for (const Eigen::Vector2d& p : points)
    if (std::abs((p - line.point).dot(normal)) <= band_px) ++count;
  return count;
}

/// The line most candidates lie near (within band_px): the coarse side and
/// lines through pairs of candidates half the side apart (an edge is long, a
/// spur or a notch short, so a long pair on the edge finds most of them).
Line2 consensusLine(const std::vector<Eigen::Vector2d>& candidates, const CoarseSide& side, double band_px)
{
  constexpr std::size_t kHypotheses = 32;
  Line2 best{side.from, side.along};
  std::size_t best_count = countNear(candidates, best, band_px);
  // Candidates come in outline order, which runs along the side (several
  // outlines each run along their own part of it): sort by position along.
  std::vector<Eigen::Vector2d> sorted = candidates;
  std::sort(sorted.begin(), sorted.end(), [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.dot(side.along) < b.dot(side.along);
  });
  const std::size_t half = sorted.size() / 2;
  const std::size_t step = std::max<std::size_t>(1, half / kHypotheses);
  for (std::size_t i = 0; i + half < sorted.size() && i < half; i += step)
  {
    const Eigen::Vector2d direction = sorted[i + half] - sorted[i];
    if (direction.norm() < 1e-9) continue;
    const Line2 hypothesis{sorted[i], direction.normalized()};
    const std::size_t count = countNear(candidates, hypothesis, band_px);
    if (count > best_count)
    {
      best_count = count;
      best = hypothesis;
    }
  }
  return best;
}

/// Least-squares line (centroid and principal direction) of the points.
Line2 leastSquaresLine(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& direction_hint)
{
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const Eigen::Vector2d& p : points) scatter += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(scatter);
  Eigen::Vector2d direction = solver.eigenvectors().col(1);  // largest eigenvalue
  if (direction.dot(direction_hint) < 0.0) direction = -direction;
  return {centroid, direction};
}

std::vector<Eigen::Vector2d> pointsNear(const std::vector<Eigen::Vector2d>& points, const Line2& line, double band_px)
{
  const Eigen::Vector2d normal(-line.direction.y(), line.direction.x());
  std::vector<Eigen::Vector2d> near;
  for (const Eigen::Vector2d& p : points)
    if (std::abs((p - line.point).dot(normal)) <= band_px) near.push_back(p);
  return near;
}

/// Unit normal of `line` on the outer side of `side`.
Eigen::Vector2d outwardNormal(const Line2& line, const CoarseSide& side)
{
  const Eigen::Vector2d normal(line.direction.y(), -line.direction.x());
  return normal.dot(side.outward) < 0.0 ? Eigen::Vector2d(-normal) : normal;
}

/// The direction of a side without the dips of a ragged edge. Where noise
/// makes an edge ragged (pixels dropping out of the colour threshold in low
/// light), the outline dips into the plate at random, and a least-squares
/// line through all its points tilts toward wherever the dips cluster.
/// Points more than envelope_trim_px inside the line are left out and the
/// line fitted again, until it runs along the edge's outer pixels (a clean
/// digital edge spreads its points over at most one pixel, centred on the
/// line: hardly any are left out).
Line2 envelopeLine(const std::vector<Eigen::Vector2d>& support, const Line2& line, const Eigen::Vector2d& outward,
                   const QuadFitParams& params)
{
  constexpr int kPasses = 3;
  Line2 fitted = line;
  for (int pass = 0; pass < kPasses; ++pass)
  {
    std::vector<Eigen::Vector2d> kept;
    kept.reserve(support.size());
    for (const Eigen::Vector2d& p : support)
      if ((p - fitted.point).dot(outward) >= -params.envelope_trim_px) kept.push_back(p);
    if (static_cast<int>(kept.size()) < params.min_side_points) break;
    fitted = leastSquaresLine(kept, line.direction);
  }
  return fitted;
}

/// Value below which `fraction` of the values lie (nearest rank).
double quantile(std::vector<double> values, double fraction)
{
  const std::size_t rank =
      static_cast<std::size_t>(std::lround(fraction * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
  return values[rank];
}

/// Where the edge lies across a fitted side line, from the offsets (outward)
/// of its outline points. The outline's pixel centres lie inside the true
/// edge by an amount that depends on the colours on either side of it (their
/// mean: 0.3 to 1.8 px inside on the synthetic rig's plates, depending on
/// whether ground or a lit side face borders them, and on how ragged noise
/// makes the edge); their outer envelope does not, and a high quantile of it
/// ignores the few noisy pixels that stick out.
///
/// A clean digital edge puts its outline's pixel centres anywhere up to one
/// grid step (max(|nx|, |ny|) px across the line) inside it: the edge lies
/// between the envelope and the innermost point plus one step. On edges
/// along the grid or its diagonals every point is at the same offset, that
/// interval is a whole step wide and its middle is the best estimate; on
/// other slopes, or ragged edges, it is (nearly) empty and the envelope is
/// the estimate.
double edgeOffsetPx(const std::vector<double>& offsets_px, const Eigen::Vector2d& outward, const QuadFitParams& params)
{
  const double envelope_px = quantile(offsets_px, params.edge_quantile);
  const double innermost_px = quantile(offsets_px, 1.0 - params.edge_quantile);
  const double step_px = std::max(std::abs(outward.x()), std::abs(outward.y()));
  const double uncertain_px = std::max(0.0, innermost_px + step_px - envelope_px);
  return envelope_px + 0.5 * uncertain_px + params.edge_offset_px;
}

/// The edge line of `side` from the outline: direction from a least-squares
/// fit to the points near the consensus line, position from their offsets
/// across it (see edgeOffsetPx()). False (and the coarse side) when too few
/// points support it.
bool refineSide(const std::vector<cv::Point>& outline, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                const Eigen::Vector2d& inside_point, const QuadFitParams& params, Line2& edge)
{
  const CoarseSide side = coarseSide(from, to, inside_point);
  edge = Line2{from, side.along};
  const std::vector<Eigen::Vector2d> candidates = sideCandidates(outline, side, params);
  if (static_cast<int>(candidates.size()) < params.min_side_points) return false;

  Line2 line = consensusLine(candidates, side, params.side_band_px);
  std::vector<Eigen::Vector2d> support;
  // Twice: the least-squares line can take in points the consensus line
  // just missed, and drop ones it just took.
  for (int pass = 0; pass < 2; ++pass)
  {
    support = pointsNear(candidates, line, params.side_band_px);
    if (static_cast<int>(support.size()) < params.min_side_points) return false;
    line = leastSquaresLine(support, side.along);
  }
  // The envelope's line may take in edge points the mean line left out of
  // its band (where many dips pulled it in): select again around it.
  Eigen::Vector2d outward;
  for (int pass = 0; pass < 2; ++pass)
  {
    outward = outwardNormal(line, side);
    line = envelopeLine(support, line, outward, params);
    support = pointsNear(candidates, line, params.side_band_px);
    if (static_cast<int>(support.size()) < params.min_side_points) return false;
  }
  outward = outwardNormal(line, side);

  std::vector<double> offsets_px;
  offsets_px.reserve(support.size());
  for (const Eigen::Vector2d& p : support) offsets_px.push_back((p - line.point).dot(outward));
  edge = Line2{line.point + edgeOffsetPx(offsets_px, outward, params) * outward, line.direction};
  return true;
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
  for (const auto& outline : outlines) points.insert(points.end(), outline.begin(), outline.end());
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
  for (int k = 0; k < 4; ++k) refineSide(points, (*coarse)[k], (*coarse)[(k + 1) % 4], inside, params, sides[k]);

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
}  // namespace brick_pose
