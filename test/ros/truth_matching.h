#pragma once
// Matching the pipeline's detections to the synthetic camera's ground truth,
// for the rostests.

#include <cmath>
#include <map>

#include <ros/time.h>

#include "brick_pose/BrickDetection.h"
#include "brick_pose/BrickTruthArray.h"
#include "brick_pose/ros/conversions.h"

namespace brick_pose_test
{
/// The ground-truth brick whose top face holds a detection's centre (within
/// 3 cm of its plane, inside the face); -1 when none does.
inline int truthBrickOf(const brick_pose::BrickTruthArray& truth, const brick_pose::BrickDetection& detection)
{
  using brick_pose::ros_conversions::fromPose;
  const Eigen::Vector3d centre = fromPose(detection.pose.pose).translation();
  for (const brick_pose::BrickTruth& brick : truth.bricks)
  {
    const Eigen::Vector3d in_brick = fromPose(brick.pose).inverse() * centre;
    if (brick.type == detection.type && std::abs(in_brick.z()) < 0.03 &&
        std::abs(in_brick.x()) < 0.5 * brick.dimensions.x && std::abs(in_brick.y()) < 0.5 * brick.dimensions.y)
      return brick.instance_id;
  }
  return -1;
}
/// The camera's latest ground-truth messages by stamp, for pairing each
/// detections message with the truth of its own frame. Not locked: the
/// watch that owns it locks around both calls.
class TruthByStamp
{
public:
  void add(const brick_pose::BrickTruthArrayConstPtr& truth)
  {
    by_stamp_[truth->header.stamp] = truth;
    while (by_stamp_.size() > kKept) by_stamp_.erase(by_stamp_.begin());
  }

  /// Null when no truth of that stamp is kept.
  brick_pose::BrickTruthArrayConstPtr find(const ros::Time& stamp) const
  {
    const auto found = by_stamp_.find(stamp);
    return found == by_stamp_.end() ? nullptr : found->second;
  }

private:
  static constexpr std::size_t kKept = 200;  // several seconds at 30 Hz
  std::map<ros::Time, brick_pose::BrickTruthArrayConstPtr> by_stamp_;
};
}  // namespace brick_pose_test
