#pragma once
// How well a posed model explains one view of it (view_consistency.h): the
// numbers the whole-view acceptance of Super4PCS decides on.

namespace brick_pose
{
namespace registration
{
struct ViewScore
{
  /// Fraction (0..1) of the scan's trusted points that lie on the posed model
  /// surface with a normal that agrees: what of the scan the pose explains.
  double target_coverage = 0.0;
  /// Fraction (0..1) of the model points the viewpoint should see (on faces
  /// turned towards it) that the scan has, position and normal: what of the
  /// expected view the scan confirms.
  double model_coverage = 0.0;
  /// Fraction (0..1) of those expected points that lie in front of a point
  /// the scan saw behind them, on the same line of sight: the camera looked
  /// through where the pose puts a surface.
  double free_space_violation = 0.0;
  /// Model points the viewpoint should see (the model_coverage denominator).
  int expected_visible_points = 0;

  /// One number to rank poses by: all three must be good for a high value.
  double combined() const { return target_coverage * model_coverage * (1.0 - free_space_violation); }
};
}  // namespace registration
}  // namespace brick_pose
