#pragma once
// Checks that a cloud can be registered at all, so that the search never
// runs on data it cannot handle (and never loops looking for a base).

#include <string>

#include "brick_pose/registration/point_set.h"

namespace brick_pose
{
namespace registration
{
/// Throws InputError naming `cloud_name` and the problem when the cloud is
/// empty, has fewer than 4 points, has a NaN/Inf coordinate or normal, has a
/// normal count different from its point count, or when all its points are
/// identical or collinear (no 4-point base can be drawn from such a cloud).
void validateRegistrationInput(const PointSet& cloud, const std::string& cloud_name);
}  // namespace registration
}  // namespace brick_pose
