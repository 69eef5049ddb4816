// The ROS adapters' conversions, without a roscore: camera_info in both
// directions (with the errors a broken driver would cause) and images.

#include <gtest/gtest.h>

#include <cmath>

#include "brick_pose/common/errors.h"
#include "brick_pose/ros/conversions.h"

namespace brick_pose
{
namespace
{
std::string inputErrorOf(const sensor_msgs::CameraInfo& info)
{
  try
  {
    ros_conversions::fromCameraInfo(info);
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(RosConversions, CameraInfoRoundTrip)
{
  const PinholeCamera camera = PinholeCamera::d415Color1280x720();
  const sensor_msgs::CameraInfo info = ros_conversions::toCameraInfo(camera, std_msgs::Header());
  const PinholeCamera back = ros_conversions::fromCameraInfo(info);
  EXPECT_EQ(back.width_px, 1280);
  EXPECT_DOUBLE_EQ(back.fx_px, camera.fx_px);
  EXPECT_DOUBLE_EQ(back.cy_px, camera.cy_px);
}

TEST(RosConversions, BrokenCameraInfoIsNamed)
{
  sensor_msgs::CameraInfo empty;  // what an uncalibrated or missing driver sends: all zeros
  EXPECT_NE(inputErrorOf(empty).find("camera_info"), std::string::npos);
  sensor_msgs::CameraInfo zero_focal = ros_conversions::toCameraInfo(PinholeCamera::d415Color1280x720(), {});
  zero_focal.K[0] = 0.0;
  EXPECT_NE(inputErrorOf(zero_focal).find("fx"), std::string::npos) << inputErrorOf(zero_focal);
  sensor_msgs::CameraInfo nan_focal = ros_conversions::toCameraInfo(PinholeCamera::d415Color1280x720(), {});
  nan_focal.K[4] = std::nan("");
  EXPECT_NE(inputErrorOf(nan_focal).find("fy"), std::string::npos) << inputErrorOf(nan_focal);
}

TEST(RosConversions, ImageMessageKeepsPixelsAndEncoding)
{
  cv::Mat depth(3, 5, CV_16UC1);
  for (int v = 0; v < depth.rows; ++v)
    for (int u = 0; u < depth.cols; ++u)
      depth.at<unsigned short>(v, u) = static_cast<unsigned short>(1000 + 10 * v + u);
  std_msgs::Header header;
  header.frame_id = "camera_color_optical_frame";
  const sensor_msgs::ImagePtr message = ros_conversions::toImageMessage(depth(cv::Rect(1, 0, 3, 3)), "16UC1", header);
  EXPECT_EQ(message->encoding, "16UC1");
  EXPECT_EQ(message->width, 3u);
  EXPECT_EQ(message->step, 6u);
  const auto* pixels = reinterpret_cast<const unsigned short*>(message->data.data());
  EXPECT_EQ(pixels[0], 1001);
  EXPECT_EQ(pixels[3 * 2 + 2], 1023) << "row 2, column 2 of the view";
  EXPECT_EQ(message->header.frame_id, "camera_color_optical_frame");
}

TEST(RosConversions, PoseRoundTrip)
{
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0.1, -0.2, 1.3);
  EXPECT_TRUE(ros_conversions::fromPose(ros_conversions::toPose(pose)).isApprox(pose, 1e-12));
}
}  // namespace brick_pose
