// rostest: a plain box lying on a side or standing on an end is published
// as its catalogue type with `resting` saying how it rests, its pose at the
// centre of the face up (checked against the camera's ground truth) and
// its dimensions that face's and the depth below it; the service, asked
// for it, answers the same.

#include <cmath>
#include <mutex>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include <brick_pose/BrickDetectionArray.h>
#include <brick_pose/BrickTruthArray.h>
#include <brick_pose/GetBrickPose.h>
#include <ros/ros.h>

#include "brick_pose/ros/conversions.h"

namespace
{
/// The first detection of a box not upright, and the truth of its frame.
class RestingWatch
{
public:
  void onTruth(const brick_pose::BrickTruthArray::ConstPtr& truth)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    latest_truth_ = truth;
  }
  void onDetections(const brick_pose::BrickDetectionArray::ConstPtr& message)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!latest_truth_) return;
    for (const brick_pose::BrickDetection& detection : message->detections)
      if (detection.resting != "upright")
      {
        if (detection.complete_face) ++complete_;
        if (found_) continue;
        found_ = detection;
        truth_ = latest_truth_;
      }
  }
  /// Detections of the box not upright published complete, over all frames.
  int complete() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return complete_;
  }
  std::optional<brick_pose::BrickDetection> found() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return found_;
  }
  brick_pose::BrickTruthArray::ConstPtr truth() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return truth_;
  }

private:
  mutable std::mutex mutex_;
  brick_pose::BrickTruthArray::ConstPtr latest_truth_, truth_;
  std::optional<brick_pose::BrickDetection> found_;
  int complete_ = 0;
};
}  // namespace

TEST(RestingBoxes, ABoxOnASideOrAnEndIsPublishedAtItsFaceUpAndSaysHowItRests)
{
  ros::NodeHandle node;
  RestingWatch watch;
  ros::Subscriber truth = node.subscribe("/camera/synthetic_camera/ground_truth", 20, &RestingWatch::onTruth, &watch);
  ros::Subscriber detections = node.subscribe("/brick_pose/detections", 20, &RestingWatch::onDetections, &watch);
  const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(120.0);
  while (!watch.found() && ros::WallTime::now() < give_up) ros::WallDuration(0.2).sleep();
  const std::optional<brick_pose::BrickDetection> found = watch.found();
  ASSERT_TRUE(found) << "no box was published resting otherwise than upright";

  // The catalogue's box_small (0.30 x 0.20 x 0.15 m) on a long side shows
  // 0.30 x 0.15 m with 0.20 m below; on an end 0.20 x 0.15 m with 0.30 m.
  EXPECT_EQ(found->type, "box_small");
  EXPECT_EQ(found->frame, "brick_box_small_" + std::to_string(found->id));
  const bool on_side = found->resting == "on_side";
  EXPECT_TRUE(on_side || found->resting == "on_end") << found->resting;
  EXPECT_NEAR(found->dimensions.x, on_side ? 0.30 : 0.20, 1e-6);
  EXPECT_NEAR(found->dimensions.y, 0.15, 1e-6);
  EXPECT_NEAR(found->dimensions.z, on_side ? 0.20 : 0.30, 1e-6);

  // The pose's origin is the centre of a face of the truth box: half the
  // box's width (on a side) or length (on an end) out from its axis, half
  // its height down from its top; z out of that face.
  ASSERT_TRUE(watch.truth());
  ASSERT_EQ(watch.truth()->bricks.size(), 1u);
  using brick_pose::ros_conversions::fromPose;
  const brick_pose::BrickTruth& box = watch.truth()->bricks.front();
  const Eigen::Isometry3d brick_T_face = fromPose(box.pose).inverse() * fromPose(found->pose.pose);
  const Eigen::Vector3d centre = brick_T_face.translation();
  const Eigen::Vector3d normal = brick_T_face.linear().col(2);
  EXPECT_NEAR(centre.z(), -0.5 * box.dimensions.z, 0.005);
  if (on_side)
  {
    EXPECT_NEAR(std::abs(centre.y()), 0.5 * box.dimensions.y, 0.005);
    EXPECT_NEAR(centre.x(), 0.0, 0.005);
    EXPECT_GT(std::abs(normal.y()), std::cos(2.0 * M_PI / 180.0));
  }
  else
  {
    EXPECT_NEAR(std::abs(centre.x()), 0.5 * box.dimensions.x, 0.005);
    EXPECT_NEAR(centre.y(), 0.0, 0.005);
    EXPECT_GT(std::abs(normal.x()), std::cos(2.0 * M_PI / 180.0));
  }

  // The service, asked for that box by its id, says how it rests.
  ASSERT_TRUE(ros::service::waitForService("/brick_pose/get_brick_pose", ros::Duration(30.0)));
  brick_pose::GetBrickPose call;
  call.request.id = found->id;
  ASSERT_TRUE(ros::service::call("/brick_pose/get_brick_pose", call));
  ASSERT_TRUE(call.response.success) << call.response.message;
  EXPECT_EQ(call.response.type, "box_small");
  EXPECT_EQ(call.response.resting, found->resting);
  EXPECT_NEAR(call.response.dimensions.z, found->dimensions.z, 1e-9);

  // Its four edges are steps down to the table: it is complete (in most
  // frames; the rig's noise is drawn afresh for each).
  ros::WallDuration(3.0).sleep();
  EXPECT_GT(watch.complete(), 0) << found->partial_reason;
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "resting_boxes_test");
  ros::AsyncSpinner spinner(1);
  spinner.start();
  return RUN_ALL_TESTS();
}
