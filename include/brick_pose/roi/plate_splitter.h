#pragma once
// Plates of one colour that lie side by side at the same height (the rows of
// an organised pile) merge into one colour segment wherever perspective hides
// the 1-3 cm gap between them. Their least-area quad then measures the
// brick's length one way and n widths (plus gaps) the other; this cuts such a
// segment into its n plates.

#include <vector>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/roi/brick_candidate.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
/// How many plates of width `width_m` with gaps of at most a few cm fit in
/// `across_m` (1 when it is a single plate).
int sideBySideCount(double across_m, double width_m);

/// The parts of `segment` (measured as `measured`: plane, ordered 3D corners)
/// when one side of its quad is at most `type`'s length (+ `tolerance_m`;
/// shorter when clipped or occluded) and the other holds n >= 2 widths;
/// empty otherwise. Cuts run parallel to the
/// length, evenly spaced on the plane, or through the apex of a convexity
/// defect deeper than 4 px (the visible end of a gap) close to that spacing.
std::vector<Segment> splitSideBySide(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                                     const BrickType& type, double tolerance_m);
/// Plates at different heights that still touch in a colour segment (an edge
/// the image-level depth cut missed: flying pixels, shadows): the parts of
/// `segment` whose pixels are 4-connected through steps of at most
/// `max_step_m` in depth, largest first, each of at least `min_area_px`.
/// Pixels without depth belong to no part. Empty when there is only one part.
std::vector<Segment> splitAtDepthSteps(const RgbdFrame& frame, const Segment& segment, double max_step_m,
                                       int min_area_px);
}  // namespace brick_pose
