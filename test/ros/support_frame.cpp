// rostest: with the launch argument support_frame, every frame the ingestion
// stage passes on carries the xy-plane of that tf frame in the camera frame.

#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "brick_pose/BrickDetectionArray.h"

TEST(SupportFrame, FramesCarryThePlaneOfTheSupportFrame)
{
  const auto detections =
      ros::topic::waitForMessage<brick_pose::BrickDetectionArray>("/brick_pose/detections", ros::Duration(60.0));
  ASSERT_NE(detections, nullptr) << "the pipeline published no detections";
  ASSERT_TRUE(ros::service::waitForService("/brick_pose/zero_copy_probe/frame_support", ros::Duration(10.0)));
  std_srvs::Trigger support;
  ASSERT_TRUE(ros::service::call("/brick_pose/zero_copy_probe/frame_support", support));
  ASSERT_TRUE(support.response.success) << support.response.message;
  std::istringstream numbers(support.response.message);
  double nx = NAN, ny = NAN, nz = NAN, d = NAN;
  numbers >> nx >> ny >> nz >> d;
  // The deck (support_frame.test) lies at (0, 0.5, 1) m in the optical
  // frame, turned 90 deg about x: its +z is the camera's -y (up in the
  // image), and the plane y = 0.5 is -y + 0.5 = 0.
  EXPECT_NEAR(nx, 0.0, 1e-6) << support.response.message;
  EXPECT_NEAR(ny, -1.0, 1e-6) << support.response.message;
  EXPECT_NEAR(nz, 0.0, 1e-6) << support.response.message;
  EXPECT_NEAR(d, 0.5, 1e-6) << support.response.message;
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "support_frame_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
