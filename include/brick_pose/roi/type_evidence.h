#pragma once
// What tells catalogue types apart when a face is typed by its size alone
// (colour-free): the face's length and width, and the heights of the side
// faces seen below its edges. Several types can share a top (a flat and a
// tall box), and a box lying on a side or standing on an end shows a face
// near another type's top; the closest type is then a guess, and a guess is
// never published as a complete top.

#include <string>
#include <vector>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/roi/side_faces.h"

namespace brick_pose
{
/// How much worse a rival type must fit (m of error, over the face's length
/// and width and the heights of the sides reaching the support together)
/// before the evidence rules it out. On the real mOSD scenes Kinect measures
/// sides within 6 mm of the catalogue height and tops within about 12 mm.
constexpr double kTypeMarginM = 0.015;

/// The type in `fitting` closest to a face of `length_m` x `width_m` and,
/// where sides are seen to their foot, to their height. Sides reaching the
/// supporting plane are the surest; without one, a side ending on another
/// level surface (a box it stands on) still tells. Null for no types.
const BrickType* closestType(const std::vector<const BrickType*>& fitting, double length_m, double width_m,
                             std::vector<SideFaceEvidence> sides);

/// The faces of `types` other than their tops that differ from the top by
/// kTypeMarginM or more, each as a type whose "top" is that face, as tall as
/// the dimension left over, named "<type> lying on a side" or "<type>
/// standing on an end". A brick whose side is its top's size adds nothing:
/// that face looks the same.
std::vector<BrickType> lyingVariants(const std::vector<BrickType>& types);

/// Why `best` is not certain: the rivals (other types, lying variants) that
/// the evidence does not rule out, as "type uncertain: ..."; empty when it
/// rules all out. A rival is ruled out when it fits the face's size and the
/// sides reaching the support kTypeMarginM worse in all, or when a side
/// ending on anything else (only a lower bound: a lower neighbour may hide
/// the rest) is taller than it. Rivals within kTypeMarginM of `best` in every
/// dimension are the same shape: no doubt.
std::string typeDoubt(const std::vector<const BrickType*>& rivals, const BrickType& best, double length_m,
                      double width_m, const std::vector<SideFaceEvidence>& sides,
                      const SideFaceParams& params = SideFaceParams());
}  // namespace brick_pose
