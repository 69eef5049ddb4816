#include "brick_pose/eval/candidate_matching.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <Eigen/Geometry>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace eval
{
namespace
{
constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return std::atan2(a.cross(b).norm(), a.dot(b)) * kDegPerRad;
}

/// Right-handed frame with z = normal and x = the long axis made orthogonal to it.
Eigen::Matrix3d faceFrame(const Eigen::Vector3d& long_axis, const Eigen::Vector3d& normal)
{
  const Eigen::Vector3d z = normal.normalized();
  const Eigen::Vector3d x = (long_axis - z * z.dot(long_axis)).normalized();
  Eigen::Matrix3d frame;
  frame.col(0) = x;
  frame.col(1) = z.cross(x);
  frame.col(2) = z;
  return frame;
}

double rotationAngleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b)
{
  return Eigen::AngleAxisd(a.transpose() * b).angle() * kDegPerRad;
}

/// Dominant face of the candidate and its pixel count there.
std::pair<int, int> dominantFace(const BrickCandidate& candidate, const SceneTruth& truth)
{
  std::map<int, int> votes;
  const int pixel_count = static_cast<int>(truth.face_index.total());
  for (const int pixel : candidate.pixel_indices)
    if (pixel >= 0 && pixel < pixel_count) ++votes[truth.faceAt(pixel)];
  std::pair<int, int> best{-1, 0};
  for (const auto& [face, count] : votes)
    if (face >= 0 && count > best.second) best = {face, count};
  return best;
}

bool typeMatches(const BrickCandidate& candidate, const FaceTruth& face)
{
  return face.type.empty() || face.type == candidate.type_name;
}
}  // namespace

const char* toString(CandidateOutcome outcome)
{
  switch (outcome)
  {
    case CandidateOutcome::kWholeTop: return "whole top face";
    case CandidateOutcome::kPartialTop: return "part of a whole top (half mask)";
    case CandidateOutcome::kHiddenTop: return "top not whole in view (hidden strip / cut)";
    case CandidateOutcome::kSideFace: return "side face";
    case CandidateOutcome::kOtherFace: return "other face of an object";
    case CandidateOutcome::kSupport: return "table / ground";
    case CandidateOutcome::kMixed: return "no dominant face";
    case CandidateOutcome::kWrongType: return "top of another type";
    case CandidateOutcome::kDuplicate: return "second candidate on a top";
    case CandidateOutcome::kUncertainTop: return "top whose wholeness the truth cannot tell";
  }
  return "?";
}

void MatchParams::validate() const
{
  if (!(min_face_share > 0.0 && min_face_share <= 1.0)) throw ConfigError("min_face_share must be in (0, 1]");
  if (!(min_top_coverage > 0.0 && min_top_coverage <= 1.0)) throw ConfigError("min_top_coverage must be in (0, 1]");
  if (!(legacy_min_visible_fraction >= 0.0 && legacy_min_visible_fraction <= 1.0))
    throw ConfigError("legacy_min_visible_fraction must be in [0, 1]");
}

std::array<double, 4> cornerErrorsPx(const QuadCorners& measured, const std::array<Eigen::Vector2d, 4>& truth)
{
  std::array<double, 4> best{};
  double best_sum = std::numeric_limits<double>::max();
  for (const int direction : {1, -1})
    for (int shift = 0; shift < 4; ++shift)
    {
      std::array<double, 4> errors{};
      double sum = 0.0;
      for (int k = 0; k < 4; ++k)
      {
        errors[k] = (measured[k] - truth[((shift + direction * k) % 4 + 4) % 4]).norm();
        sum += errors[k];
      }
      if (sum < best_sum)
      {
        best_sum = sum;
        best = errors;
      }
    }
  return best;
}

TopFaceErrors topFaceErrors(const BrickCandidate& candidate, const TopFaceGeometry& geometry,
                            const PinholeCamera& camera)
{
  TopFaceErrors errors;
  const Eigen::Vector3d measured_long = candidate.corners_m[1] - candidate.corners_m[0];
  const Eigen::Matrix3d truth_frame = faceFrame(geometry.long_axis, geometry.normal);
  const Eigen::Matrix3d measured_frame = faceFrame(measured_long, candidate.normal);
  // The face looks the same turned half a turn about its normal.
  Eigen::Matrix3d flipped = measured_frame;
  flipped.col(0) = -flipped.col(0);
  flipped.col(1) = -flipped.col(1);
  errors.rotation_deg = std::min(rotationAngleDeg(measured_frame, truth_frame), rotationAngleDeg(flipped, truth_frame));
  errors.normal_deg = angleDeg(candidate.normal, geometry.normal);
  errors.centre_mm = 1000.0 * (candidate.centroid_m - geometry.centre_m).norm();
  errors.length_error_mm = 1000.0 * std::abs(candidate.length_m - geometry.length_m);
  errors.width_error_mm = 1000.0 * std::abs(candidate.width_m - geometry.width_m);
  std::array<Eigen::Vector2d, 4> truth_corners_px;
  for (int k = 0; k < 4; ++k) truth_corners_px[k] = camera.project(geometry.corners_m[k]);
  const std::array<double, 4> corner_errors = cornerErrorsPx(candidate.corners_px, truth_corners_px);
  errors.corner_error_px = 0.25 * (corner_errors[0] + corner_errors[1] + corner_errors[2] + corner_errors[3]);
  return errors;
}

