#pragma once
// Conversions between the ROS-free core types and ROS messages.

#include <string>

#include <Eigen/Geometry>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>
#include <opencv2/core.hpp>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

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

/// Copies `image` into a message with the given encoding ("rgb8", "16UC1", ...).
sensor_msgs::ImagePtr toImageMessage(const cv::Mat& image, const std::string& encoding,
                                     const std_msgs::Header& header);

geometry_msgs::Pose toPose(const Eigen::Isometry3d& pose);
geometry_msgs::Transform toTransform(const Eigen::Isometry3d& pose);
Eigen::Isometry3d fromPose(const geometry_msgs::Pose& pose);
}  // namespace ros_conversions
}  // namespace brick_pose
