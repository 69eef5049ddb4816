#pragma once
// The direction a segment's outline runs along, measured on its plane.
//
// Touching bricks of one layer lie parallel, so every straight stretch of
// their merged outline runs along one of two perpendicular directions, even
// where the outline is a Z or an L of offset bricks. The least-area quad of
// such an outline is not aligned with the bricks (a parallelogram of two
// offset bricks is enclosed more tightly by a tilted rectangle), and a
// tiling on the quad's axes then fits no brick at all. The outline's own
// dominant direction (modulo a quarter turn) is the bricks' axis.

#include <optional>

#include <Eigen/Core>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/geometry/plane_fit.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
struct OutlineAxisParams
{
  /// Straight stretches are found by simplifying the outline to this many
  /// pixels.
  double simplify_px = 2.0;
  /// Stretches shorter than this (pixels) neither vote nor count in the
  /// outline's length: a depth edge ragged with noise and fattening breaks
  /// into many short pieces at every angle, which would dilute the sides.
  double min_stretch_px = 8.0;
  /// Stretches within this angle (modulo a quarter turn) of the peak vote
  /// for it.
  double agree_deg = 4.0;
  /// The peak must hold at least this share of the outline's length on the
  /// plane, or the outline has no clear axis.
  double min_support = 0.6;
};

struct OutlineAxis
{
  /// Unit direction on the plane (camera frame), perpendicular to its normal.
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  /// Share of the outline's length (on the plane) along it or across it.
  double support = 0.0;
};

/// The outline's dominant direction on `plane`, or nothing when the outline
/// has no clear one (too few straight stretches agree, or no outline).
std::optional<OutlineAxis> dominantOutlineAxis(const RgbdFrame& frame, const Segment& segment,
                                               const PlaneFit& plane, const OutlineAxisParams& params = {});
}  // namespace brick_pose
