#pragma once
// Matches the front end's candidates of one frame against its SceneTruth and
// says what each candidate really is: a whole top face, a side face, a strip
// of a hidden top, half of a top, the table ... A candidate the front end
// marks complete that is anything but a whole top face of its type is a
// **false complete face**: the confident wrong answer a picker would act on.
//
// A candidate's face is the truth face that holds most of its depth pixels
// (at least min_face_share of them); the candidate "covers" that face by
// the share of the face's pixels it holds.

#include <array>
#include <string>
#include <vector>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/eval/scene_truth.h"
#include "brick_pose/roi/brick_candidate.h"

namespace brick_pose
{
namespace eval
{
enum class CandidateOutcome
{
  kWholeTop,      ///< A whole-in-view top face, covered, of the candidate's type, first on it.
  kPartialTop,    ///< On a whole top but covering too little of it ("half mask").
  kHiddenTop,     ///< On a top that is not whole in view (occluded or cut by the border).
  kSideFace,      ///< A side face of a cuboid.
  kOtherFace,     ///< Another face of an object (bottom, tilted, unclassified).
  kSupport,       ///< The table or the ground.
  kMixed,         ///< No single face holds min_face_share of its pixels.
  kWrongType,     ///< On a top face of another catalogue type.
  kDuplicate,     ///< A later candidate on a whole top already matched.
  kUncertainTop,  ///< On a top whose truth cannot say whether it is whole: not scored.
};
constexpr int kCandidateOutcomeCount = 10;

const char* toString(CandidateOutcome outcome);

struct MatchParams
{
  double min_face_share = 0.5;
  /// A whole top counts as found by a candidate holding at least this share
  /// of its visible pixels (the candidate's pixels are depth pixels only,
  /// and the edges of a real face are often without depth).
  double min_top_coverage = 0.7;
  /// The earlier benchmark's recall set: tops at least this visible.
  double legacy_min_visible_fraction = 0.6;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// Errors of a candidate's top-face measurement against the truth geometry.
struct TopFaceErrors
{
  /// Angle of the rotation between the candidate's face frame (long axis,
  /// normal) and the truth's, modulo the face's half-turn symmetry.
  double rotation_deg = 0.0;
  double normal_deg = 0.0;
  double centre_mm = 0.0;           ///< Candidate centroid_m to the truth centre.
  double length_error_mm = 0.0;     ///< |measured - true|
  double width_error_mm = 0.0;
  /// Mean image distance of the quad corners to the projected true corners,
  /// best cyclic correspondence.
  double corner_error_px = 0.0;
};

struct CandidateMatch
{
  CandidateOutcome outcome = CandidateOutcome::kMixed;
  int face = -1;             ///< Dominant truth face, -1 when none.
  double face_share = 0.0;   ///< Of the candidate's pixels on that face.
  double coverage = 0.0;     ///< Of that face's pixels held by the candidate.
  bool complete = false;     ///< The candidate's claim.
  /// complete, and anything but a whole top (kUncertainTop excepted: the
  /// truth cannot judge it).
  bool false_complete = false;
  /// The earlier benchmark's rule: mostly one top face (any visibility), of
  /// the candidate's type, the first candidate on it.
  bool legacy_true_positive = false;
  /// kWrongType on a whole top, covered, whose type the candidate names
  /// among its other_possible_types: the face found, its type left open
  /// where only a side would tell.
  bool type_left_open = false;
  bool has_errors = false;   ///< Errors are measured on kWholeTop matches with geometry.
  TopFaceErrors errors;
};

/// One truth top face and whether it was found.
struct TopMatch
{
  int face = -1;
  bool whole_in_view = false;
  bool whole_uncertain = false;
  double visible_fraction = 0.0;
  bool found = false;           ///< A kWholeTop candidate on it.
  bool found_complete = false;  ///< ... marked complete.
  bool legacy_found = false;    ///< A legacy true positive on it.
  /// Not found, but a candidate on it leaves its type open (type_left_open).
  bool found_type_left_open = false;
};

struct FrameMatch
{
  std::vector<CandidateMatch> candidates;  ///< In candidate order.
  std::vector<TopMatch> tops;              ///< Every top face of the truth.
};

/// Matches `candidates` (the front end's, in its order) against `truth`.
/// `camera` projects the truth corners for the corner error.
FrameMatch matchCandidates(const std::vector<BrickCandidate>& candidates, const SceneTruth& truth,
                           const PinholeCamera& camera, const MatchParams& params = MatchParams());

/// Image distance of each measured corner to its truth corner, for the
/// cyclic correspondence (either direction) of least total distance.
std::array<double, 4> cornerErrorsPx(const QuadCorners& measured, const std::array<Eigen::Vector2d, 4>& truth);

/// Errors of `candidate` against `geometry` (exposed for tests).
TopFaceErrors topFaceErrors(const BrickCandidate& candidate, const TopFaceGeometry& geometry,
                            const PinholeCamera& camera);
}  // namespace eval
}  // namespace brick_pose
