#include "brick_pose/sim/d415_modes.h"

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace sim
{
namespace
{
struct Mode
{
  const char* name;
  int width_px;
  int height_px;
};

constexpr Mode kModes[] = {{"1280x720", 1280, 720}, {"848x480", 848, 480}, {"640x480", 640, 480},
                           {"640x360", 640, 360},   {"1920x1080", 1920, 1080}};

// Focal length of the full 1920x1080 sensor; 1280x720 gives the rig's
// long-standing 920 px.
constexpr double kFullSensorFxPx = 1380.0;
}  // namespace

const std::vector<std::string>& d415ColourModeNames()
{
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all;
    for (const Mode& mode : kModes) all.emplace_back(mode.name);
    return all;
  }();
  return names;
}

PinholeCamera d415ColourMode(const std::string& resolution)
{
  for (const Mode& mode : kModes)
  {
    if (resolution != mode.name) continue;
    PinholeCamera camera;
    camera.width_px = mode.width_px;
    camera.height_px = mode.height_px;
    camera.fx_px = camera.fy_px = kFullSensorFxPx * mode.height_px / 1080.0;
    camera.cx_px = 0.5 * mode.width_px;
    camera.cy_px = 0.5 * mode.height_px;
    return camera;
  }
  std::string known;
  for (const std::string& name : d415ColourModeNames()) known += (known.empty() ? "" : ", ") + name;
  throw ConfigError("parameter 'resolution': unknown D415 colour mode '" + resolution + "' (known: " + known + ")");
}
}  // namespace sim
}  // namespace brick_pose
