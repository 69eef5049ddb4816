#pragma once
// The tracked path (issue 14): a brick already measured in recent frames
// starts from its last final pose instead of from Super4PCS. The
// constant-time correction then refines that pose from the new frame's face,
// as it refines a Super4PCS pose; and when the correction's own size says
// the brick moved or its pose jumped, the brick is registered afresh. A
// static pile then costs about a front end per frame.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/correction/pose_correction.h"
#include "brick_pose/pose/brick_pose_estimator.h"
#include "brick_pose/roi/brick_candidate.h"

namespace brick_pose
{
struct TrackedPoseParams
{
  /// Off: Super4PCS for every candidate of every frame.
  bool enabled = true;
  /// A candidate is the brick of a previous pose when its face centre lies
  /// on that brick's top face (within this of its plane, and inside the face
  /// grown by this) ...
  double match_margin_m = 0.03;
  /// ... and its normal is within this of the brick's z axis.
  double match_angle_deg = 15.0;
  /// A correction larger than these says the brick moved or the pose jumped:
  /// register it again. The correction of a static brick is sensor noise,
  /// well below a millimetre and a tenth of a degree.
  double moved_translation_m = 0.005;
  double moved_rotation_deg = 2.0;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// A brick's final pose from an earlier frame.
struct PreviousPose
{
  std::string type_name;
  std::uint32_t id = 0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< T_cam_brick
  Eigen::Vector3d dimensions_m = Eigen::Vector3d::Zero();
  double fitness = 0.0;
};

/// The latest final poses, and which of them a new candidate continues.
class PreviousPoses
{
public:
  explicit PreviousPoses(const TrackedPoseParams& params = TrackedPoseParams());

  /// Replaces the remembered poses with the latest detections'.
  void update(std::vector<PreviousPose> poses) { poses_ = std::move(poses); }

  /// The previous pose `candidate` continues (closest face centre first),
  /// or nothing: a new brick, or tracking disabled.
  std::optional<PreviousPose> match(const BrickCandidate& candidate) const;

  std::size_t size() const { return poses_.size(); }

private:
  TrackedPoseParams params_;
  std::vector<PreviousPose> poses_;
};

/// A registration that starts from `previous` instead of from Super4PCS:
/// its pose, its fitness carried over, success, no search time.
BrickRegistration registrationFromPrevious(const PreviousPose& previous);

/// True when `correction` of a tracked pose is larger than a static brick's
/// noise (see TrackedPoseParams).
bool correctionSaysMoved(const PoseCorrection& correction, const TrackedPoseParams& params);
}  // namespace brick_pose
