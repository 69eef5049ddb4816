// The tracked path: which candidate continues which previous pose, and when
// the correction of a tracked pose says the brick moved.

#include <cmath>

#include <gtest/gtest.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/pose/tracked_pose.h"

namespace brick_pose
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

/// A brick lying flat 1.2 m in front of a camera looking straight at it
/// (its z axis toward the camera).
PreviousPose brickAt(const std::string& type, double x_m, double length_m)
{
  PreviousPose previous;
  previous.type_name = type;
  previous.pose.linear() = Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  previous.pose.translation() = Eigen::Vector3d(x_m, 0.0, 1.2);
  previous.dimensions_m = Eigen::Vector3d(length_m, 0.2, 0.2);
  previous.fitness = 0.7;
  return previous;
}

BrickCandidate candidateAt(const std::string& type, double x_m, const Eigen::Vector3d& normal = -Eigen::Vector3d::UnitZ())
{
  BrickCandidate candidate;
  candidate.type_name = type;
  candidate.centroid_m = Eigen::Vector3d(x_m, 0.0, 1.2);
  candidate.normal = normal;
  return candidate;
}
}  // namespace

TEST(TrackedPose, ACandidateOnAPreviousTopFaceContinuesIt)
{
  PreviousPoses previous;
  previous.update({brickAt("green", 0.0, 0.6), brickAt("green", 0.3, 0.6)});
  // A partly hidden face: its visible centre is 25 cm along the first brick's axis.
  const auto match = previous.match(candidateAt("green", 0.24));
  ASSERT_TRUE(match.has_value());
  EXPECT_DOUBLE_EQ(match->pose.translation().x(), 0.3) << "the closer face centre wins";
  EXPECT_FALSE(previous.match(candidateAt("red", 0.0)).has_value()) << "another type";
  EXPECT_FALSE(previous.match(candidateAt("green", 1.0)).has_value()) << "off every face";
  const Eigen::Vector3d tilted = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitY()) * -Eigen::Vector3d::UnitZ();
  EXPECT_FALSE(previous.match(candidateAt("green", 0.0, tilted)).has_value()) << "a face turned 29 deg away";
}

TEST(TrackedPose, DisabledTrackingMatchesNothing)
{
  TrackedPoseParams params;
  params.enabled = false;
  PreviousPoses previous(params);
  previous.update({brickAt("green", 0.0, 0.6)});
  EXPECT_FALSE(previous.match(candidateAt("green", 0.0)).has_value());
}

TEST(TrackedPose, TheRegistrationCarriesThePoseAndItsFitness)
{
  const PreviousPose previous = brickAt("red", 0.1, 0.3);
  const BrickRegistration registration = registrationFromPrevious(previous);
  EXPECT_TRUE(registration.result.success);
  EXPECT_DOUBLE_EQ(registration.result.lcp_score, 0.7);
  EXPECT_LT((registration.pose.translation() - previous.pose.translation()).norm(), 1e-12);
  EXPECT_GT(registration.pose.linear().col(2).dot(previous.pose.linear().col(2)), 0.999999);
}

TEST(TrackedPose, OnlyACorrectionAboveTheNoiseSaysMoved)
{
  TrackedPoseParams params;
  PoseCorrection noise;
  noise.offset_m = Eigen::Vector3d(0.0003, 0.0, 0.0);
  noise.delta_in_brick.linear() = Eigen::AngleAxisd(0.1 * kPi / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_FALSE(correctionSaysMoved(noise, params));
  PoseCorrection shifted = noise;
  shifted.offset_m = Eigen::Vector3d(0.02, 0.0, 0.0);
  EXPECT_TRUE(correctionSaysMoved(shifted, params)) << "shifted 2 cm";
  PoseCorrection turned = noise;
  turned.delta_in_brick.linear() = Eigen::AngleAxisd(5.0 * kPi / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(correctionSaysMoved(turned, params)) << "turned 5 deg";
  params.moved_translation_m = 0.0;
  EXPECT_THROW(PreviousPoses{params}, ConfigError);
}
}  // namespace brick_pose