FrameMatch matchCandidates(const std::vector<BrickCandidate>& candidates, const SceneTruth& truth,
                           const PinholeCamera& camera, const MatchParams& params)
{
  params.validate();
  if (truth.face_index.type() != CV_32SC1 || truth.face_index.cols != camera.width_px ||
      truth.face_index.rows != camera.height_px)
    throw InputError("matchCandidates: the truth's face index image does not match the camera");

  FrameMatch match;
  std::vector<bool> whole_taken(truth.faces.size(), false), legacy_taken(truth.faces.size(), false);
  for (const BrickCandidate& candidate : candidates)
  {
    CandidateMatch result;
    result.complete = candidate.complete;
    const auto [face_index, votes] = dominantFace(candidate, truth);
    if (!candidate.pixel_indices.empty())
      result.face_share = static_cast<double>(votes) / static_cast<double>(candidate.pixel_indices.size());
    if (face_index >= 0 && result.face_share >= params.min_face_share)
    {
      result.face = face_index;
      const FaceTruth& face = truth.faces[static_cast<std::size_t>(face_index)];
      result.coverage = face.visible_px > 0 ? static_cast<double>(votes) / face.visible_px : 0.0;
      switch (face.role)
      {
        case FaceRole::kSupport: result.outcome = CandidateOutcome::kSupport; break;
        case FaceRole::kSide: result.outcome = CandidateOutcome::kSideFace; break;
        case FaceRole::kBottom:
        case FaceRole::kOther: result.outcome = CandidateOutcome::kOtherFace; break;
        case FaceRole::kTop:
          if (!typeMatches(candidate, face)) result.outcome = CandidateOutcome::kWrongType;
          else if (face.whole_uncertain) result.outcome = CandidateOutcome::kUncertainTop;
          else if (!face.whole_in_view) result.outcome = CandidateOutcome::kHiddenTop;
          else if (result.coverage < params.min_top_coverage) result.outcome = CandidateOutcome::kPartialTop;
          else if (whole_taken[static_cast<std::size_t>(face_index)]) result.outcome = CandidateOutcome::kDuplicate;
          else
          {
            result.outcome = CandidateOutcome::kWholeTop;
            whole_taken[static_cast<std::size_t>(face_index)] = true;
          }
          result.type_left_open = result.outcome == CandidateOutcome::kWrongType && face.whole_in_view &&
                                  !face.whole_uncertain && result.coverage >= params.min_top_coverage &&
                                  std::find(candidate.other_possible_types.begin(),
                                            candidate.other_possible_types.end(),
                                            face.type) != candidate.other_possible_types.end();
          if (typeMatches(candidate, face) && !legacy_taken[static_cast<std::size_t>(face_index)])
          {
            result.legacy_true_positive = true;
            legacy_taken[static_cast<std::size_t>(face_index)] = true;
          }
          break;
      }
      if (result.outcome == CandidateOutcome::kWholeTop && face.has_geometry)
      {
        result.has_errors = true;
        result.errors = topFaceErrors(candidate, face.geometry, camera);
      }
    }
    result.false_complete = result.complete && result.outcome != CandidateOutcome::kWholeTop &&
                            result.outcome != CandidateOutcome::kUncertainTop;
    match.candidates.push_back(result);
  }

  for (std::size_t f = 0; f < truth.faces.size(); ++f)
  {
    const FaceTruth& face = truth.faces[f];
    if (face.role != FaceRole::kTop) continue;
    TopMatch top;
    top.face = static_cast<int>(f);
    top.whole_in_view = face.whole_in_view;
    top.whole_uncertain = face.whole_uncertain;
    top.visible_fraction = face.visible_fraction;
    top.legacy_found = legacy_taken[f];
    for (const CandidateMatch& candidate : match.candidates)
    {
      if (candidate.face != top.face) continue;
      if (candidate.outcome == CandidateOutcome::kWholeTop)
      {
        top.found = true;
        top.found_complete = candidate.complete;
      }
      top.found_type_left_open = top.found_type_left_open || candidate.type_left_open;
    }
    top.found_type_left_open = top.found_type_left_open && !top.found;
    match.tops.push_back(top);
  }
  return match;
}
}  // namespace eval
}  // namespace brick_pose
