#pragma once
// Corners of a catalogue cuboid in its own frame (origin at the centre of
// the top face, x along the length, y along the width, z out of the top).
// Shared by the rig (ray casting, ground truth) and the rviz markers.

#include <array>

#include <Eigen/Core>

#include "brick_pose/catalogue/brick_catalogue.h"

namespace brick_pose
{
/// The four corners of the top face, counter-clockwise seen from +z:
/// (+x,+y), (-x,+y), (-x,-y), (+x,-y).
std::array<Eigen::Vector3d, 4> topFaceCornersInBrick(const BrickType& type);

/// The eight corners of the body: the top face's four, then the same four
/// `height_m` below.
std::array<Eigen::Vector3d, 8> cuboidCornersInBrick(const BrickType& type);
}  // namespace brick_pose
