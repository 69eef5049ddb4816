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
/// that `kinds` says depth bounds, or half off each end when both or
/// neither are.
std::array<Eigen::Vector3d, 4> cornersTrimmedToSize(const std::array<Eigen::Vector3d, 4>& corners_m,
                                                    const EdgeKinds& kinds, double length_m, double width_m,
                                                    double max_trim_m);
}  // namespace brick_pose
