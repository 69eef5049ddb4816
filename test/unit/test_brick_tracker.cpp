// Stable identities: ids follow physical bricks across frames, are never
// given to another brick, and a static brick's pose can be averaged.

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/pose/brick_tracker.h"

namespace brick_pose
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

TrackerObservation at(const std::string& type, double x_m, double y_m, double yaw_deg = 0.0)
{
  TrackerObservation observation;
  observation.type_name = type;
  observation.pose.translation() = Eigen::Vector3d(x_m, y_m, 1.2);
  observation.pose.linear() = Eigen::AngleAxisd(yaw_deg * kPi / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return observation;
}
}  // namespace

TEST(BrickTracker, IdsFollowBricksWhateverTheirOrderInTheFrame)
{
  BrickTracker tracker;
  const auto first = tracker.update({at("red", 0.0, 0.0), at("red", 0.25, 0.0), at("blue", 0.0, 0.3)}, 1.0);
  ASSERT_EQ(first.size(), 3u);
  EXPECT_EQ(first[0].id, 1u);
  EXPECT_EQ(first[1].id, 2u);
  EXPECT_EQ(first[2].id, 3u);
  EXPECT_TRUE(first[0].new_track);
  // Next frame: reordered (as a distance ranking would), slightly moved by noise.
  const auto second = tracker.update({at("blue", 0.001, 0.3), at("red", 0.251, 0.0), at("red", 0.0, 0.002)}, 1.033);
  EXPECT_EQ(second[0].id, 3u);
  EXPECT_EQ(second[1].id, 2u);
  EXPECT_EQ(second[2].id, 1u);
  EXPECT_FALSE(second[2].new_track);
  EXPECT_EQ(second[2].frames_seen, 2);
}

TEST(BrickTracker, AnotherTypeOrAFarPoseIsAnotherBrick)
{
  BrickTracker tracker;
  tracker.update({at("red", 0.0, 0.0)}, 0.0);
  const auto next = tracker.update({at("green", 0.0, 0.0), at("red", 0.2, 0.0)}, 0.1);
  EXPECT_EQ(next[0].id, 2u);
  EXPECT_EQ(next[1].id, 3u);
}

TEST(BrickTracker, AGoneBrickIsForgottenAndItsIdNeverReused)
{
  BrickTrackerParams params;
  params.forget_after_s = 1.0;
  BrickTracker tracker(params);
  tracker.update({at("red", 0.0, 0.0)}, 0.0);
  EXPECT_EQ(tracker.update({}, 0.5).size(), 0u);
  EXPECT_EQ(tracker.update({at("red", 0.0, 0.0)}, 0.9)[0].id, 1u) << "back within forget_after_s: same id";
  tracker.update({}, 2.5);
  EXPECT_EQ(tracker.trackCount(), 0u);
  EXPECT_EQ(tracker.update({at("red", 0.0, 0.0)}, 2.6)[0].id, 2u) << "forgotten: a new id, 1 is not reused";
}

TEST(BrickTracker, ALoopedBagKeepsTheIds)
{
  BrickTracker tracker;
  tracker.update({at("red", 0.0, 0.0)}, 100.0);
  EXPECT_EQ(tracker.update({at("red", 0.0, 0.0)}, 10.0)[0].id, 1u) << "time went back: the brick is still there";
}

TEST(BrickTracker, SmoothingAveragesAStaticBrickAndFollowsAMovedOne)
{
  BrickTrackerParams params;
  params.smoothing_weight = 0.1;
  params.static_translation_m = 0.005;
  BrickTracker smoothed(params);
  BrickTracker raw;
  std::mt19937 random(3);
  std::normal_distribution<double> noise_m(0.0, 0.001);
  double raw_error = 0.0, smoothed_error = 0.0;
  for (int frame = 0; frame < 200; ++frame)
  {
    const TrackerObservation observation = at("red", 0.1 + noise_m(random), 0.2 + noise_m(random));
    const double stamp_s = frame / 30.0;
    const auto a = smoothed.update({observation}, stamp_s);
    const auto b = raw.update({observation}, stamp_s);
    if (frame < 50) continue;
    smoothed_error += (a[0].pose.translation() - Eigen::Vector3d(0.1, 0.2, 1.2)).norm();
    raw_error += (b[0].pose.translation() - Eigen::Vector3d(0.1, 0.2, 1.2)).norm();
  }
  EXPECT_LT(smoothed_error, 0.4 * raw_error);
  // A real move (2 cm) is followed at once, not averaged away.
  const auto moved = smoothed.update({at("red", 0.12, 0.2)}, 10.0);
  EXPECT_NEAR(moved[0].pose.translation().x(), 0.12, 1e-9);
  EXPECT_EQ(moved[0].frames_averaged, 1);
}

TEST(BrickTracker, AHalfTurnOfASymmetricTopIsTheSameOrientationWhenAveraging)
{
  BrickTrackerParams params;
  params.smoothing_weight = 0.5;
  BrickTracker tracker(params);
  tracker.update({at("red", 0.0, 0.0, 10.0)}, 0.0);
  const auto next = tracker.update({at("red", 0.0, 0.0, 190.0)}, 0.1);
  const double yaw_deg = std::atan2(next[0].pose.linear()(1, 0), next[0].pose.linear()(0, 0)) * 180.0 / kPi;
  EXPECT_NEAR(yaw_deg, 10.0, 1e-6);
  EXPECT_EQ(next[0].frames_averaged, 2);
}

TEST(BrickTracker, RejectsBadParameters)
{
  BrickTrackerParams params;
  params.smoothing_weight = 0.0;
  EXPECT_THROW(BrickTracker{params}, ConfigError);
  params = BrickTrackerParams();
  params.match_distance_m = -1.0;
  EXPECT_THROW(BrickTracker{params}, ConfigError);
}
}  // namespace brick_pose
