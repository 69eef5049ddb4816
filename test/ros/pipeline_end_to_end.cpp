// rostest: the whole pipeline on the synthetic D415. The service returns each
// brick within 1 degree and 3 mm of ground truth, explains a request it cannot
// serve, and the pipeline survives malformed frames.

#include <gtest/gtest.h>

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Empty.h>

#include "brick_pose/BrickDetectionArray.h"
#include "brick_pose/BrickTruthArray.h"
#include "brick_pose/GetBrickPose.h"
#include "brick_pose/registration/brick_symmetry.h"
#include "brick_pose/ros/conversions.h"

namespace
{
using brick_pose::ros_conversions::fromPose;

const char* const kService = "/brick_pose/get_brick_pose";
const char* const kTruth = "/camera/synthetic_camera/ground_truth";

brick_pose::BrickTruthArrayConstPtr currentTruth()
{
  return ros::topic::waitForMessage<brick_pose::BrickTruthArray>(kTruth, ros::Duration(30.0));
}

/// Detections of a frame stamped after `after` (so they come from the current scene).
brick_pose::BrickDetectionArrayConstPtr detectionsAfter(const ros::Time& after)
{
  for (int i = 0; i < 200; ++i)
  {
    const auto detections =
        ros::topic::waitForMessage<brick_pose::BrickDetectionArray>("/brick_pose/detections", ros::Duration(30.0));
    if (!detections) return nullptr;
    if (detections->header.stamp > after && !detections->detections.empty()) return detections;
  }
  return nullptr;
}

brick_pose::GetBrickPose::Response callService(const std::string& type, const std::string& policy = "")
{
  brick_pose::GetBrickPose call;
  call.request.type = type;
  call.request.policy = policy;
  call.request.max_age_s = 5.0;
  EXPECT_TRUE(ros::service::call(kService, call));
  return call.response;
}

void expectPoseMatchesTruth(const brick_pose::BrickTruthArray& truth, int scene)
{
  ASSERT_EQ(truth.bricks.size(), 1u);
  const auto& brick = truth.bricks.front();
  const auto response = callService(brick.type, "nearest");
  ASSERT_TRUE(response.success) << "scene " << scene << ": " << response.message;
  EXPECT_EQ(response.type, brick.type);
  EXPECT_EQ(response.pose.header.frame_id, "camera_color_optical_frame");
  const auto error = brick_pose::registration::poseErrorModuloSymmetry(fromPose(response.pose.pose), fromPose(brick.pose));
  EXPECT_LT(error.rotation_deg, 1.0) << "scene " << scene << " " << brick.type;
  EXPECT_LT(error.translation_mm(), 3.0) << "scene " << scene << " " << brick.type;
  std::printf("scene %d: %s within %.3f deg and %.2f mm of ground truth\n", scene, brick.type.c_str(),
              error.rotation_deg, error.translation_mm());
}

void nextScene()
{
  std_srvs::Empty call;
  ASSERT_TRUE(ros::service::call("/camera/synthetic_camera/next_scene", call));
}
}  // namespace

TEST(PipelineEndToEnd, ServiceReturnsEachBrickNearGroundTruth)
{
  ASSERT_TRUE(ros::service::waitForService(kService, ros::Duration(60.0)));
  for (int scene = 0; scene < 4; ++scene)
  {
    if (scene > 0) nextScene();
    const ros::Time changed = ros::Time::now();
    ASSERT_NE(detectionsAfter(changed), nullptr) << "no detections for scene " << scene;
    const auto truth = currentTruth();
    ASSERT_NE(truth, nullptr);
    expectPoseMatchesTruth(*truth, scene);
  }
}

TEST(PipelineEndToEnd, RequestsThatCannotBeServedSayWhy)
{
  ASSERT_NE(detectionsAfter(ros::Time::now()), nullptr);
  const auto unknown = callService("purple");
  EXPECT_FALSE(unknown.success);
  EXPECT_NE(unknown.message.find("unknown brick type 'purple'"), std::string::npos) << unknown.message;

  const auto absent = callService("orange");  // the scenes hold red and green bricks only
  EXPECT_FALSE(absent.success);
  EXPECT_NE(absent.message.find("no orange brick"), std::string::npos) << absent.message;

  const auto bad_policy = callService("", "heaviest");
  EXPECT_FALSE(bad_policy.success);
  EXPECT_NE(bad_policy.message.find("heaviest"), std::string::npos) << bad_policy.message;

  brick_pose::GetBrickPose bad_frame;
  bad_frame.request.target_frame = "no_such_frame";
  ASSERT_TRUE(ros::service::call(kService, bad_frame));
  EXPECT_FALSE(bad_frame.response.success);
  EXPECT_NE(bad_frame.response.message.find("tf"), std::string::npos) << bad_frame.response.message;

  brick_pose::GetBrickPose too_old;
  too_old.request.max_age_s = 1e-6;
  ASSERT_TRUE(ros::service::call(kService, too_old));
  EXPECT_FALSE(too_old.response.success);
  EXPECT_NE(too_old.response.message.find("too old"), std::string::npos) << too_old.response.message;
}

TEST(PipelineEndToEnd, SurvivesMalformedFrames)
{
  ros::NodeHandle node("/camera");
  ros::Publisher color = node.advertise<sensor_msgs::Image>("color/image_raw", 5);
  ros::Publisher depth = node.advertise<sensor_msgs::Image>("aligned_depth_to_color/image_raw", 5);
  ros::Publisher info = node.advertise<sensor_msgs::CameraInfo>("color/camera_info", 5);
  ros::WallDuration(1.0).sleep();  // let the pipeline connect
  for (int i = 0; i < 10; ++i)
  {
    std_msgs::Header header;
    header.stamp = ros::Time::now();
    header.frame_id = "camera_color_optical_frame";
    sensor_msgs::Image bad_color;
    bad_color.header = header;
    bad_color.encoding = i % 2 ? "bgr8" : "mono8";
    bad_color.width = 4 + i;
    bad_color.height = 3;
    bad_color.step = bad_color.width * (i % 2 ? 3 : 1);
    bad_color.data.assign(bad_color.step * bad_color.height, 0);
    sensor_msgs::Image bad_depth = bad_color;
    bad_depth.encoding = i % 3 ? "32FC1" : "rgb8";
    bad_depth.data.clear();  // shorter than step x height
    sensor_msgs::CameraInfo zero_info;
    zero_info.header = header;
    zero_info.width = bad_color.width;
    zero_info.height = bad_color.height;
    color.publish(bad_color);
    depth.publish(bad_depth);
    info.publish(zero_info);
    ros::WallDuration(0.05).sleep();
  }
  // The pipeline keeps going: a later good frame still gives the right pose.
  nextScene();
  const ros::Time changed = ros::Time::now();
  ASSERT_NE(detectionsAfter(changed), nullptr) << "no detections after the malformed frames";
  const auto truth = currentTruth();
  ASSERT_NE(truth, nullptr);
  expectPoseMatchesTruth(*truth, 99);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "pipeline_end_to_end_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
