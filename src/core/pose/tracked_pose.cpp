#include "brick_pose/pose/tracked_pose.h"

#include <algorithm>
#include <cmath>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/registration/brick_symmetry.h"

namespace brick_pose
{
namespace
{
}  // namespace

void TrackedPoseParams::validate() const
{
  if (!(match_margin_m >= 0.0)) throw ConfigError("tracked pose: match_margin_m must be >= 0");
  if (!(match_angle_deg > 0.0 && match_angle_deg <= 90.0))
    throw ConfigError("tracked pose: match_angle_deg must be in (0, 90]");
  if (!(moved_translation_m > 0.0)) throw ConfigError("tracked pose: moved_translation_m must be > 0");
  if (!(moved_rotation_deg > 0.0)) throw ConfigError("tracked pose: moved_rotation_deg must be > 0");
}

PreviousPoses::PreviousPoses(const TrackedPoseParams& params) : params_(params) { params_.validate(); }

std::optional<PreviousPose> PreviousPoses::match(const BrickCandidate& candidate) const
{
  if (!params_.enabled) return std::nullopt;
  const double min_cos = std::cos(params_.match_angle_deg * kDegToRad);
  const PreviousPose* best = nullptr;
  double best_distance_m = 0.0;
  for (const PreviousPose& previous : poses_)
  {
    if (previous.type_name != candidate.type_name) continue;
    // Both normals point toward the camera (canonical poses and the front end's plane).
    if (std::abs(previous.pose.linear().col(2).dot(candidate.normal)) < min_cos) continue;
    const Eigen::Vector3d in_brick = previous.pose.inverse() * candidate.centroid_m;
    const bool on_face = std::abs(in_brick.z()) <= params_.match_margin_m &&
                         std::abs(in_brick.x()) <= 0.5 * previous.dimensions_m.x() + params_.match_margin_m &&
                         std::abs(in_brick.y()) <= 0.5 * previous.dimensions_m.y() + params_.match_margin_m;
    const double distance_m = in_brick.norm();
    if (on_face && (!best || distance_m < best_distance_m))
    {
      best = &previous;
      best_distance_m = distance_m;
    }
  }
  if (!best) return std::nullopt;
  return *best;
}

BrickRegistration registrationFromPrevious(const PreviousPose& previous)
{
  BrickRegistration registration;
  registration.pose = registration::canonicalisePose(previous.pose, registration::ModelSymmetry::kRectangle);
  registration.result.source_to_target = registration.pose;
  registration.result.success = true;
  registration.result.lcp_score = previous.fitness;
  registration.result.reason = "tracked from the previous pose";
  registration.elapsed_ms = 0.0;
  return registration;
}

bool correctionSaysMoved(const PoseCorrection& correction, const TrackedPoseParams& params)
{
  const double rotation_deg = Eigen::AngleAxisd(correction.delta_in_brick.linear()).angle() * kRadToDeg;
  return correction.offset_m.norm() > params.moved_translation_m || rotation_deg > params.moved_rotation_deg;
}
}  // namespace brick_pose
