#include "brick_pose/pose/brick_tracker.h"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace
{

double angleBetweenDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * kRadToDeg;
}

double rotationAngleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b)
{
  return Eigen::AngleAxisd(a.transpose() * b).angle() * kRadToDeg;
}

/// The brick turned by a half-turn about its z axis is the same brick (its
/// top face is symmetric): of the two, the orientation closest to `reference`.
Eigen::Matrix3d closestSymmetric(const Eigen::Matrix3d& rotation, const Eigen::Matrix3d& reference)
{
  const Eigen::Matrix3d turned = rotation * Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return rotationAngleDeg(turned, reference) < rotationAngleDeg(rotation, reference) ? turned : rotation;
}
}  // namespace

void BrickTrackerParams::validate() const
{
  if (!(match_distance_m > 0.0)) throw ConfigError("brick tracker: match_distance_m must be > 0");
  if (!(match_angle_deg > 0.0 && match_angle_deg <= 180.0))
    throw ConfigError("brick tracker: match_angle_deg must be in (0, 180]");
  if (!(forget_after_s >= 0.0)) throw ConfigError("brick tracker: forget_after_s must be >= 0");
  if (!(smoothing_weight > 0.0 && smoothing_weight <= 1.0))
    throw ConfigError("brick tracker: smoothing_weight must be in (0, 1]");
  if (!(static_translation_m >= 0.0)) throw ConfigError("brick tracker: static_translation_m must be >= 0");
  if (!(static_rotation_deg >= 0.0)) throw ConfigError("brick tracker: static_rotation_deg must be >= 0");
}

BrickTracker::BrickTracker(const BrickTrackerParams& params) : params_(params) { params_.validate(); }

bool BrickTracker::matches(const Track& track, const TrackerObservation& observation) const
{
  return track.type_name == observation.type_name &&
         (track.pose.translation() - observation.pose.translation()).norm() <= params_.match_distance_m &&
         angleBetweenDeg(track.pose.linear().col(2), observation.pose.linear().col(2)) <= params_.match_angle_deg;
}

void BrickTracker::follow(Track& track, const TrackerObservation& observation, double stamp_s)
{
  const Eigen::Matrix3d rotation = closestSymmetric(observation.pose.linear(), track.pose.linear());
  const bool is_static =
      (observation.pose.translation() - track.pose.translation()).norm() <= params_.static_translation_m &&
      rotationAngleDeg(rotation, track.pose.linear()) <= params_.static_rotation_deg;
  if (params_.smoothing_weight < 1.0 && is_static)
  {
    // Weight of the new pose: 1/n for the first frames (a plain mean), then
    // the configured exponential weight.
    const double weight = std::max(params_.smoothing_weight, 1.0 / (track.frames_averaged + 1));
    const Eigen::Quaterniond average = Eigen::Quaterniond(track.pose.linear()).slerp(weight, Eigen::Quaterniond(rotation));
    track.pose.translation() += weight * (observation.pose.translation() - track.pose.translation());
    track.pose.linear() = average.normalized().toRotationMatrix();
    ++track.frames_averaged;
  }
  else
  {
    // Keep the published orientation continuous across the half-turn symmetry
    // only when smoothing; otherwise publish the observation as measured.
    track.pose = observation.pose;
    track.frames_averaged = 1;
  }
  track.last_seen_s = stamp_s;
  ++track.frames_seen;
}

std::vector<TrackedBrick> BrickTracker::update(const std::vector<TrackerObservation>& observations, double stamp_s)
{
  if (started_ && stamp_s < last_stamp_s_)
    for (Track& track : tracks_) track.last_seen_s = stamp_s;  // time restarted: a looped bag
  started_ = true;
  last_stamp_s_ = stamp_s;
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [&](const Track& track) { return stamp_s - track.last_seen_s > params_.forget_after_s; }),
                tracks_.end());

  // Closest pairs first, so that two bricks side by side do not swap ids.
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t o = 0; o < observations.size(); ++o)
    for (std::size_t t = 0; t < tracks_.size(); ++t)
      if (matches(tracks_[t], observations[o]))
        pairs.emplace_back((tracks_[t].pose.translation() - observations[o].pose.translation()).norm(), o, t);
  std::sort(pairs.begin(), pairs.end());
  std::vector<int> track_of(observations.size(), -1);
  std::vector<bool> track_taken(tracks_.size(), false);
  for (const auto& [distance_m, o, t] : pairs)
    if (track_of[o] < 0 && !track_taken[t])
    {
      track_of[o] = static_cast<int>(t);
      track_taken[t] = true;
    }

  std::vector<TrackedBrick> result(observations.size());
  const std::size_t known = tracks_.size();
  for (std::size_t o = 0; o < observations.size(); ++o)
  {
    if (track_of[o] >= 0)
    {
      Track& track = tracks_[static_cast<std::size_t>(track_of[o])];
      follow(track, observations[o], stamp_s);
      result[o] = {track.id, track.pose, false, track.frames_seen, track.frames_averaged};
      continue;
    }
    tracks_.push_back({next_id_++, observations[o].type_name, observations[o].pose, stamp_s, 1, 1});
    result[o] = {tracks_.back().id, tracks_.back().pose, true, 1, 1};
  }
  // A track not matched in this frame starts counting its consecutive frames again.
  for (std::size_t t = 0; t < known; ++t)
    if (!track_taken[t]) tracks_[t].frames_seen = 0;
  return result;
}
}  // namespace brick_pose
