#pragma once
// The paper's least-area quadrilateral around a segment's outline. A convex
// hull follows every bump of a noisy or partly occluded outline; a brick face
// is four straight edges, so the hull is reduced to the enclosing
// quadrilateral that adds the least area, and the corners are then refined to
// sub-pixel accuracy by fitting a line to the outline points of each side.
// Each fit looks a few pixels inside the coarse side (a spur or a noisy pixel
// puts the enclosing side outside the edge, or tilts it), takes the line most
// points agree on (so notches, spurs and occluded stretches do not count) and
// places it at the outer envelope of its points.

#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace brick_pose
{
using QuadCorners = std::array<Eigen::Vector2d, 4>;

struct QuadFitParams
{
  /// Outline points up to this far inside a coarse side are candidates for
  /// its edge line.
  double side_search_px = 6.0;
  /// Points within this distance of the line most candidates agree on are
  /// fitted to it.
  double side_band_px = 2.0;
  /// A ragged edge's dips do not tilt its line: points more than this
  /// inside the line are left out and the line fitted again.
  double envelope_trim_px = 0.7;
  /// Points this close to a corner (fraction of the side, at least
  /// min_corner_margin_px) are left out: morphology rounds corners.
  double corner_margin_fraction = 0.1;
  double min_corner_margin_px = 3.0;
  /// The edge lies at this quantile of the fitted points' offsets across the
  /// line, plus edge_offset_px outward. The outline's pixel centres lie
  /// inside the true edge by an amount that depends on the colours on either
  /// side of it (their mean: 0.3 to 1.8 px inside on the synthetic rig's
  /// plates, depending on whether ground or a lit side face borders them);
  /// their outer envelope does not, and a high quantile of it ignores the
  /// few noisy pixels that stick out. 0.98 and 0.05 px gave the least face
  /// centre and corner error on bench_pose's frames (seeds 1-3: corner
  /// median 0.34-0.39 px, signed length error median within 0.05 mm).
  double edge_quantile = 0.98;
  double edge_offset_px = 0.05;
  /// Fewer points than this on a side: keep the coarse side.
  int min_side_points = 5;
  /// A refined corner farther than this from the coarse corner is not
  /// trusted (the coarse corner is kept).
  double max_refinement_shift_px = 8.0;
};

/// The least-area enclosing quadrilateral of a convex polygon (any
/// orientation): edges are removed greedily (each time the one whose removal,
/// by extending its two neighbouring edges to their intersection, adds the
/// least area) down to 12, then the best four of the remaining edges are
/// chosen exhaustively. Empty when no enclosing quadrilateral exists (a
/// triangle, or edges that cannot close four sides).
std::optional<QuadCorners> reduceToLeastAreaQuad(const std::vector<Eigen::Vector2d>& convex_polygon);

/// The refined least-area quadrilateral of a closed outline (image pixels,
/// e.g. from cv::findContours), corners clockwise on screen (image y down).
std::optional<QuadCorners> fitLeastAreaQuad(const std::vector<cv::Point>& outline,
                                            const QuadFitParams& params = QuadFitParams());

/// The same for a face seen in several pieces (an occluder across it): the
/// quad encloses all outlines and each side is refined on the points of all.
std::optional<QuadCorners> fitLeastAreaQuad(const std::vector<std::vector<cv::Point>>& outlines,
                                            const QuadFitParams& params = QuadFitParams());

/// Outlines of every blob of a binary mask (external contours), in image
/// pixels of the full frame.
std::vector<std::vector<cv::Point>> allOutlines(const cv::Mat& mask, const cv::Point& offset_px = cv::Point());

/// Outline of the largest blob of a binary mask, in image pixels of the full
/// frame (`offset_px` = position of the mask's top-left pixel in the image).
std::vector<cv::Point> largestOutline(const cv::Mat& mask, const cv::Point& offset_px = cv::Point());

/// Signed area, positive when the corners run clockwise on screen (y down).
double signedAreaPx(const QuadCorners& corners);
}  // namespace brick_pose
