// rostest: with the launch argument support_frame, every frame the ingestion
// stage passes on carries the xy-plane of that tf frame in the camera frame.

#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/static_transform_broadcaster.h>

TEST(SupportFrame, FramesCarryThePlaneOfTheSupportFrame)
{
  // The deck lies at (0, 0.5, 1) m in the optical frame, turned 90 deg
  // about x: its +z is the camera's -y (up in the image), and its plane,
  // y = 0.5, is -y + 0.5 = 0.
  tf2_ros::StaticTransformBroadcaster broadcaster;
  geometry_msgs::TransformStamped deck;
  deck.header.stamp = ros::Time::now();
  deck.header.frame_id = "camera_color_optical_frame";
  deck.child_frame_id = "pallet_deck";
  deck.transform.translation.y = 0.5;
  deck.transform.translation.z = 1.0;
  deck.transform.rotation.x = std::sqrt(0.5);
  deck.transform.rotation.w = std::sqrt(0.5);
  broadcaster.sendTransform(deck);

  ASSERT_TRUE(ros::service::waitForService("/brick_pose/zero_copy_probe/frame_support", ros::Duration(60.0)));
  // Frames before the transform reached the ingestion stage carry none.
  std_srvs::Trigger support;
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(60.0);
  do
  {
    ros::WallDuration(0.2).sleep();
    ASSERT_TRUE(ros::service::call("/brick_pose/zero_copy_probe/frame_support", support));
  } while (!support.response.success && ros::WallTime::now() < give_up);
  ASSERT_TRUE(support.response.success) << support.response.message;
  std::istringstream numbers(support.response.message);
  double nx = NAN, ny = NAN, nz = NAN, d = NAN;
  numbers >> nx >> ny >> nz >> d;
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
