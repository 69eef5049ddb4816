#pragma once
// Matching the pipeline's detections to the synthetic camera's ground truth,
// for the rostests.

#include <cmath>

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
}  // namespace brick_pose_test
