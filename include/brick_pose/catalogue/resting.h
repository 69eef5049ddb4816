#pragma once
// A box need not stand on its bottom: on a table it may lie on a long side
// or stand on an end. Seen from above it then shows another of its faces,
// of another size, with another depth below it. restingAs() describes it as
// a type whose "top" is the face up, so that typing, registration and the
// published pose treat it like any type; Resting says which face that is.

#include <string>

#include "brick_pose/catalogue/brick_catalogue.h"

namespace brick_pose
{
/// "upright", "on_side", "on_end": the words BrickDetection.resting uses.
const char* toString(Resting resting);

/// `type` resting so, as a type whose top is the face up: on a side its
/// length x height is up and its width below; on an end its width x height
/// is up and its length below (length the longer of the two up). Named
/// "<type> lying on a side" or "<type> standing on an end"; upright it is
/// `type` itself.
BrickType restingAs(const BrickType& type, Resting resting);

/// Whether a box of this type may be published resting on a side or an
/// end: only a type without a plate colour. A brick's plate is the face its
/// gripper needs, and a brick on its side shows none.
inline bool mayRestOtherwise(const BrickType& type) { return !type.hasPlateColour(); }
}  // namespace brick_pose
