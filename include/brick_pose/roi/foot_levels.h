#pragma once
// The levels a face may stand on. A box's top lies its height above what it
// stands on: the supporting plane (the floor, a table), other boxes, or
// something the catalogue does not hold (a pallet's deck, a plinth). Around
// a face's outline, the surfaces lower than the face that are seen level at
// one height above the support are such levels; each is one more place the
// box may stand, so each can only widen the types its height allows.

#include <vector>

#include <opencv2/core.hpp>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/geometry/plane_fit.h"
#include "brick_pose/roi/up_direction.h"

namespace brick_pose
{
struct FootLevelParams
{
  /// The ring read around the face's mask (pixels out from it): the first
  /// few are skipped, as a D4xx fattens a raised face's depth over its edge.
  int inner_px = 4;
  int outer_px = 12;
  /// Ring pixels lower than the face's plane by more than this (m) may be
  /// where it stands.
  double below_face_m = 0.02;
  /// ... and lie on a level surface: its normal, from the depth this many
  /// pixels to either side, within max_level_tilt_deg of the support's (a
  /// side face is 90 degrees off; D4xx noise tilts a level surface's
  /// normal by some 10-25 degrees over a few pixels at 1-2 m).
  int normal_baseline_px = 3;
  double max_level_tilt_deg = 45.0;
  /// ... and bend no more than this (m) over that baseline: a pixel across
  /// a depth jump, a mix of a near and a far surface, lies at any height.
  double max_bend_m = 0.01;
  /// A level: at least this share of those pixels, and min_pixels of them,
  /// within `tolerance_m` of one height above the support.
  double min_share = 0.2;
  int min_pixels = 30;
};

/// The heights above `support`'s plane (m) of the level surfaces seen
/// around the mask (`mask`, placed at `box_px` in the image) of a face on
/// `plane`, other than the support itself (within `tolerance_m` of 0).
/// Empty without a supporting plane.
std::vector<double> levelsAroundFoot(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box_px,
                                     const PlaneFit& plane, const UpDirection& support, double tolerance_m,
                                     const FootLevelParams& params = FootLevelParams());
}  // namespace brick_pose
