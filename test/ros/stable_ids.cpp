// rostest: on a static pile of at least six bricks, every tf frame
// brick_<type>_<id> stays attached to the same ground-truth brick, and every
// ground-truth brick keeps its frame name, over 300 consecutive frames.

#include <map>
#include <mutex>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include "brick_pose/BrickDetectionArray.h"
#include "brick_pose/BrickTruthArray.h"
#include "truth_matching.h"

namespace
{
using brick_pose_test::truthBrickOf;

constexpr int kFrames = 300;
constexpr std::size_t kMinBricks = 6;

class IdentityWatch
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
    if (!truth || frames_ >= kFrames) return;
    ++frames_;
    min_bricks_ = std::min(min_bricks_, detections->detections.size());
    for (const brick_pose::BrickDetection& detection : detections->detections)
    {
      const int brick = truthBrickOf(*truth, detection);
      if (brick < 0)
      {
        ++unmatched_;
        continue;
      }
      const auto named = truth_of_frame_.emplace(detection.frame, brick);
      if (!named.second && named.first->second != brick) ++frame_swaps_;
      const auto kept = frame_of_truth_.emplace(brick, detection.frame);
      if (!kept.second && kept.first->second != detection.frame) ++renamed_;
    }
  }

  int frames() const { std::lock_guard<std::mutex> lock(mutex_); return frames_; }

  mutable std::mutex mutex_;
  brick_pose_test::TruthByStamp truths_;
  std::map<std::string, int> truth_of_frame_;
  std::map<int, std::string> frame_of_truth_;
  int frames_ = 0, frame_swaps_ = 0, renamed_ = 0, unmatched_ = 0;
  std::size_t min_bricks_ = 1000;
};

TEST(StableIds, FramesStayWithTheirBricksFor300Frames)
{
  ros::NodeHandle node;
  IdentityWatch watch;
  ros::Subscriber truth = node.subscribe("/camera/synthetic_camera/ground_truth", 50, &IdentityWatch::onTruth, &watch);
  ros::Subscriber detections = node.subscribe("/brick_pose/detections", 50, &IdentityWatch::onDetections, &watch);
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(200.0);
  while (watch.frames() < kFrames && ros::WallTime::now() < deadline) ros::WallDuration(0.1).sleep();
  std::lock_guard<std::mutex> lock(watch.mutex_);
  ASSERT_EQ(watch.frames_, kFrames) << "frames with detections and their ground truth";
  EXPECT_GE(watch.min_bricks_, kMinBricks) << "the pile must show at least six bricks in every frame";
  EXPECT_EQ(watch.frame_swaps_, 0) << "a frame name moved to another brick";
  EXPECT_EQ(watch.renamed_, 0) << "a brick got another frame name";
  EXPECT_EQ(watch.unmatched_, 0) << "detections on no ground-truth top face";
  EXPECT_GE(watch.truth_of_frame_.size(), kMinBricks);
}
}  // namespace

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "stable_ids_test");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
