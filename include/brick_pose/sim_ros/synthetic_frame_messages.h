#pragma once
// A rendered synthetic frame as the messages realsense2_camera publishes with
// align_depth:=true, plus its ground truth. Shared by the SyntheticCamera
// nodelet and the brick_pose_simulate bag writer so both publish the same thing.

#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "brick_pose/BrickTruthArray.h"
#include "brick_pose/ros/camera_topics.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
struct SyntheticFrameMessages
{
  sensor_msgs::ImagePtr color;  // rgb8
  sensor_msgs::CameraInfoPtr color_info;
  sensor_msgs::ImagePtr depth;  // 16UC1, millimetres, aligned to colour
  sensor_msgs::CameraInfoPtr depth_info;
  BrickTruthArrayPtr truth;
  /// truth_<type>_<instance>, then the ground (kTruthGroundFrame).
  std::vector<geometry_msgs::TransformStamped> truth_frames;
};

/// tf child frame of the ground the rig's scene stands on (+z up): give it
/// as support_frame to run a scene with its ground known, as the benchmark
/// does.
constexpr const char* kTruthGroundFrame = "truth_ground";

SyntheticFrameMessages toMessages(const sim::SyntheticFrame& frame, const ros::Time& stamp,
                                  const std::string& optical_frame_id);

/// tf child frame name of one ground-truth brick.
std::string truthFrameName(const sim::BrickTruth& truth);

/// camera_link -> colour optical frame, as realsense2_camera publishes it
/// (optical frame: z forward, x right, y down; camera_link: x forward, z up).
geometry_msgs::TransformStamped cameraLinkToOptical(const ros::Time& stamp, const std::string& camera_link,
                                                    const std::string& optical_frame_id);
}  // namespace brick_pose
