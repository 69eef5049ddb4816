#pragma once
// SceneTruth of a synthetic rig frame: the rig's face labels are exact, so
// only the roles need deciding (a catalogue top face counts as a top only
// while it faces up; the face up of a box lying on a side or standing on an
// end is the top of the type catalogue/resting.h makes of it, "box_small
// lying on a side"); whether each top is whole in view is the rig's own
// verdict on its edges plus a check of its visible fraction.

#include <Eigen/Core>

#include "brick_pose/eval/scene_truth.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace eval
{
struct RigTruthParams
{
  /// A top face is whole in view when the rig says all its edges are in
  /// the image and unhidden (BrickTruth::top_face_complete) and at least
  /// this fraction of it is visible: a box standing inside another's top
  /// leaves the edges free but hides the face. Not 1: the rounded edges of
  /// boxes and the outermost pixel row cost a little.
  double min_visible_fraction = 0.95;
  /// A catalogue top face (or a resting box's face up) is a top while its
  /// normal is within this of "up"; a cuboid face is a side while its
  /// normal is within this of horizontal.
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
