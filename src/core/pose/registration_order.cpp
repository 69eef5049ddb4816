#include "brick_pose/pose/registration_order.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
void RegistrationOrderParams::validate() const
{
  if (!(match_radius_m > 0.0)) throw ConfigError("registration order: match_radius_m must be > 0");
  if (forget_after_frames < 1) throw ConfigError("registration order: forget_after_frames must be >= 1");
}

RegistrationOrder::RegistrationOrder(const RegistrationOrderParams& params) : params_(params) { params_.validate(); }

RegistrationOrder::Remembered* RegistrationOrder::find(const BrickCandidate& candidate)
{
  Remembered* best = nullptr;
  double best_distance_m = params_.match_radius_m;
  for (Remembered& remembered : memory_)
  {
    if (remembered.type_name != candidate.type_name) continue;
    const double distance_m = (remembered.centre_m - candidate.centroid_m).norm();
    if (distance_m < best_distance_m)
    {
      best_distance_m = distance_m;
      best = &remembered;
    }
  }
  return best;
}

std::vector<std::size_t> RegistrationOrder::order(const std::vector<BrickCandidate>& candidates)
{
  ++frame_;
  memory_.erase(std::remove_if(memory_.begin(), memory_.end(),
                               [this](const Remembered& r) {
                                 return frame_ - r.last_seen_frame > params_.forget_after_frames;
                               }),
                memory_.end());
  // Frames since the last attempt; never attempted counts as forever.
  std::vector<std::int64_t> overdue(candidates.size(), std::numeric_limits<std::int64_t>::max());
  for (std::size_t i = 0; i < candidates.size(); ++i)
  {
    Remembered* remembered = find(candidates[i]);
    if (!remembered)
    {
      memory_.push_back({candidates[i].type_name, candidates[i].centroid_m, -1, frame_});
      continue;
    }
    remembered->centre_m = candidates[i].centroid_m;
    remembered->last_seen_frame = frame_;
    if (remembered->last_attempt_frame >= 0) overdue[i] = frame_ - remembered->last_attempt_frame;
  }
  std::vector<std::size_t> indices(candidates.size());
  std::iota(indices.begin(), indices.end(), 0);
  std::stable_sort(indices.begin(), indices.end(), [&](std::size_t a, std::size_t b) { return overdue[a] > overdue[b]; });
  return indices;
}

void RegistrationOrder::attempted(const BrickCandidate& candidate)
{
  if (Remembered* remembered = find(candidate)) remembered->last_attempt_frame = frame_;
}
}  // namespace brick_pose
