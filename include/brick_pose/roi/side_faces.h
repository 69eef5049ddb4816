#pragma once
// The side faces below a top face's edges. Seen obliquely, a brick shows a
// side face hanging from its top's near edges, as tall as the brick. A face
// of the catalogue's top size whose visible sides end at another height is
// not that brick's top (a box lying on another face, the front of a standing
// box): where a side face is seen whole, its height must be the catalogue's.
//
// Each edge's side plane is the plane through the edge at right angles to
// the face. Below the edge (away from the face's normal) that plane is
// marched in small steps at several places along the edge; the run of
// depth pixels on it gives the side's visible height, and what ends the run
// says whether the height is the whole side (a surface at the foot of the
// side, or nothing: the side hangs free) or only its visible part (a nearer
// surface in front of it, no depth, the image border).

#include <array>
#include <string>

#include <Eigen/Core>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/roi/up_direction.h"

namespace brick_pose
{
enum class SideFaceVerdict
{
  kNotVisible,  ///< Faces away from the camera, or no side surface below the edge.
  kCutShort,    ///< Seen, but hidden or out of view before its foot.
  kMatches,     ///< Seen to its foot, of the catalogue height.
  kMismatch,    ///< Seen to its foot, of another height (nor a stack of two or three).
};

struct SideFaceParams
{
  /// Depth pixels within this distance of the side plane lie on it.
  double plane_tolerance_m = 0.012;
  /// The side plane is marched down to this multiple of the catalogue height
  /// (bricks stacked flush show up to three heights of side as one wall).
  double search_factor = 3.5;
  /// A side shorter than this is not a visible side.
  double min_visible_m = 0.015;
  /// Heights agree within max(height_tolerance_m, height_tolerance_fraction * height).
  double height_tolerance_m = 0.02;
  double height_tolerance_fraction = 0.2;
  /// Places along the edge where the side is marched.
  int columns = 7;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// What was seen below one edge.
struct SideFaceEvidence
{
  bool visible = false;      ///< A side surface runs down from the edge.
  bool foot_seen = false;    ///< ... and is seen to its foot: a nearer surface at the level where it ends.
  /// ... and that surface is the frame's supporting plane (the ground, a
  /// table): the side reaches it, so its height is the brick's (any other
  /// surface may be a lower neighbour in front, hiding the rest).
  bool foot_on_support = false;
  double visible_height_m = 0.0;  ///< Median height seen (to the foot when foot_seen).
};

/// The side below edge k (corners k to k + 1 of `corners_m`) along `up`
/// reversed (unit, toward the camera side of the face), marched down to
/// search_factor x `max_height_m`. `up` is the face's normal, or the frame's
/// up when the face is level: a narrow top's own normal may be a few degrees
/// off, which over 20 cm of side leaves the side plane.
SideFaceEvidence measureSideFace(const RgbdFrame& frame, const std::array<Eigen::Vector3d, 4>& corners_m,
                                 const Eigen::Vector3d& up, int edge, double max_height_m, const UpDirection& support,
                                 const SideFaceParams& params = SideFaceParams());

/// The side compared with a brick of `height_m`: a side seen to its foot
/// matches when it is one, two or three heights tall (bricks stacked flush
/// below show one wall of sides); it contradicts the height when it reaches
/// the supporting plane at another height, or is taller. A shorter side
/// ending on another surface is only cut short.
SideFaceVerdict judgeSideFace(const SideFaceEvidence& side, double height_m,
                              const SideFaceParams& params = SideFaceParams());

std::string toString(SideFaceVerdict verdict);
}  // namespace brick_pose
