#pragma once
// Stages 4 and 5 for one brick candidate: Super4PCS registration of the
// artificial model (the top face, origin at its centre) onto the segment,
// then refinement of that pose by the constant-time correction (default), by
// ICP (the paper's baseline) or not at all.

#include <map>
#include <string>

#include <Eigen/Geometry>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/correction/icp_refinement.h"
#include "brick_pose/correction/pose_correction.h"
#include "brick_pose/correction/refinement_method.h"
#include "brick_pose/registration/point_set.h"
#include "brick_pose/registration/registration_result.h"
#include "brick_pose/registration/super4pcs.h"
#include "brick_pose/roi/brick_candidate.h"

namespace brick_pose
{
struct BrickPoseEstimatorParams
{
  registration::Super4PCSParams super4pcs;
  /// Grid step of the artificial model cloud of each brick type.
  double model_spacing_m = 0.01;
  /// Super4PCS's good_enough_ratio when the correction follows. The
  /// correction takes tilt, yaw and position from the measured face, so the
  /// registration only has to put the model on the face (any yaw will do);
  /// waiting for the LCP of a near-perfect 4-point pose mostly spends the
  /// time budget. 0.75 of the visible fraction still rejects a model lying
  /// across a long face.
  double correction_good_enough_ratio = 0.75;
  /// Super4PCS time budget (s) for a face the front end measured as partial
  /// (cut by an occluder or the image border). Its LCP cannot be judged
  /// against a well-known overlap, so the search tends to run to the end of
  /// its budget; and the service never picks such a face, whose pose only
  /// serves the pickable test. The best pose found by then is kept.
  double partial_face_max_time_s = 0.03;
  RefinementMethod refinement = kDefaultRefinementMethod;
  PoseCorrectionParams correction;
  IcpParams icp;

  /// Throws ConfigError naming the first unusable field.
  void validate() const;
};

/// Super4PCS's view of one candidate.
struct BrickRegistration
{
  registration::RegistrationResult result;
  /// Canonical T_cam_brick (z toward the camera, deterministic x sign).
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  double elapsed_ms = 0.0;
};

/// The final pose of one candidate and how it was obtained.
struct BrickPoseEstimate
{
  /// The candidate's type: a catalogue type, or one resting on a side or
  /// an end as restingAs() names it ("box_small lying on a side").
  std::string type_name;
  /// The catalogue type it is, and how it rests: the pose and the
  /// dimensions are those of the face up (length, width, depth below).
  std::string catalogue_type;
  Resting resting = Resting::kUpright;
  Eigen::Vector3d dimensions_m = Eigen::Vector3d::Zero();
  BrickRegistration registration;
  RefinementMethod refinement = RefinementMethod::kNone;
  /// Canonical final T_cam_brick.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  /// Set when refinement == kCorrection.
  PoseCorrection correction;
  /// Set when refinement == kIcp.
  IcpRefinement icp;
  double refinement_ms = 0.0;
};

class BrickPoseEstimator
{
public:
  /// Builds the model cloud of every catalogue type once, and of each plain
  /// box type resting on a side and on an end. Throws ConfigError.
  BrickPoseEstimator(const BrickCatalogue& catalogue, const BrickPoseEstimatorParams& params);

  /// Stage 4. Throws InputError when the candidate cannot be registered
  /// (unknown type, too few points) and when Super4PCS finds no pose.
  BrickRegistration registerCandidate(const BrickCandidate& candidate) const;

  /// Stage 5 from a registration. Throws InputError when the correction
  /// rejects the input as degenerate.
  BrickPoseEstimate refine(const BrickCandidate& candidate, const BrickRegistration& registration) const;

  /// Both stages.
  BrickPoseEstimate estimate(const BrickCandidate& candidate) const;

  const BrickPoseEstimatorParams& params() const { return params_; }
  const BrickCatalogue& catalogue() const { return catalogue_; }

private:
  /// A type a candidate may name, with its model cloud.
  struct Model
  {
    BrickType type;
    registration::PointSet points;
  };

  /// The model of the type a candidate names (a catalogue type or one
  /// resting otherwise). Throws InputError for an unknown one.
  const Model& modelOf(const BrickCandidate& candidate) const;

  BrickCatalogue catalogue_;
  BrickPoseEstimatorParams params_;
  std::map<std::string, Model> models_;  ///< by type name
};
}  // namespace brick_pose
