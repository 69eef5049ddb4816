#pragma once
// Checks a pose of a model against one view of it: a scan seen from a known
// viewpoint (a depth camera's centre). A pose that only makes some points
// meet (the largest common pointset of 4PCS) is easily fooled by a cuboid's
// near-symmetries, e.g. a quarter turn about the long axis of a brick with a
// 0.2 x 0.2 cross-section maps its top onto a side and its end onto itself.
// Here a pose has to pass three tests, each of which such a wrong pose fails:
//  - target coverage: scan points lie on the model surface *and* their
//    normals agree with the model's;
//  - model coverage: the model faces turned towards the viewpoint (a convex
//    model hides exactly its back faces) are seen in the scan;
//  - free space: no such face lies in front of a point the scan observed
//    behind it on the same line of sight.
// Only scan points whose normals the caller trusts (not edges, not flying
// pixels, not grazing surfaces; see whole_view_registration.cpp) count in the
// target coverage and give free-space evidence; any scan point with a normal
// that agrees confirms a model point as seen.

#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/registration/point_grid.h"
#include "brick_pose/registration/point_set.h"
#include "brick_pose/registration/view_score.h"

namespace brick_pose
{
namespace registration
{
struct ViewConsistencyParams
{
  /// The scan's viewpoint in the target frame (the camera centre).
  Eigen::Vector3d viewpoint_m = Eigen::Vector3d::Zero();
  /// A scan point and a model point match within this distance.
  double match_radius_m = 0.01;
  /// A model point counts as seen when a scan point with an agreeing normal
  /// lies within this distance (0: match_radius_m). It may be wider than the
  /// match radius: that bounds how far a scan point lies off the surface,
  /// whereas this must span the gaps of an evenly thinned scan, whose points
  /// can lie up to about two spacings from a spot of a face that was seen.
  double seen_radius_m = 0.0;
  /// ... and when their normals differ by at most this.
  double max_normal_difference_deg = 30.0;
  /// A model point counts as seen from the viewpoint when its normal is
  /// turned towards it with at least this cosine (grazing faces return little
  /// depth on a stereo camera and are not required).
  double min_visible_cos = 0.3;
  /// A model point in front of an observed scan point by more than this
  /// violates free space (depth noise and flying pixels stay below it).
  double free_space_margin_m = 0.02;
};

class ViewConsistency
{
public:
  /// `model` (model frame) and `target` (scan, target frame) need unit
  /// normals, the target's oriented towards the viewpoint; `trusted` lists
  /// the target points to use. `model_sample` is a sparser subset of the
  /// model for the model-side tests. The clouds must outlive this object.
  /// Throws ConfigError for a non-positive radius.
  ViewConsistency(const PointSet& model, const PointSet& model_sample, const PointSet& target,
                  std::vector<int> trusted, const ViewConsistencyParams& params);
  // Holds grids over its own members' storage.
  ViewConsistency(const ViewConsistency&) = delete;
  ViewConsistency& operator=(const ViewConsistency&) = delete;

  /// Target coverage alone (the cheap test for the search): returns early,
  /// below score_to_beat, as soon as the pose cannot exceed it. With
  /// max_points > 0, on about that many trusted points spread over the scan.
  double targetCoverage(const Eigen::Isometry3d& model_to_target, double score_to_beat = 0.0,
                        int max_points = 0) const;

  /// All three tests.
  ViewScore evaluate(const Eigen::Isometry3d& model_to_target) const;

  /// Indices of model points turned towards the viewpoint with at least
  /// min_cos at this pose (a convex model's visible part).
  std::vector<int> facingModelPoints(const Eigen::Isometry3d& model_to_target, double min_cos) const;

  /// The scan points used (the coverage denominators).
  const std::vector<int>& trustedTargetPoints() const { return trusted_; }
  const PointGrid& modelGrid() const { return model_grid_; }
  const PointSet& model() const { return model_; }
  const PointSet& target() const { return target_; }
  const ViewConsistencyParams& params() const { return params_; }

private:
  bool targetPointMatched(int target_index, const Eigen::Isometry3d& target_to_model) const;
  double modelCoverage(const Eigen::Isometry3d& model_to_target, const std::vector<int>& expected) const;
  double freeSpaceViolation(const Eigen::Isometry3d& model_to_target, const std::vector<int>& expected) const;

  const PointSet& model_;
  const PointSet& model_sample_;
  const PointSet& target_;
  ViewConsistencyParams params_;
  double seen_radius_m_;
  double min_normal_cos_ = 0.0;
  std::vector<int> trusted_;
  std::vector<Eigen::Vector3d> trusted_points_;
  PointGrid model_grid_;
  PointGrid target_grid_;  // over all target points: seen is seen
  // Lines of sight: every target point projected onto the plane at unit
  // distance along the mean viewing direction, in a grid of angular cells.
  Eigen::Matrix3d sight_frame_ = Eigen::Matrix3d::Identity();  // rows: across, across, along
  std::vector<Eigen::Vector3d> sight_points_;  // (x / z, y / z, 0)
  std::vector<double> sight_range_m_;  // distance from the viewpoint
  double sight_radius_ = 0.0;  // angular search radius (tangent)
  PointGrid sight_grid_;
};
}  // namespace registration
}  // namespace brick_pose
