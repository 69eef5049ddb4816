#pragma once
// How well a segment fills its quad away from the quad's sides.
//
// A segment's outline comes from depth, and depth edges are ragged: a
// stereo (D4xx) or structured-light (Kinect) matching window leaves the
// boundary a pixel or two in or out, row by row. On a face a few dozen
// pixels across that rim alone costs a tenth or more of the quad (whole
// real box tops in mOSD fill 0.83-0.85 of theirs), while a notch, an L or a
// merged piece leaves its shortfall in one place, deeper than any rim. The
// fill measured a rim's depth inside the quad's sides tells them apart.

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "brick_pose/roi/least_area_quad.h"

namespace brick_pose
{
/// The quad moved `inset_px` inward along each side's normal (corners where
/// the moved sides meet); empty when the quad is too small for it (a side
/// would pass its opposite, or the quad turn over) or has a side of no
/// length or two sides parallel where they meet.
std::optional<QuadCorners> insetQuad(const QuadCorners& quad, double inset_px);

/// Whether all of the quad's area outside the outlines (which enclose
/// `outline_area_px`) could lie in a rim `rim_px` deep along its sides: no
/// more than rim_px times the quad's perimeter. Where it could not, no rim
/// explains the shortfall (and a quad far larger than its outline is never
/// rasterised).
bool shortfallFitsARim(double outline_area_px, const QuadCorners& quad, double rim_px);

/// Share of the pixels inside insetQuad(quad, inset_px) that lie inside the
/// outlines (closed, image pixels; what they enclose counts, holes too).
/// 0 when there is no inset quad.
double insetFillRatio(const std::vector<std::vector<cv::Point>>& outlines, const QuadCorners& quad,
                      double inset_px);
}  // namespace brick_pose
