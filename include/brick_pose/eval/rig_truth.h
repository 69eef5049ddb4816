#pragma once
// SceneTruth of a synthetic rig frame: the rig's face labels are exact, so
// only the roles need deciding (a catalogue top face counts as a top only
// while it faces up) and whether each top is whole in view.

#include <Eigen/Core>

#include "brick_pose/eval/scene_truth.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace eval
{
struct RigTruthParams
{
  /// A top face is whole in view from this visible fraction on (pixels in
  /// the image and not hidden, over the face's projected area). Not 1: the
  /// face's outermost pixel row is often lost to rounding when nothing hides
  /// it or a corner grazes the image border (bench_pose's "whole top face
  /// visible" group uses the same 0.99).
  double whole_min_visible_fraction = 0.99;
  /// A catalogue top face is a top while its normal is within this of "up";
  /// a cuboid face is a side while its normal is within this of horizontal.
  double max_up_tilt_deg = 30.0;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// Faces of every brick (6 per brick, index (instance - 1) * 6 + face - 1)
/// and one support face (the ground) last. `up_in_camera` is the world's up
/// direction in the camera frame (unit).
SceneTruth rigSceneTruth(const sim::SyntheticFrame& frame, const Eigen::Vector3d& up_in_camera,
                         const RigTruthParams& params = RigTruthParams());
}  // namespace eval
}  // namespace brick_pose
