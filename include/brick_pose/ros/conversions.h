#pragma once
// Conversions between the ROS-free core types and ROS messages that no ROS
// library does for us (images go through cv_bridge, poses through tf2_eigen):
// camera_info to intrinsics, validated field by field.

#include <string>

#include <Eigen/Geometry>
#include <geometry_msgs/Pose.h>
#include <sensor_msgs/CameraInfo.h>
#include <tf2_eigen/tf2_eigen.h>

#include "brick_pose/camera/pinhole_camera.h"

namespace brick_pose
{
namespace ros_conversions
{
/// camera_info of an undistorted (plumb_bob with zero coefficients) camera,
/// as realsense2_camera publishes for its rectified colour stream.
sensor_msgs::CameraInfo toCameraInfo(const PinholeCamera& camera, const std_msgs::Header& header);

/// Intrinsics from camera_info's K; throws InputError when K or the size is
/// unusable (the message names the field).
PinholeCamera fromCameraInfo(const sensor_msgs::CameraInfo& info);

/// tf2_eigen's conversion, returning the value.
inline Eigen::Isometry3d fromPose(const geometry_msgs::Pose& pose)
{
  Eigen::Isometry3d isometry;
  tf2::fromMsg(pose, isometry);
  return isometry;
}
}  // namespace ros_conversions
}  // namespace brick_pose
