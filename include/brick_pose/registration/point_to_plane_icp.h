#pragma once
// A short point-to-plane ICP of scan points onto a model surface with
// normals, pairing only points whose normals agree. Used on the pose
// hypotheses of a whole-view registration (a candidate and its near-symmetric
// alternatives) to give each its best local fit before they are compared:
// a wrong hypothesis left a few centimetres off would look worse than it is
// and make the right-vs-wrong margin look larger than it is.

#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/registration/point_grid.h"
#include "brick_pose/registration/point_set.h"

namespace brick_pose
{
namespace registration
{
struct PointToPlaneParams
{
  double radius_m = 0.03;  ///< pairs farther apart are ignored
  double max_normal_difference_deg = 30.0;
  int iterations = 6;
  double min_step_m = 1e-5;  ///< convergence: translation of one step
  /// Pairs farther off the plane than 3 robust standard deviations, and
  /// than this, are left out of each step.
  double min_trim_offset_m = 0.004;
};

/// The refined model -> target transform. `model_grid` indexes model.points
/// with a max radius of at least params.radius_m; target points need unit
/// normals (`target_indices` selects which take part).
Eigen::Isometry3d refinePointToPlane(const PointSet& model, const PointGrid& model_grid, const PointSet& target,
                                     const std::vector<int>& target_indices, const Eigen::Isometry3d& model_to_target,
                                     const PointToPlaneParams& params);
}  // namespace registration
}  // namespace brick_pose
