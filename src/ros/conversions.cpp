#include "brick_pose/ros/conversions.h"

#include <cstring>

#include <boost/make_shared.hpp>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace ros_conversions
{
sensor_msgs::CameraInfo toCameraInfo(const PinholeCamera& camera, const std_msgs::Header& header)
{
  sensor_msgs::CameraInfo info;
  info.header = header;
  info.width = static_cast<std::uint32_t>(camera.width_px);
  info.height = static_cast<std::uint32_t>(camera.height_px);
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {camera.fx_px, 0.0, camera.cx_px, 0.0, camera.fy_px, camera.cy_px, 0.0, 0.0, 1.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  info.P = {camera.fx_px, 0.0, camera.cx_px, 0.0, 0.0, camera.fy_px, camera.cy_px, 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

PinholeCamera fromCameraInfo(const sensor_msgs::CameraInfo& info)
{
  PinholeCamera camera;
  camera.width_px = static_cast<int>(info.width);
  camera.height_px = static_cast<int>(info.height);
  camera.fx_px = info.K[0];
  camera.fy_px = info.K[4];
  camera.cx_px = info.K[2];
  camera.cy_px = info.K[5];
  try
  {
    camera.validate();
  }
  catch (const ConfigError& e)
  {
    throw InputError(std::string("camera_info: ") + e.what());
  }
  return camera;
}

}  // namespace ros_conversions
}  // namespace brick_pose
