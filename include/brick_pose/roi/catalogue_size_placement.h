#pragma once
// D4xx depth carries a face a few pixels over a step down (its stereo
// matching window fattens the foreground), so a colour-free face, whose
// segment is cut out of depth, measures long on every side its depth bounds:
// on the rig's D4xx scenes, complete faces' step-down edges lay 4-10 mm out
// (median) and their colour-located edges (lines, seams, wall feet) within
// 1 mm. Where one end of an axis is such an edge and the other is not, the
// face's centre is off by half that excess.
//
// Once a face is complete its type is known, and so its true size: the
// excess over it is taken off the edges depth bounds, and none off the
// ones colour placed. The measured length and width are not changed.

#include <array>
#include <limits>

#include <Eigen/Core>

#include "brick_pose/roi/edge_evidence.h"

namespace brick_pose
{
/// Whether the face's depth, not colour, bounds it at an edge of this kind
/// (a step down, a crease, a drop beside walls): there D4xx depth ends
/// beyond the face's true edge.
bool depthBoundsEdge(EdgeKind kind);

/// `corners_m` (a face's quad on its plane; edges 0 and 2 the long ones,
/// edge k from corner k to k + 1) with its edges moved in so that the face
/// is `length_m` x `width_m`. Along each axis the excess (at most
/// `max_trim_m`; none when the face is not longer) comes off the one end
/// that `kinds` says depth bounds, or half off each end when neither is.
/// When both are, `colour_inset_m` (how far inside its depth edge the
/// colour image shows edge k end, NaN where it cannot tell: see
/// stepEdgeInsetPx) shares it. Depth fattens the foreground by different
/// amounts on different sides (more where the face hides the ground than
/// where its own side shows below the edge). Both ends seen share it in
/// proportion, where their sum agrees with the excess within
/// `colour_agreement_m` (print near an edge, a label's border, can pass for
/// it: two measures that agree are trusted); one end seen, no farther in
/// than the excess, takes what it shows and the other end the rest;
/// otherwise half each.
std::array<Eigen::Vector3d, 4> cornersTrimmedToSize(
    const std::array<Eigen::Vector3d, 4>& corners_m, const EdgeKinds& kinds, double length_m, double width_m,
    double max_trim_m,
    const std::array<double, 4>& colour_inset_m = {{std::numeric_limits<double>::quiet_NaN(),
                                                    std::numeric_limits<double>::quiet_NaN(),
                                                    std::numeric_limits<double>::quiet_NaN(),
                                                    std::numeric_limits<double>::quiet_NaN()}},
    double colour_agreement_m = 0.0);
}  // namespace brick_pose
