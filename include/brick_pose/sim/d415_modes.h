#pragma once
// The colour streams of a D415 the rig can imitate, by name ("640x480"),
// with typical factory intrinsics per mode: the colour sensor is 1920x1080
// with fx ~1380 px, and every mode scales it to the mode's height (the 4:3
// mode crops the sides), so fx = 1380 * height / 1080.

#include <string>
#include <vector>

#include "brick_pose/camera/pinhole_camera.h"

namespace brick_pose
{
namespace sim
{
/// The modes d415ColourMode() knows, e.g. "1280x720".
const std::vector<std::string>& d415ColourModeNames();

/// Intrinsics of the named mode; throws ConfigError naming parameter
/// 'resolution' and listing the modes when the name is unknown.
PinholeCamera d415ColourMode(const std::string& resolution);
}  // namespace sim
}  // namespace brick_pose
