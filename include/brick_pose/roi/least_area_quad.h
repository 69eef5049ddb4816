#pragma once
// The paper's least-area quadrilateral around a segment's outline. A convex
// hull follows every bump of a noisy or partly occluded outline; a brick face
// is four straight edges, so the hull is reduced to the enclosing
// quadrilateral that adds the least area, and the corners are then refined to
// sub-pixel accuracy by fitting lines to the outline points of each side
// (convexity defects mark the outline stretches that are not edge points).

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
  /// Outline points within this distance of a coarse side are fitted to it.
  double side_band_px = 2.0;
  /// Points this close to a corner (fraction of the side, at least
  /// min_corner_margin_px) are left out: morphology rounds corners.
  double corner_margin_fraction = 0.1;
  double min_corner_margin_px = 3.0;
  /// The outline's pixel centres lie inside the true edge; the fitted lines
  /// are moved out by edge_offset_px * max(|nx|, |ny|). A mask sampled at
  /// pixel centres is 0.5 px (one half step) inside; on images that
  /// integrate over the pixel (real cameras, the anti-aliased synthetic rig)
  /// the colour threshold keeps partly covered edge pixels and 0.25 measured
  /// best (bench_frontend corner error 0.44 px median against 0.64 at 0.5).
  double edge_offset_px = 0.25;
  /// Outline stretches inside convexity defects deeper than this are not used.
  double defect_depth_px = 2.0;
  /// Fewer points than this on a side: keep the coarse side.
  int min_side_points = 5;
  /// A refined corner farther than this from the coarse corner is not trusted.
  double max_refinement_shift_px = 4.0;
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

/// Intersection of the diagonals: the image of the centre of a planar
/// rectangle under perspective.
Eigen::Vector2d diagonalIntersection(const QuadCorners& corners);
}  // namespace brick_pose
