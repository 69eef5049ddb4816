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

sensor_msgs::ImagePtr toImageMessage(const cv::Mat& image, const std::string& encoding,
                                     const std_msgs::Header& header)
{
  auto message = boost::make_shared<sensor_msgs::Image>();
  message->header = header;
  message->encoding = encoding;
  message->height = static_cast<std::uint32_t>(image.rows);
  message->width = static_cast<std::uint32_t>(image.cols);
  message->is_bigendian = 0;
  message->step = static_cast<std::uint32_t>(image.cols * image.elemSize());
  message->data.resize(static_cast<std::size_t>(message->step) * image.rows);
  for (int row = 0; row < image.rows; ++row)
    std::memcpy(&message->data[static_cast<std::size_t>(row) * message->step], image.ptr(row), message->step);
  return message;
}

geometry_msgs::Pose toPose(const Eigen::Isometry3d& pose)
{
  geometry_msgs::Pose message;
  const Eigen::Quaterniond rotation(pose.linear());
  message.position.x = pose.translation().x();
  message.position.y = pose.translation().y();
  message.position.z = pose.translation().z();
  message.orientation.x = rotation.x();
  message.orientation.y = rotation.y();
  message.orientation.z = rotation.z();
  message.orientation.w = rotation.w();
  return message;
}

geometry_msgs::Transform toTransform(const Eigen::Isometry3d& pose)
{
  const geometry_msgs::Pose as_pose = toPose(pose);
  geometry_msgs::Transform message;
  message.translation.x = as_pose.position.x;
  message.translation.y = as_pose.position.y;
  message.translation.z = as_pose.position.z;
  message.rotation = as_pose.orientation;
  return message;
}

Eigen::Isometry3d fromPose(const geometry_msgs::Pose& pose)
{
  Eigen::Isometry3d result = Eigen::Isometry3d::Identity();
  result.linear() = Eigen::Quaterniond(pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z)
                        .normalized()
                        .toRotationMatrix();
  result.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return result;
}
}  // namespace ros_conversions
}  // namespace brick_pose
