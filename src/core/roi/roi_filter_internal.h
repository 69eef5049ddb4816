#pragma once

// What the three parts of RoiFilter share (roi_filter.cpp,
// roi_filter_tiling.cpp, roi_filter_typing.cpp): constants and small
// helpers. Internal to the core library: not installed.

#include <string>
#include <vector>

#include "brick_pose/roi/roi_filter.h"

namespace brick_pose
{
namespace roi_internal
{
/// A colour-free face that smaller catalogue tops cover this well (all but
/// this share) may be those bricks touching. When seams are seen along
/// nearly every cut (kMinSeenCutShare) the tiles are bricks and may leave
/// more untiled: a pallet stack's boxes merged into one of the large size
/// left 0.105-0.116 with seams along 3 of 3 or 4 cuts, while real single
/// boxes (mOSD) whose print crosses some cuts leave 0.119-0.225 with seams
/// along at most 3 of 5.
constexpr double kMaxUntiledForAlternative = 0.1;
constexpr double kMaxUntiledWithSeenSeams = 0.15;
constexpr double kMinSeenCutShare = 0.75;

/// "what value rule limit", the value to 3 significant digits.
std::string describe(const std::string& what, double value, const std::string& rule, double limit);

/// Why one part of a split segment (a tile, a side-by-side cut, a part
/// between depth steps) was dropped, reported over that part's footprint.
RoiRejection partRejection(const Segment& part, const std::string& reason);

/// A line this strong (standard errors of its along-line scatter) where
/// smaller bricks would meet doubts the whole, though the tiler did not cut
/// there. On bench_frontend's rig frames the whole green, blue and box tops
/// scored 0.2-2.6 at their nominal cuts; a row of touching bricks merged
/// into an orange-sized face at 848x480 scored 17 with no cut seen. Two
/// lines of kPairedSeamStrength do too: four red bricks merged into a blue
/// top scored 4.9 and 4.7 at both cuts, and no whole top of 100 frames per
/// class had two above 3. (Measured at one position per line with a line
/// error floor of 1.5 grey levels; the floor is now 0.6 and composed tops
/// are searched across the dimension tolerance, which can only raise the
/// scores: these now doubt more, never less.)
constexpr double kFaintSeamStrength = 5.0;
constexpr double kPairedSeamStrength = 4.0;

/// The direction sides hang from a face: the frame's up for a level face
/// (a narrow top's own normal can be degrees off), else the face's normal.
Eigen::Vector3d sideAxis(const BrickCandidate& candidate, const FrameContext& context);

/// Whether an edge of the face is cut by the border or an occluder.
bool anyTruncated(const BrickCandidate& candidate);

/// "edge 2: occlusion boundary" for the first truncated edge.
std::string truncation(const BrickCandidate& candidate);

/// The catalogue's types named `type_name`, or all of them for an empty name.
std::vector<const BrickType*> typesFor(const BrickCatalogue& catalogue, const std::string& type_name);

/// Puts `doubt` first in the candidate's type_doubt, before any it had.
void addTypeDoubt(BrickCandidate& candidate, const std::string& doubt);
}  // namespace roi_internal
}  // namespace brick_pose
