#include "brick_pose/pose/brick_pose_estimator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unordered_set>

#include "brick_pose/catalogue/resting.h"
#include "brick_pose/common/elapsed.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/correction/measured_face.h"
#include "brick_pose/registration/brick_symmetry.h"
#include "brick_pose/registration/model_cloud.h"

namespace brick_pose
{
namespace
{
/// Below this, too little of the face is seen to fix its pose.
constexpr double kMinOverlap = 0.25;

/// Area of the face the segment covers: its points projected into the plane
/// and counted on a 1 cm grid. Independent of how the segment was sampled.
double visibleFaceArea(const pcl::PointCloud<pcl::PointXYZ>& points, const Eigen::Vector3d& normal)
{
  constexpr double kCell_m = 0.01;
  const Eigen::Vector3d u = normal.unitOrthogonal();
  const Eigen::Vector3d v = normal.cross(u);
  std::unordered_set<std::uint64_t> cells;
  for (const pcl::PointXYZ& point : points)
  {
    const Eigen::Vector3d p(point.x, point.y, point.z);
    if (!p.allFinite()) continue;
    const auto i = static_cast<std::int64_t>(std::floor(p.dot(u) / kCell_m));
    const auto j = static_cast<std::int64_t>(std::floor(p.dot(v) / kCell_m));
    cells.insert((static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint64_t>(j & 0xffffffff));
  }
  return static_cast<double>(cells.size()) * kCell_m * kCell_m;
}

MeasuredFace measuredFaceOf(const BrickCandidate& candidate)
{
  MeasuredFace face;
  face.t1_m = candidate.t1_m;
  face.t2_m = candidate.t2_m;
  face.centroid_m = candidate.plane.centroid_m;
  face.normal = candidate.normal;
  return face;
}
}  // namespace

void BrickPoseEstimatorParams::validate() const
{
  super4pcs.validate();
  if (!(model_spacing_m > 0.0)) throw ConfigError("parameter 'model_spacing_m' must be > 0");
  if (!(correction_good_enough_ratio > 0.0 && correction_good_enough_ratio <= 1.0))
    throw ConfigError("parameter 'correction_good_enough_ratio' must be in (0, 1], got " +
                      std::to_string(correction_good_enough_ratio));
  if (!(partial_face_max_time_s > 0.0))
    throw ConfigError("parameter 'partial_face_max_time_s' must be > 0, got " + std::to_string(partial_face_max_time_s));
  icp.validate();
}

BrickPoseEstimator::BrickPoseEstimator(const BrickCatalogue& catalogue, const BrickPoseEstimatorParams& params)
  : catalogue_(catalogue), params_(params)
{
  params_.validate();
  if (catalogue_.empty()) throw ConfigError("brick pose estimator: the catalogue is empty");
  registration::ModelCloudParams options;
  options.spacing_m = params_.model_spacing_m;
  for (const BrickType& type : catalogue_.types())
    for (const Resting resting : {Resting::kUpright, Resting::kOnSide, Resting::kOnEnd})
    {
      if (resting != Resting::kUpright && !mayRestOtherwise(type)) continue;
      const BrickType as_top = restingAs(type, resting);
      models_[as_top.name] = {as_top, registration::buildBrickModelCloud(as_top, options)};
    }
}

const BrickPoseEstimator::Model& BrickPoseEstimator::modelOf(const BrickCandidate& candidate) const
{
  const auto model = models_.find(candidate.type_name);
  if (model == models_.end()) throw InputError("candidate of unknown brick type '" + candidate.type_name + "'");
  return model->second;
}

BrickRegistration BrickPoseEstimator::registerCandidate(const BrickCandidate& candidate) const
{
  const auto start = std::chrono::steady_clock::now();
  const Model& model = modelOf(candidate);
  if (!candidate.points || candidate.points->size() < 4)
    throw InputError("candidate '" + candidate.type_name + "' has fewer than 4 points");
  registration::PointSet target = registration::fromPcl(*candidate.points);
  // The model carries normals and the segment does not: register points only.
  registration::PointSet source;
  source.points = model.points.points;
  // The LCP of the whole-face model can reach only the fraction of the face
  // that is visible: an occluded brick needs a lower overlap, or Super4PCS
  // rejects its (correct) pose as too poor a match.
  registration::Super4PCSParams params = params_.super4pcs;
  const BrickType& type = model.type;
  const double visible_fraction =
      visibleFaceArea(*candidate.points, candidate.normal) / (type.length_m * type.width_m);
  params.overlap = std::clamp(visible_fraction, kMinOverlap, params_.super4pcs.overlap);
  // The correction takes tilt, yaw and position from the measured face and
  // needs the registration only to within the face's symmetry, so Super4PCS's
  // ICP polish (most of its time) would be thrown away.
  if (params_.refinement == RefinementMethod::kCorrection)
  {
    params.refine_iterations = 0;
    params.fine_refine_iterations = 0;
    params.good_enough_ratio = std::min(params.good_enough_ratio, params_.correction_good_enough_ratio);
  }
  if (!candidate.complete) params.max_time_s = std::min(params.max_time_s, params_.partial_face_max_time_s);
  BrickRegistration registration;
  registration.result = registration::Super4PCS(params).align(source, target);
  registration.elapsed_ms = millisecondsSince(start);
  if (!registration.result.success)
    throw InputError("Super4PCS found no pose for '" + candidate.type_name + "': " + registration.result.reason);
  // A face seen from one side: z toward the camera, then a fixed x sign.
  registration.pose =
      registration::canonicalisePose(registration.result.source_to_target, registration::ModelSymmetry::kRectangle);
  return registration;
}

BrickPoseEstimate BrickPoseEstimator::refine(const BrickCandidate& candidate, const BrickRegistration& registration) const
{
  const BrickType& type = modelOf(candidate).type;
  BrickPoseEstimate estimate;
  estimate.type_name = type.name;
  estimate.catalogue_type = type.catalogueName();
  estimate.resting = type.resting;
  estimate.dimensions_m = type.dimensions_m();
  estimate.registration = registration;
  estimate.refinement = params_.refinement;
  const auto start = std::chrono::steady_clock::now();
  switch (params_.refinement)
  {
    case RefinementMethod::kCorrection:
      estimate.correction = correctPose(registration.pose, type, measuredFaceOf(candidate), params_.correction);
      estimate.pose = estimate.correction.corrected_pose;
      break;
    case RefinementMethod::kIcp:
      estimate.icp = refinePoseWithIcp(registration.pose, type, *candidate.points, params_.icp);
      estimate.pose = estimate.icp.refined_pose;
      break;
    case RefinementMethod::kNone:
    default:
      estimate.pose = registration.pose;
      break;
  }
  estimate.refinement_ms = millisecondsSince(start);
  estimate.pose = registration::canonicalisePose(estimate.pose, registration::ModelSymmetry::kRectangle);
  return estimate;
}

BrickPoseEstimate BrickPoseEstimator::estimate(const BrickCandidate& candidate) const
{
  return refine(candidate, registerCandidate(candidate));
}
}  // namespace brick_pose
