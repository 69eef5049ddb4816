// Issue 14: with the tracked path, a brick that moved between two frames
// (shifted 2 cm, turned 5 deg) is registered afresh and reported at its new
// pose in that frame; a static brick stays on the tracked path.

#include <gtest/gtest.h>

#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/pose/brick_pose_estimator.h"
#include "brick_pose/pose/tracked_pose.h"
#include "brick_pose/registration/brick_symmetry.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

struct Observed
{
  RgbdFrame frame;
  sim::BrickTruth truth;
};

Observed observe(const sim::Scene& scene, std::uint64_t seed)
{
  const sim::SyntheticRig rig(PinholeCamera::d415Color1280x720(), sim::SensorModel());
  const sim::SyntheticFrame rendered = rig.render(scene, seed);
  return {makeRgbdFrame(rendered.rgb, rendered.depth_mm, rendered.camera, FrameHeader{0, "camera"}),
          rendered.truth.front()};
}

BrickPoseEstimatorParams untimedParams()
{
  BrickPoseEstimatorParams params;
  params.super4pcs.max_time_s = 600.0;
  params.partial_face_max_time_s = 600.0;
  return params;
}

/// The tracked path as the pipeline runs it: a candidate that continues the
/// previous pose is refined from it, and registered afresh when the
/// correction says it moved.
struct TrackedResult
{
  BrickPoseEstimate estimate;
  bool tracked = false;
  bool re_registered = false;
};

TrackedResult estimateTracked(const BrickPoseEstimator& estimator, const BrickCandidate& candidate,
                              const PreviousPoses& previous)
{
  TrackedResult result;
  const std::optional<PreviousPose> match = previous.match(candidate);
  if (!match)
  {
    result.estimate = estimator.estimate(candidate);
    return result;
  }
  result.tracked = true;
  result.estimate = estimator.refine(candidate, registrationFromPrevious(*match));
  if (correctionSaysMoved(result.estimate.correction, TrackedPoseParams()))
  {
    result.re_registered = true;
    result.estimate = estimator.estimate(candidate);
  }
  return result;
}
}  // namespace

TEST(TrackedMoves, AMovedBrickIsReRegisteredAndAStaticOneStaysTracked)
{
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  const FrontEnd front_end(catalogue);
  const BrickPoseEstimator estimator(catalogue, untimedParams());
  sim::SceneParams scene_params;
  scene_params.types = {"green"};
  scene_params.min_distance_m = 0.8;
  scene_params.max_distance_m = 1.0;
  sim::Scene scene = sim::SceneGenerator(catalogue, scene_params).generate(5);

  // Frame 1: a new brick, registered.
  const Observed first = observe(scene, 1);
  const FrontEndResult first_front = front_end.process(first.frame);
  ASSERT_EQ(first_front.candidates.size(), 1u);
  ASSERT_TRUE(first_front.candidates[0].complete);
  PreviousPoses previous;
  const TrackedResult initial = estimateTracked(estimator, first_front.candidates[0], previous);
  EXPECT_FALSE(initial.tracked);
  previous.update({{"green", 1, initial.estimate.pose, initial.estimate.dimensions_m, 0.7}});

  // Frame 2: nothing moved, new sensor noise: tracked, not registered again.
  const Observed still = observe(scene, 2);
  const FrontEndResult still_front = front_end.process(still.frame);
  ASSERT_EQ(still_front.candidates.size(), 1u);
  const TrackedResult unchanged = estimateTracked(estimator, still_front.candidates[0], previous);
  EXPECT_TRUE(unchanged.tracked);
  EXPECT_FALSE(unchanged.re_registered);
  const auto still_error = registration::poseErrorModuloSymmetry(unchanged.estimate.pose, still.truth.camera_T_brick);
  EXPECT_LT(still_error.rotation_deg, 0.5);
  EXPECT_LT(still_error.translation_mm(), 2.0);

  // Frame 3: the brick shifted 2 cm along its width and turned 5 deg about the vertical.
  sim::PlacedBrick& brick = scene.bricks.front();
  brick.world_T_brick.translate(Eigen::Vector3d(0.0, 0.02, 0.0));
  brick.world_T_brick.rotate(Eigen::AngleAxisd(5.0 * kPi / 180.0, Eigen::Vector3d::UnitZ()));
  const Observed moved = observe(scene, 3);
  const FrontEndResult moved_front = front_end.process(moved.frame);
  ASSERT_EQ(moved_front.candidates.size(), 1u);
  const TrackedResult followed = estimateTracked(estimator, moved_front.candidates[0], previous);
  EXPECT_TRUE(followed.tracked) << "the moved face still lies on the old one";
  EXPECT_TRUE(followed.re_registered) << "a 2 cm / 5 deg correction says it moved";
  const auto moved_error = registration::poseErrorModuloSymmetry(followed.estimate.pose, moved.truth.camera_T_brick);
  EXPECT_LT(moved_error.rotation_deg, 0.5);
  EXPECT_LT(moved_error.translation_mm(), 2.0);
}
}  // namespace brick_pose
