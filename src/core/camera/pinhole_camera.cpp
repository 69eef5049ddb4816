#include "brick_pose/camera/pinhole_camera.h"

#include <cmath>
#include <sstream>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
PinholeCamera PinholeCamera::d415Color1280x720()
{
  PinholeCamera camera;
  camera.width_px = 1280;
  camera.height_px = 720;
  camera.fx_px = 920.0;
  camera.fy_px = 920.0;
  camera.cx_px = 640.0;
  camera.cy_px = 360.0;
  return camera;
}

void PinholeCamera::validate() const
{
  auto fail = [](const std::string& field, double value, const std::string& rule) {
    std::ostringstream text;
    text << "camera intrinsics: " << field << " = " << value << " " << rule;
    throw ConfigError(text.str());
  };
  if (width_px <= 0) fail("width", width_px, "must be > 0");
  if (height_px <= 0) fail("height", height_px, "must be > 0");
  if (!(fx_px > 0.0) || !std::isfinite(fx_px)) fail("fx", fx_px, "must be a finite value > 0");
  if (!(fy_px > 0.0) || !std::isfinite(fy_px)) fail("fy", fy_px, "must be a finite value > 0");
  // The principal point of a real camera lies inside the image; one far
  // outside means the camera_info fields were mixed up.
  if (!std::isfinite(cx_px) || cx_px < -width_px || cx_px > 2.0 * width_px)
    fail("cx", cx_px, "must lie near the image (0 .. width)");
  if (!std::isfinite(cy_px) || cy_px < -height_px || cy_px > 2.0 * height_px)
    fail("cy", cy_px, "must lie near the image (0 .. height)");
}

bool PinholeCamera::contains(double u_px, double v_px, double margin_px) const
{
  const double low = margin_px - 0.5;
  return u_px > low && v_px > low && u_px < width_px - 1 - low && v_px < height_px - 1 - low;
}

PinholeCamera PinholeCamera::scaled(double factor) const
{
  PinholeCamera camera = *this;
  camera.width_px = static_cast<int>(std::lround(width_px * factor));
  camera.height_px = static_cast<int>(std::lround(height_px * factor));
  camera.fx_px = fx_px * factor;
  camera.fy_px = fy_px * factor;
  // Pixel centres sit at integer coordinates, so the principal point scales
  // about the image corner at (-0.5, -0.5).
  camera.cx_px = (cx_px + 0.5) * factor - 0.5;
  camera.cy_px = (cy_px + 0.5) * factor - 0.5;
  return camera;
}
}  // namespace brick_pose
