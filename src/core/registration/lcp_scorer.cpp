#include "brick_pose/registration/lcp_scorer.h"

namespace brick_pose
{
namespace registration
{
LcpScorer::LcpScorer(const std::vector<Eigen::Vector3d>& source_sample, const std::vector<Eigen::Vector3d>& target,
                     double radius_m)
  : source_sample_(source_sample), radius_m_(radius_m), grid_(target, radius_m)
{
}

double LcpScorer::score(const Eigen::Isometry3d& source_to_target, double score_to_beat) const
{
  const int n = static_cast<int>(source_sample_.size());
  if (n == 0)
    return 0.0;
  const double count_to_beat = score_to_beat * n;
  int inliers = 0;
  for (int i = 0; i < n; ++i)
  {
    if (grid_.anyWithin(source_to_target * source_sample_[i], radius_m_))
      ++inliers;
    else if (inliers + (n - i - 1) <= count_to_beat)
      return static_cast<double>(inliers) / n;  // cannot beat it any more
  }
  return static_cast<double>(inliers) / n;
}
}  // namespace registration
}  // namespace brick_pose
