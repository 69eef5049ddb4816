#pragma once
// Pieces of one plate's face that an occluder cut apart: which two partial
// candidates may be joined, and the segment made of both. The front end
// filters the joined segment again and keeps it only if it passes.

#include "brick_pose/roi/brick_candidate.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
/// True when `a` and `b` may be two pieces of one plate's face: both partial,
/// both typed by the same plate colour, their normals within
/// `max_angle_deg`, and each one's centre within `max_offset_m` of the
/// other's plane.
///
/// Only pieces typed by colour: the joined segment is filtered as that
/// colour's, where a line in the colour image is the plate's edge. Two
/// colour-free pieces (tiles of a printed box top, cut where the print draws
/// lines) would be judged so too, and were found complete on part of a real
/// box's top.
bool mayBePiecesOfOneFace(const BrickCandidate& a, const BrickCandidate& b, double max_angle_deg, double max_offset_m);

/// One segment made of the footprints of two candidates, of `a`'s type; its
/// pixel indices in raster order.
Segment joinSegments(const BrickCandidate& a, const BrickCandidate& b);
}  // namespace brick_pose
