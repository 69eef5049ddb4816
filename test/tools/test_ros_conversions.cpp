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
}  // namespace brick_pose
