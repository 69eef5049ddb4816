#pragma once
// A synthetic rig frame dressed as an mOSD scene (labels 1 for the ground,
// 10 * (i + 2) for brick i, 0 where the sensor has no depth), so that the
// mOSD ground-truth extraction can be checked against the rig's exact truth.

#include <string>

#include "brick_pose/eval/mosd_scene.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace eval
{
/// Object number (label / 10) that brick `instance_id` (1-based) gets.
inline int mosdObjectOfRigInstance(int instance_id) { return instance_id + 1; }

MosdScene mosdSceneFromRig(const sim::SyntheticFrame& frame, const std::string& name);
}  // namespace eval
}  // namespace brick_pose
