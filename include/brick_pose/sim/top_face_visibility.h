#pragma once
// Whether a brick's top face is wholly in view: the ground truth against
// which a detector's "complete face" claims are judged. Decided by rays to
// samples along the face's four edges, not by counting pixels, so that a
// strip hidden under a neighbour or cut by the image border is caught even
// when it is only a few pixels wide.

#include <array>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/sim/ray_caster.h"
#include "brick_pose/sim/scene.h"

namespace brick_pose
{
namespace sim
{
/// Samples per edge: at 1280x720 a 1.8 m edge seen from 0.6 m spans ~2700
/// pixels, so 64 samples leave gaps; occluders narrower than ~1/64 of an edge
/// can slip through, which the border and neighbour cases this exists for do
/// not produce.
constexpr int kTopEdgeSamples = 64;

/// Visibility of the top face of scene.bricks[brick_index] through `camera`.
TopFaceVisibility topFaceVisibility(const Scene& scene, const RayCaster& caster, const PinholeCamera& camera,
                                    int brick_index);

/// The same for any `face` of the brick, seen as the top of the type
/// restingAs() makes of the brick with that face up (its tilt_deg is then
/// the face's normal's from the world's up).
TopFaceVisibility faceVisibility(const Scene& scene, const RayCaster& caster, const PinholeCamera& camera,
                                 int brick_index, CuboidFace face);
}  // namespace sim
}  // namespace brick_pose
