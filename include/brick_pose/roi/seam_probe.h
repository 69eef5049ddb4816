#pragma once
// A quick look for a seam across a face one brick wide, before tiling it.
//
// Without colour, a face cut off by the image border or an occluder cannot
// be typed by its size, so it is tiled in case it is several bricks end to
// end, one of them whole. Tiling reads seam evidence along every line of a
// grid over the face, and on a pile most such faces are one brick partly
// out of view: the tiler found nothing on 133 of 134 of them (gapped piles
// at 640x480), and their tiling was 60 % of the ROI stage there. A tiling
// is kept only where a cut shows a seam; across a strip one brick wide a
// cut spans the whole width, so the face's grey level and depth averaged
// across it, bin by bin along its length, dip there as much as along the
// cut itself. No dip near the seam's strength anywhere: no tiling to try.
// Where the dips lie says more: a tile is kept only when both its ends are
// seen, and a strip cut off at one end (a brick running out of view) whose
// only dips lie no brick's length from its seen end and from each other
// cannot hold one (seamsMayBoundABrick).
// Not looked for: a seam along the strip's length, between two bricks each
// mostly cut off by one of its long edges (a strip cut off along both).
// Both could only be partial; the rig never showed one.

#include <array>
#include <vector>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/roi/brick_candidate.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
struct SeamProbeParams
{
  /// A bin's dip is read between bins this many pixels to either side (the
  /// tiler's seam_arm_px) ...
  int arm_px = 3;
  /// ... and counts as a possible seam at this many robust standard
  /// deviations of all bins' dips (a cut is kept at 6 of its own, whose
  /// noise is the same) ...
  double min_strength = 3.5;
  /// ... and at this share of the smallest seam a cut is kept with
  /// (EdgeEvidenceParams' min_line_contrast, min_groove_m).
  double min_share_of_smallest_seam = 0.5;
};

struct SeamProbe
{
  /// Bins along the face read (both arms inside it, enough pixels).
  int bins = 0;
  /// Strongest dip of any bin, in robust standard deviations (grey: darker
  /// or brighter than both sides; depth: a groove).
  double strongest = 0.0;
  /// Some bin dips enough to be a seam: the face may be several bricks.
  bool seam_possible = true;
  /// The face's edges at either end of its long edge: at 0 and at
  /// `length_m` along it (3 and 1 when corner 0 to 1 is the long edge).
  std::array<int, 2> end_edges{{3, 1}};
  double length_m = 0.0;
  /// Whether the strip was long enough to read; then `possible_seams_m`
  /// holds where along the long edge (m from its end at 0) a bin dips
  /// enough to be a seam.
  bool located = false;
  std::vector<double> possible_seams_m;
};

/// Reads `face` (measured from `segment`) in bins about a pixel long along
/// its long edge, each the mean over the face's width.
/// `smallest_line_contrast` (grey levels) and `smallest_groove_m` are the
/// smallest seams a cut is kept with. With fewer than a few bins read, a
/// seam stays possible.
SeamProbe probeSeamsAcross(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& face,
                           double smallest_line_contrast, double smallest_groove_m,
                           const SeamProbeParams& params = SeamProbeParams());

/// Whether one brick of the strip could be seen whole: two of its seen ends
/// (`end_seen`: those of the probe's `end_edges`) and its possible seams lie
/// one of `lengths_m` apart, within `tolerance_m`. A tile of a strip one
/// brick wide is kept only when both its ends are seen, an end of the face
/// or a seam, so without such a pair its tiling keeps nothing. True where
/// the probe could not locate its seams.
bool seamsMayBoundABrick(const SeamProbe& probe, const std::array<bool, 2>& end_seen,
                         const std::vector<double>& lengths_m, double tolerance_m);
}  // namespace brick_pose
