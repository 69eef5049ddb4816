// rostest: the front end's result is reused only while nothing in view
// changes. The synthetic camera shows a new pile every 2 s. Every detection
// must lie on a brick of its own frame's ground truth (a reused result from
// the pile before would not), a reused result's keyframe must show the same
// pile as the frame it is published for, and frames in between must reuse
// the front end. (A pile's first detections may be reused, from its own
// first frame: under the full suite's load a later stage may drop that
// frame after the segmentation made it the keyframe.)

#include <cmath>
#include <cstdint>
#include <mutex>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include "brick_pose/BrickDetectionArray.h"
#include "brick_pose/BrickTruthArray.h"
#include "truth_matching.h"

namespace
{
using brick_pose_test::truthBrickOf;

constexpr int kPiles = 4;

/// A pile is known by its bricks' poses: the camera draws each pile afresh.
double pileKey(const brick_pose::BrickTruthArray& truth)
{
  double key = static_cast<double>(truth.bricks.size());
  for (const brick_pose::BrickTruth& brick : truth.bricks)
    key += brick.pose.position.x + 10.0 * brick.pose.position.y + 100.0 * brick.pose.position.z;
  return key;
}

class ChangeWatch
{
public:
  void onTruth(const brick_pose::BrickTruthArrayConstPtr& truth)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    truths_.add(truth);
  }

  void onDetections(const brick_pose::BrickDetectionArrayConstPtr& detections)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const brick_pose::BrickTruthArrayConstPtr truth = truths_.find(detections->header.stamp);
    if (!truth || piles_ > kPiles) return;
    const double pile = pileKey(*truth);
    if (piles_ == 0 || pile != current_pile_)
    {
      ++piles_;
      current_pile_ = pile;
    }
    ++frames_;
    if (detections->front_end_reused) countReuse(*detections, pile);
    for (const brick_pose::BrickDetection& detection : detections->detections)
    {
      ++detections_;
      if (truthBrickOf(*truth, detection) < 0) ++unmatched_;
    }
  }

  int piles() const { std::lock_guard<std::mutex> lock(mutex_); return piles_; }

  /// A reused result and the pile its keyframe showed (the keyframe's stamp
  /// is the frame's less front_end_age_s).
  void countReuse(const brick_pose::BrickDetectionArray& detections, double pile)
  {
    ++reused_frames_;
    const std::int64_t age_ns = std::llround(detections.front_end_age_s * 1e9);
    ros::Time keyframe_stamp;
    keyframe_stamp.fromNSec(detections.header.stamp.toNSec() - static_cast<std::uint64_t>(age_ns));
    const brick_pose::BrickTruthArrayConstPtr keyframe_truth = truths_.find(keyframe_stamp);
    if (!keyframe_truth) return;
    ++reused_verified_;
    if (pileKey(*keyframe_truth) != pile) ++reused_from_another_pile_;
  }

  mutable std::mutex mutex_;
  brick_pose_test::TruthByStamp truths_;
  double current_pile_ = 0.0;
  int piles_ = 0, frames_ = 0, reused_frames_ = 0, reused_verified_ = 0, reused_from_another_pile_ = 0;
  int detections_ = 0, unmatched_ = 0;
};

TEST(SceneChanges, ReusedResultsAreNeverAnEarlierPiles)
{
  ros::NodeHandle node;
  ChangeWatch watch;
  ros::Subscriber truth = node.subscribe("/camera/synthetic_camera/ground_truth", 50, &ChangeWatch::onTruth, &watch);
  ros::Subscriber detections = node.subscribe("/brick_pose/detections", 50, &ChangeWatch::onDetections, &watch);
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(180.0);
  while (watch.piles() <= kPiles && ros::WallTime::now() < deadline) ros::WallDuration(0.1).sleep();
  std::lock_guard<std::mutex> lock(watch.mutex_);
  ASSERT_GT(watch.piles_, kPiles) << "piles seen with detections";
  EXPECT_EQ(watch.reused_from_another_pile_, 0) << "reused results whose keyframe showed another pile, of "
                                                << watch.reused_verified_ << " whose keyframe's truth was kept";
  EXPECT_GT(watch.reused_verified_, watch.reused_frames_ / 2) << "reused results whose keyframe's truth was kept";
  EXPECT_EQ(watch.unmatched_, 0) << "detections on no top face of their own frame's truth, of " << watch.detections_;
  EXPECT_GT(watch.reused_frames_, watch.frames_ / 2) << "a static pile's front end must be reused";
  EXPECT_GT(watch.detections_, 0);
}
}  // namespace

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "scene_changes_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
