// The matcher that scores front-end candidates against truth: what each
// candidate really is, which of them are false complete faces, and the
// tally of recall and errors. Candidates and truth are built by hand.
#include <cmath>

#include <gtest/gtest.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/eval/candidate_matching.h"
#include "brick_pose/eval/rig_truth.h"
#include "brick_pose/eval/score_tally.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace
{
constexpr int kWidth = 60, kHeight = 40;

PinholeCamera smallCamera()
{
  PinholeCamera camera;
  camera.width_px = kWidth;
  camera.height_px = kHeight;
  camera.fx_px = camera.fy_px = 50.0;
  camera.cx_px = 29.5;
  camera.cy_px = 19.5;
  return camera;
}

/// Faces of the hand-made truth, in index order.
enum Face
{
  kWholeTop = 0,   // object 1, type "red", rows 2-9, cols 2-21
  kSide = 1,       // object 1, rows 10-19, cols 2-21
  kHiddenTop = 2,  // object 2, type "red", occluded; rows 2-9, cols 30-49
  kTable = 3,      // everything else
  kUncertain = 4,  // object 3, rows 25-34, cols 30-49
};

void paint(eval::SceneTruth& truth, int face, int row_begin, int row_end, int col_begin, int col_end)
{
  for (int v = row_begin; v < row_end; ++v)
    for (int u = col_begin; u < col_end; ++u) truth.face_index.at<int>(v, u) = face;
}

eval::SceneTruth handMadeTruth()
{
  eval::SceneTruth truth;
  truth.face_index = cv::Mat(kHeight, kWidth, CV_32SC1, cv::Scalar(kTable));
  truth.faces.resize(5);
  truth.faces[kWholeTop].object_id = 1;
  truth.faces[kWholeTop].role = eval::FaceRole::kTop;
  truth.faces[kWholeTop].type = "red";
  truth.faces[kWholeTop].whole_in_view = true;
  truth.faces[kWholeTop].visible_fraction = 1.0;
  truth.faces[kSide].object_id = 1;
  truth.faces[kSide].role = eval::FaceRole::kSide;
  truth.faces[kSide].type = "red";
  truth.faces[kHiddenTop].object_id = 2;
  truth.faces[kHiddenTop].role = eval::FaceRole::kTop;
  truth.faces[kHiddenTop].type = "red";
  truth.faces[kHiddenTop].visible_fraction = 0.7;
  truth.faces[kHiddenTop].not_whole_reason = "occluded";
  truth.faces[kTable].role = eval::FaceRole::kSupport;
  truth.faces[kUncertain].object_id = 3;
  truth.faces[kUncertain].role = eval::FaceRole::kTop;
  truth.faces[kUncertain].whole_uncertain = true;
  truth.faces[kUncertain].visible_fraction = 0.9;
  paint(truth, kWholeTop, 2, 10, 2, 22);
  paint(truth, kSide, 10, 20, 2, 22);
  paint(truth, kHiddenTop, 2, 10, 30, 50);
  paint(truth, kUncertain, 25, 35, 30, 50);
  truth.faces.back().visible_px = 0;
  for (int pixel = 0; pixel < kWidth * kHeight; ++pixel) ++truth.faces[static_cast<std::size_t>(truth.faceAt(pixel))].visible_px;
  return truth;
}

BrickCandidate candidateOver(int row_begin, int row_end, int col_begin, int col_end, bool complete,
                             const std::string& type = "red")
{
  BrickCandidate candidate;
  candidate.type_name = type;
  candidate.complete = complete;
  for (int v = row_begin; v < row_end; ++v)
    for (int u = col_begin; u < col_end; ++u) candidate.pixel_indices.push_back(v * kWidth + u);
  candidate.area_px = static_cast<int>(candidate.pixel_indices.size());
  return candidate;
}

eval::FrameMatch match(const std::vector<BrickCandidate>& candidates)
{
  return eval::matchCandidates(candidates, handMadeTruth(), smallCamera());
}

TEST(CandidateMatching, CompleteWholeTopIsRightAndFound)
{
  const eval::FrameMatch result = match({candidateOver(2, 10, 2, 22, true)});
  ASSERT_EQ(result.candidates.size(), 1u);
  EXPECT_EQ(result.candidates[0].outcome, eval::CandidateOutcome::kWholeTop);
  EXPECT_FALSE(result.candidates[0].false_complete);
  EXPECT_TRUE(result.candidates[0].legacy_true_positive);
  EXPECT_DOUBLE_EQ(result.candidates[0].coverage, 1.0);
  ASSERT_EQ(result.tops.size(), 3u);
  EXPECT_TRUE(result.tops[0].found);
  EXPECT_TRUE(result.tops[0].found_complete);
}

TEST(CandidateMatching, SideFaceMarkedCompleteIsAFalseComplete)
{
  const eval::FrameMatch result = match({candidateOver(10, 20, 2, 22, true)});
  EXPECT_EQ(result.candidates[0].outcome, eval::CandidateOutcome::kSideFace);
  EXPECT_TRUE(result.candidates[0].false_complete);
  EXPECT_FALSE(result.candidates[0].legacy_true_positive);
  EXPECT_FALSE(result.tops[0].found);
}

TEST(CandidateMatching, SideFaceMarkedPartialIsNotAFalseComplete)
{
  const eval::FrameMatch result = match({candidateOver(10, 20, 2, 22, false)});
  EXPECT_EQ(result.candidates[0].outcome, eval::CandidateOutcome::kSideFace);
  EXPECT_FALSE(result.candidates[0].false_complete);
}

TEST(CandidateMatching, HalfOfAWholeTopMarkedCompleteIsAFalseComplete)
{
  const eval::FrameMatch result = match({candidateOver(2, 10, 2, 12, true)});
  EXPECT_EQ(result.candidates[0].outcome, eval::CandidateOutcome::kPartialTop);
  EXPECT_TRUE(result.candidates[0].false_complete);
  EXPECT_NEAR(result.candidates[0].coverage, 0.5, 1e-12);
  // The earlier benchmark counted it (mostly one top face, right type).
  EXPECT_TRUE(result.candidates[0].legacy_true_positive);
  EXPECT_FALSE(result.tops[0].found);
}

TEST(CandidateMatching, StripOfAHiddenTopMarkedCompleteIsAFalseComplete)
{
  const eval::FrameMatch result = match({candidateOver(2, 10, 30, 50, true)});
  EXPECT_EQ(result.candidates[0].outcome, eval::CandidateOutcome::kHiddenTop);
  EXPECT_TRUE(result.candidates[0].false_complete);
}

TEST(CandidateMatching, TableAndMixedCandidatesAreFalseCompletes)
{
  const eval::FrameMatch result = match({candidateOver(30, 40, 0, 20, true),
                                         // top, side and table: no face holds half of it
                                         candidateOver(2, 30, 2, 22, true)});
  EXPECT_EQ(result.candidates[0].outcome, eval::CandidateOutcome::kSupport);
  EXPECT_TRUE(result.candidates[0].false_complete);
  EXPECT_EQ(result.candidates[1].outcome, eval::CandidateOutcome::kMixed);
  EXPECT_LT(result.candidates[1].face_share, 0.5);
  EXPECT_TRUE(result.candidates[1].false_complete);
}

TEST(CandidateMatching, WrongTypeAndDuplicateAreFalseCompletes)
{
  const eval::FrameMatch result = match({candidateOver(2, 10, 2, 22, true, "green"),
                                         candidateOver(2, 10, 2, 22, true), candidateOver(2, 10, 2, 22, true)});
  EXPECT_EQ(result.candidates[0].outcome, eval::CandidateOutcome::kWrongType);
  EXPECT_TRUE(result.candidates[0].false_complete);
  EXPECT_EQ(result.candidates[1].outcome, eval::CandidateOutcome::kWholeTop);
  EXPECT_FALSE(result.candidates[1].false_complete);
  EXPECT_EQ(result.candidates[2].outcome, eval::CandidateOutcome::kDuplicate);
  EXPECT_TRUE(result.candidates[2].false_complete);
}

TEST(CandidateMatching, AWrongTypeNamingTheTrueOneAmongItsPossibleTypesLeavesTheTopsTypeOpenNotFound)
{
  BrickCandidate open_to_red = candidateOver(2, 10, 2, 22, false, "green");
  open_to_red.other_possible_types = {"blue", "red"};
  BrickCandidate open_to_blue = candidateOver(2, 10, 2, 22, false, "green");
  open_to_blue.other_possible_types = {"blue"};
  // Half the top: too little of it, whatever its types.
  BrickCandidate half = candidateOver(2, 10, 2, 12, false, "green");
  half.other_possible_types = {"red"};
  // On the hidden top: no whole top to leave open.
  BrickCandidate hidden = candidateOver(2, 10, 30, 50, false, "green");
  hidden.other_possible_types = {"red"};

  eval::ScoreTally tally;
  const eval::FrameMatch left_open = match({open_to_red, hidden});
  EXPECT_EQ(left_open.candidates[0].outcome, eval::CandidateOutcome::kWrongType);
  EXPECT_TRUE(left_open.candidates[0].type_left_open);
  EXPECT_FALSE(left_open.candidates[1].type_left_open);
  EXPECT_FALSE(left_open.tops[0].found);
  EXPECT_TRUE(left_open.tops[0].found_type_left_open);
  EXPECT_FALSE(left_open.tops[1].found_type_left_open);
  tally.add(left_open, 0.6);
  for (const eval::FrameMatch& other : {match({open_to_blue}), match({half})})
  {
    EXPECT_FALSE(other.candidates[0].type_left_open);
    EXPECT_FALSE(other.tops[0].found_type_left_open);
    tally.add(other, 0.6);
  }
  // Found outright, a top is not counted open too.
  const eval::FrameMatch found = match({open_to_red, candidateOver(2, 10, 2, 22, false)});
  EXPECT_TRUE(found.tops[0].found);
  EXPECT_FALSE(found.tops[0].found_type_left_open);
  tally.add(found, 0.6);
  EXPECT_EQ(tally.whole_tops, 4);
  EXPECT_EQ(tally.whole_tops_found, 1);
  EXPECT_EQ(tally.whole_tops_type_left_open, 1);
  eval::ScoreTally merged;
  merged.merge(tally);
  EXPECT_EQ(merged.whole_tops_type_left_open, 1);
}

TEST(CandidateMatching, TopTheTruthCannotJudgeIsNeitherRightNorFalse)
{
  const eval::FrameMatch result = match({candidateOver(25, 35, 30, 50, true)});
  EXPECT_EQ(result.candidates[0].outcome, eval::CandidateOutcome::kUncertainTop);
  EXPECT_FALSE(result.candidates[0].false_complete);
  eval::ScoreTally tally;
  tally.add(result, 0.6);
  EXPECT_EQ(tally.whole_tops, 1);  // the uncertain top is not in the recall
  EXPECT_EQ(tally.false_complete, 0);
}

TEST(CandidateMatching, TallyCountsRecallPrecisionAndFalseCompletesByKind)
{
  eval::ScoreTally tally;
  // Frame 1: the whole top found, and a side face called complete.
  tally.add(match({candidateOver(2, 10, 2, 22, true), candidateOver(10, 20, 2, 22, true)}), 0.6);
  // Frame 2: nothing found, a hidden strip called complete.
  tally.add(match({candidateOver(2, 10, 30, 50, true)}), 0.6);
  EXPECT_EQ(tally.frames, 2);
  EXPECT_EQ(tally.candidates, 3);
  EXPECT_EQ(tally.complete_candidates, 3);
  EXPECT_EQ(tally.whole_tops, 2);
  EXPECT_EQ(tally.whole_tops_found, 1);
  EXPECT_DOUBLE_EQ(tally.recall(), 0.5);
  EXPECT_EQ(tally.false_complete, 2);
  EXPECT_EQ(tally.false_complete_by_outcome[static_cast<std::size_t>(eval::CandidateOutcome::kSideFace)], 1);
  EXPECT_EQ(tally.false_complete_by_outcome[static_cast<std::size_t>(eval::CandidateOutcome::kHiddenTop)], 1);
  // Legacy recall: tops >= 60% visible (the whole top twice, the hidden one
  // at 0.7 twice, the uncertain one at 0.9 twice); found: the whole top in
  // frame 1, the hidden top in frame 2.
  EXPECT_EQ(tally.legacy_tops, 6);
  EXPECT_EQ(tally.legacy_tops_found, 2);
  EXPECT_EQ(tally.legacy_true_positives, 2);
  EXPECT_NEAR(tally.precision(), 2.0 / 3.0, 1e-12);
  eval::ScoreTally merged;
  merged.merge(tally);
  merged.merge(tally);
  EXPECT_EQ(merged.false_complete, 4);
  EXPECT_DOUBLE_EQ(merged.recall(), 0.5);
}

TEST(CandidateMatching, TruthOfAnotherSizeIsRejected)
{
  eval::SceneTruth truth = handMadeTruth();
  truth.face_index = cv::Mat(10, 10, CV_32SC1, cv::Scalar(-1));
  EXPECT_THROW(eval::matchCandidates({}, truth, smallCamera()), InputError);
  eval::MatchParams params;
  params.min_top_coverage = 0.0;
  EXPECT_THROW(params.validate(), ConfigError);
}

TEST(CandidateMatching, TopFaceErrorsAreZeroForAnExactCandidateAndIgnoreTheHalfTurn)
{
  const PinholeCamera camera = PinholeCamera::d415Color1280x720();
  eval::TopFaceGeometry truth;
  truth.centre_m = Eigen::Vector3d(0.1, -0.05, 1.2);
  truth.normal = Eigen::Vector3d(0.0, -0.6, -0.8);
  truth.long_axis = Eigen::Vector3d(1.0, 0.0, 0.0);
  truth.length_m = 0.6;
  truth.width_m = 0.2;
  const Eigen::Vector3d across = truth.normal.cross(truth.long_axis);
  truth.corners_m = {{truth.centre_m + 0.3 * truth.long_axis + 0.1 * across,
                      truth.centre_m - 0.3 * truth.long_axis + 0.1 * across,
                      truth.centre_m - 0.3 * truth.long_axis - 0.1 * across,
                      truth.centre_m + 0.3 * truth.long_axis - 0.1 * across}};
  BrickCandidate candidate;
  candidate.normal = truth.normal;
  candidate.centroid_m = truth.centre_m;
  candidate.length_m = 0.6;
  candidate.width_m = 0.2;
  // Long edge 0->1 running against the truth's long axis: the same face half a turn round.
  candidate.corners_m = {{truth.corners_m[1], truth.corners_m[0], truth.corners_m[3], truth.corners_m[2]}};
  for (int k = 0; k < 4; ++k) candidate.corners_px[k] = camera.project(candidate.corners_m[k]);
  eval::TopFaceErrors errors = eval::topFaceErrors(candidate, truth, camera);
  EXPECT_NEAR(errors.rotation_deg, 0.0, 1e-6);
  EXPECT_NEAR(errors.centre_mm, 0.0, 1e-9);
  EXPECT_NEAR(errors.corner_error_px, 0.0, 1e-9);
  // Centre 3 mm off, width 2 mm short.
  candidate.centroid_m += Eigen::Vector3d(0.003, 0.0, 0.0);
  candidate.width_m = 0.198;
  errors = eval::topFaceErrors(candidate, truth, camera);
  EXPECT_NEAR(errors.centre_mm, 3.0, 1e-9);
  EXPECT_NEAR(errors.width_error_mm, 2.0, 1e-9);
}

TEST(RigTruth, SingleBrickHasAWholeTopFacingUpAndSideFaces)
{
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  sim::SceneParams params;
  params.types = {"red"};
  params.min_distance_m = params.max_distance_m = 1.0;
  const sim::Scene scene = sim::SceneGenerator(catalogue, params).generate(3);
  const sim::SyntheticFrame frame =
      sim::SyntheticRig(PinholeCamera::d415Color1280x720(), sim::SensorModel()).render(scene, 3);
  const Eigen::Vector3d up = scene.world_T_camera.linear().transpose() * Eigen::Vector3d::UnitZ();
  const eval::SceneTruth truth = eval::rigSceneTruth(frame, up);
  ASSERT_EQ(truth.faces.size(), 7u);  // six faces and the ground
  EXPECT_EQ(truth.faces[0].role, eval::FaceRole::kTop);
  EXPECT_TRUE(truth.faces[0].whole_in_view) << truth.faces[0].not_whole_reason;
  EXPECT_EQ(truth.faces[0].type, "red");
  EXPECT_GT(truth.faces[0].visible_px, 0);
  EXPECT_EQ(truth.faces[1].role, eval::FaceRole::kBottom);
  for (std::size_t f = 2; f < 6; ++f) EXPECT_EQ(truth.faces[f].role, eval::FaceRole::kSide) << f;
  EXPECT_EQ(truth.faces[6].role, eval::FaceRole::kSupport);
  // A side face called complete is a false complete here too.
  BrickCandidate side;
  side.type_name = "red";
  side.complete = true;
  for (int pixel = 0; pixel < static_cast<int>(truth.face_index.total()); ++pixel)
    if (truth.faceAt(pixel) >= 2 && truth.faceAt(pixel) < 6) side.pixel_indices.push_back(pixel);
  ASSERT_FALSE(side.pixel_indices.empty());
  const eval::FrameMatch result = eval::matchCandidates({side}, truth, frame.camera);
  EXPECT_NE(result.candidates[0].outcome, eval::CandidateOutcome::kWholeTop);
  EXPECT_TRUE(result.candidates[0].false_complete);
}
}  // namespace
}  // namespace brick_pose
