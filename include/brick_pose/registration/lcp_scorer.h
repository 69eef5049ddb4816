#pragma once
// Largest-common-pointset verification of a candidate transform: the
// fraction of (sampled) source points that land within delta of a target
// point. Candidates that can no longer beat the best score are abandoned
// part-way, which is what keeps verifying thousands of candidates cheap.

#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/registration/point_grid.h"

namespace brick_pose
{
namespace registration
{
class LcpScorer
{
public:
  /// Both vectors must outlive the scorer. radius_m > 0.
  LcpScorer(const std::vector<Eigen::Vector3d>& source_sample, const std::vector<Eigen::Vector3d>& target,
            double radius_m);

  /// Score in 0..1; returns early (with a value below score_to_beat) as soon
  /// as the candidate cannot exceed score_to_beat.
  double score(const Eigen::Isometry3d& source_to_target, double score_to_beat = 0.0) const;

  double radius() const { return radius_m_; }
  const PointGrid& targetGrid() const { return grid_; }

private:
  const std::vector<Eigen::Vector3d>& source_sample_;
  double radius_m_;
  PointGrid grid_;
};
}  // namespace registration
}  // namespace brick_pose
