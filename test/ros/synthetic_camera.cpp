// rostest: the SyntheticCamera nodelet publishes what realsense2_camera does
// with align_depth:=true, with ground truth as a topic and as tf frames.

#include <gtest/gtest.h>

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2_ros/transform_listener.h>

#include "brick_pose/BrickTruthArray.h"

namespace
{
template <typename Message>
typename Message::ConstPtr waitFor(const std::string& topic, double timeout_s = 30.0)
{
  return ros::topic::waitForMessage<Message>(topic, ros::Duration(timeout_s));
}
}  // namespace

TEST(SyntheticCamera, PublishesRealsenseTopics)
{
  const auto color = waitFor<sensor_msgs::Image>("/camera/color/image_raw");
  ASSERT_NE(color, nullptr) << "no colour image";
  EXPECT_EQ(color->encoding, "rgb8");
  EXPECT_EQ(color->width, 1280u);
  EXPECT_EQ(color->height, 720u);
  EXPECT_EQ(color->header.frame_id, "camera_color_optical_frame");

  const auto depth = waitFor<sensor_msgs::Image>("/camera/aligned_depth_to_color/image_raw");
  ASSERT_NE(depth, nullptr) << "no aligned depth";
  EXPECT_EQ(depth->encoding, "16UC1");
  EXPECT_EQ(depth->width, color->width);

  const auto info = waitFor<sensor_msgs::CameraInfo>("/camera/aligned_depth_to_color/camera_info");
  ASSERT_NE(info, nullptr);
  EXPECT_DOUBLE_EQ(info->K[0], 920.0);
  ASSERT_NE(waitFor<sensor_msgs::CameraInfo>("/camera/color/camera_info"), nullptr);
}

TEST(SyntheticCamera, PublishesGroundTruthAsTopicAndTf)
{
  const auto truth = waitFor<brick_pose::BrickTruthArray>("/camera/synthetic_camera/ground_truth");
  ASSERT_NE(truth, nullptr);
  ASSERT_FALSE(truth->bricks.empty());
  for (const auto& brick : truth->bricks)
  {
    EXPECT_EQ(brick.type, "green");
    EXPECT_DOUBLE_EQ(brick.dimensions.x, 0.60);
  }
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  const auto& first = truth->bricks.front();
  const std::string child = "truth_green_" + std::to_string(first.instance_id);
  std::string error;
  ASSERT_TRUE(buffer.canTransform("camera_color_optical_frame", child, ros::Time(0), ros::Duration(10.0), &error))
      << error;
  const auto transform = buffer.lookupTransform("camera_color_optical_frame", child, ros::Time(0));
  // The pile does not move, so any frame's tf gives the same pose.
  EXPECT_NEAR(transform.transform.translation.x, first.pose.position.x, 1e-9);
  EXPECT_NEAR(transform.transform.translation.z, first.pose.position.z, 1e-9);
  EXPECT_TRUE(buffer.canTransform("camera_link", child, ros::Time(0), ros::Duration(5.0), &error)) << error;
}

TEST(SyntheticCamera, BadParametersLeaveTheManagerUp)
{
  // The instance in /broken_camera has an unknown brick type: it logs the
  // error (checked by the rig-config unit tests) and stays idle, while the
  // good camera in the same manager keeps publishing.
  EXPECT_FALSE(ros::topic::waitForMessage<sensor_msgs::Image>("/broken_camera/color/image_raw", ros::Duration(2.0)))
      << "a camera with an unknown brick type must not publish";
  EXPECT_NE(waitFor<sensor_msgs::Image>("/camera/color/image_raw", 10.0), nullptr) << "manager went down";
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "synthetic_camera_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
