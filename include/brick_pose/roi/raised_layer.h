#pragma once
// Whether a colour-free plane is a raised layer of bricks or boxes worth
// tiling, rather than the ground or a table top that objects stand on.

#include <opencv2/core.hpp>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/geometry/plane_fit.h"
#include "brick_pose/roi/edge_evidence.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
/// The pixels between `inner_px` and `outer_px` outside a mask, the ring
/// around its outline: `ring` (CV_8UC1, non-zero on the ring) covers
/// `box_px`, the mask's box grown by outer_px and clipped to the image;
/// both empty when that box leaves the image.
struct OutlineRing
{
  cv::Rect box_px;
  cv::Mat ring;
};

/// The ring around `mask`, which lies at `box_px` in `frame`'s image.
OutlineRing outlineRing(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box_px, int inner_px,
                        int outer_px);

/// What lies around a segment's outline, in a ring a few pixels out.
struct OutlineSurroundings
{
  int below = 0;  ///< Ring pixels more than the step below the segment's plane.
  int above = 0;  ///< Ring pixels more than the step above it (nearer the camera).
  int level = 0;  ///< Ring pixels within the step of it.

  int withDepth() const { return below + above + level; }
  /// Most of the ring with depth lies below the plane: the segment stands
  /// up from its surroundings (a layer on a pallet, not the floor under it).
  bool fallsAway() const { return withDepth() > 0 && 2 * below > withDepth(); }
  /// Where no nearer surface rises beside it, the ring mostly lies below
  /// the plane, on at least a quarter of the ring: a low row of boxes
  /// between the pallet's edge and taller boxes standing beside it. (Around
  /// the floor nothing lies below; objects rise from it.)
  bool fallsAwayBesideWalls() const { return 4 * below >= withDepth() && below > level; }
};

/// Reads the ring between `inner_px` and `outer_px` pixels outside the
/// segment's mask: the first few pixels out are skipped because a D4xx
/// fattens a raised face's depth over its own edge.
OutlineSurroundings measureOutlineSurroundings(const RgbdFrame& frame, const Segment& segment, const PlaneFit& plane,
                                               double step_m, int inner_px, int outer_px);

/// Whether a plane ends at real edges on three sides of its quad, or on two
/// opposite ones with the others at the image border (a row longer than the
/// view: its bricks wholly in view are whole tops; a floor filling an image
/// corner is not one). A face hidden under an occluder on two sides gives
/// only bricks cut off by it. A segment that keeps clear of the image
/// border ends at real edges wherever its quad's sides are not "at the
/// border": those sides are the quad's (rows of bricks offset end to end
/// fill a quad reaching beyond the image), not where the face is cut.
bool isRaisedLayer(const EdgeKinds& kinds, bool clear_of_image_border);

/// Whether a segment's pixels stay at least `margin_px` from the image border.
bool clearOfImageBorder(const Segment& segment, const RgbdFrame& frame, int margin_px);
}  // namespace brick_pose
