// Unit tests of the constant-time pose correction (paper and full modes).

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/correction/correction_mode.h"
#include "brick_pose/correction/pose_correction.h"

namespace brick_pose
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kRadPerDeg = kPi / 180.0;
// T1 and T2 sit this far either side of the face centre along its long axis.
constexpr double kHalfSeparationM = 0.10;

Eigen::Matrix3d rotX(double deg) { return Eigen::AngleAxisd(deg * kRadPerDeg, Eigen::Vector3d::UnitX()).toRotationMatrix(); }
Eigen::Matrix3d rotY(double deg) { return Eigen::AngleAxisd(deg * kRadPerDeg, Eigen::Vector3d::UnitY()).toRotationMatrix(); }
Eigen::Matrix3d rotZ(double deg) { return Eigen::AngleAxisd(deg * kRadPerDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix(); }

Eigen::Isometry3d makePose(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& translation_m)
{
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = rotation;
  pose.translation() = translation_m;
  return pose;
}

/// A brick about 0.9 m in front of the camera, top face turned toward it
/// (brick z roughly along -z of the optical frame) and somewhat tilted.
Eigen::Isometry3d truePose()
{
  return makePose(rotX(180.0) * rotY(12.0) * rotX(-7.0) * rotZ(34.0), Eigen::Vector3d(0.05, -0.03, 0.90));
}

BrickType redBrick()
{
  return BrickCatalogue::mbzirc2020().at("red");
}

/// What a perfect front end would measure on the face of a brick at `pose`.
MeasuredFace exactFace(const Eigen::Isometry3d& pose)
{
  MeasuredFace face;
  face.t1_m = pose * Eigen::Vector3d(-kHalfSeparationM, 0.0, 0.0);
  face.t2_m = pose * Eigen::Vector3d(kHalfSeparationM, 0.0, 0.0);
  face.centroid_m = pose.translation();
  face.normal = pose.linear().col(2);
  return face;
}

PoseCorrectionParams withMode(CorrectionMode mode)
{
  PoseCorrectionParams parameters;
  parameters.mode = mode;
  return parameters;
}

/// Largest absolute entry of the difference of two poses' matrices.
double maxDifference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b)
{
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

/// Rotation angle (rad) taking `a`'s orientation to `b`'s.
double rotationAngleBetween(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b)
{
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle();
}

// The paper's example: 3.26 deg of yaw and (0.8, 3.1, -0.2) mm of offset.
const double kYawErrorDeg = 3.26;
const Eigen::Vector3d kOffsetErrorM(0.8e-3, 3.1e-3, -0.2e-3);

/// The true pose with the paper's yaw error (about the brick's z) and
/// camera-frame offset error applied.
Eigen::Isometry3d poseWithYawAndOffsetError(const Eigen::Isometry3d& truth)
{
  return makePose(truth.linear() * rotZ(-kYawErrorDeg), truth.translation() - kOffsetErrorM);
}
}  // namespace

TEST(PoseCorrection, FullIsTheDefaultMode)
{
  EXPECT_EQ(PoseCorrectionParams().mode, CorrectionMode::kFull);
  const Eigen::Isometry3d truth = truePose();
  const PoseCorrection result = correctPose(poseWithYawAndOffsetError(truth), redBrick(), exactFace(truth));
  EXPECT_EQ(result.mode, CorrectionMode::kFull);
}

TEST(PoseCorrection, PaperModeRemovesKnownYawAndOffsetExactly)
{
  const Eigen::Isometry3d truth = truePose();
  const PoseCorrection result = correctPose(poseWithYawAndOffsetError(truth), redBrick(), exactFace(truth),
                                            withMode(CorrectionMode::kPaper));
  EXPECT_EQ(result.mode, CorrectionMode::kPaper);
  EXPECT_LT(maxDifference(result.corrected_pose, truth), 1e-9);
  EXPECT_NEAR(result.yawDeg(), kYawErrorDeg, 1e-9);
  EXPECT_NEAR(result.yaw_rad, kYawErrorDeg * kRadPerDeg, 1e-9);
  EXPECT_LT((result.offset_m - kOffsetErrorM).norm(), 1e-9);
  EXPECT_EQ(result.tilt_rad, 0.0);
}

TEST(PoseCorrection, PaperModeDeltaIsRzWithTheShiftInTheRegistrationBrickFrame)
{
  const Eigen::Isometry3d truth = truePose();
  const Eigen::Isometry3d pose = poseWithYawAndOffsetError(truth);
  const MeasuredFace face = exactFace(truth);
  const PoseCorrection result = correctPose(pose, redBrick(), face, withMode(CorrectionMode::kPaper));

  // FinalPose = Pose x [Rz(theta) | dt'] with dt' = R^T dt (see the derivation
  // in pose_correction.cpp): the camera-frame dt would be wrong here.
  EXPECT_LT((result.delta_in_brick.linear() - rotZ(result.yawDeg())).norm(), 1e-12);
  EXPECT_LT((result.delta_in_brick.translation() - pose.linear().transpose() * kOffsetErrorM).norm(), 1e-12);
  EXPECT_LT(maxDifference(pose * result.delta_in_brick, result.corrected_pose), 1e-12);
  // The corrected pose maps the model origin exactly onto C1.
  EXPECT_LT((result.corrected_pose * Eigen::Vector3d::Zero() - face.midpoint_m()).norm(), 1e-12);
}

TEST(PoseCorrection, PaperModeKeepsTheTiltOfTheRegistration)
{
  // The paper corrects yaw and translation only: with a tilt error the
  // z axis stays where registration put it, and only `full` removes it.
  const Eigen::Isometry3d truth = truePose();
  const Eigen::Isometry3d pose =
      makePose(truth.linear() * rotX(2.0) * rotY(1.5) * rotZ(-kYawErrorDeg), truth.translation() - kOffsetErrorM);
  const MeasuredFace face = exactFace(truth);
  const PoseCorrection result = correctPose(pose, redBrick(), face, withMode(CorrectionMode::kPaper));
  EXPECT_LT((result.corrected_pose.linear().col(2) - pose.linear().col(2)).norm(), 1e-12);
  EXPECT_LT((result.corrected_pose.translation() - face.midpoint_m()).norm(), 1e-12);
  EXPECT_GT(rotationAngleBetween(result.corrected_pose, truth), 1.0 * kRadPerDeg);
}

TEST(PoseCorrection, FullModeRemovesKnownTiltYawAndOffsetExactly)
{
  const double roll_deg = 2.0;
  const double pitch_deg = 1.5;
  const Eigen::Isometry3d truth = truePose();
  const Eigen::Isometry3d pose = makePose(truth.linear() * rotX(roll_deg) * rotY(pitch_deg) * rotZ(-kYawErrorDeg),
                                          truth.translation() - kOffsetErrorM);
  const PoseCorrection result = correctPose(pose, redBrick(), exactFace(truth), withMode(CorrectionMode::kFull));

  EXPECT_LT(maxDifference(result.corrected_pose, truth), 1e-9);
  // The tilt between the z axes of Rx(2) Ry(1.5) and the identity.
  const double expected_tilt_deg = std::acos(std::cos(roll_deg * kRadPerDeg) * std::cos(pitch_deg * kRadPerDeg)) / kRadPerDeg;
  EXPECT_NEAR(result.tiltDeg(), expected_tilt_deg, 1e-9);
  // The yaw is measured after the tilt step, so it is close to, not equal to, the injected yaw.
  EXPECT_NEAR(result.yawDeg(), kYawErrorDeg, 0.1);
  EXPECT_LT((result.offset_m - kOffsetErrorM).norm(), 1e-9);
  EXPECT_LT(maxDifference(pose * result.delta_in_brick, result.corrected_pose), 1e-12);
}

TEST(PoseCorrection, CorrectPoseIsAFixedPointInBothModes)
{
  const Eigen::Isometry3d truth = truePose();
  for (CorrectionMode mode : {CorrectionMode::kPaper, CorrectionMode::kFull})
  {
    const PoseCorrection result = correctPose(truth, redBrick(), exactFace(truth), withMode(mode));
    EXPECT_LT(maxDifference(result.corrected_pose, truth), 1e-12) << toString(mode);
    EXPECT_NEAR(result.yaw_rad, 0.0, 1e-12) << toString(mode);
    EXPECT_NEAR(result.tilt_rad, 0.0, 1e-7) << toString(mode);
  }
}

TEST(PoseCorrection, InputIsFourVectorsSoTheCostIsConstant)
{
  // Constant time by construction: the correction receives no cloud, only
  // T1, T2, the centroid and the normal. Fails if a container sneaks in.
  EXPECT_EQ(sizeof(MeasuredFace), 4 * sizeof(Eigen::Vector3d));
}

TEST(PoseCorrection, FlippedXAxisIsCorrectedByTheSmallAngle)
{
  // Registration found the face turned by half a turn plus 3 deg; the face
  // looks the same after a half turn, so only the 3 deg may be corrected.
  const Eigen::Isometry3d truth = truePose();
  const Eigen::Isometry3d pose = makePose(truth.linear() * rotZ(180.0 - 3.0), truth.translation());
  const Eigen::Isometry3d flipped_truth = makePose(truth.linear() * rotZ(180.0), truth.translation());
  for (CorrectionMode mode : {CorrectionMode::kPaper, CorrectionMode::kFull})
  {
    MeasuredFace face = exactFace(truth);
    const PoseCorrection forward = correctPose(pose, redBrick(), face, withMode(mode));
    std::swap(face.t1_m, face.t2_m);
    const PoseCorrection backward = correctPose(pose, redBrick(), face, withMode(mode));
    for (const PoseCorrection& result : {forward, backward})
    {
      EXPECT_NEAR(result.yawDeg(), 3.0, 1e-9) << toString(mode);
      EXPECT_LT(maxDifference(result.corrected_pose, flipped_truth), 1e-9) << toString(mode);
    }
  }
}

TEST(PoseCorrection, YawIsNeverMoreThanAQuarterTurn)
{
  const Eigen::Isometry3d truth = truePose();
  for (double error_deg = -179.0; error_deg <= 180.0; error_deg += 7.0)
  {
    const Eigen::Isometry3d pose = makePose(truth.linear() * rotZ(error_deg), truth.translation());
    const PoseCorrection result =
        correctPose(pose, redBrick(), exactFace(truth), withMode(CorrectionMode::kPaper));
    EXPECT_LE(std::abs(result.yawDeg()), 90.0 + 1e-9) << error_deg;
    // The corrected x axis is parallel (either sense) to the true one.
    const double alignment = result.corrected_pose.linear().col(0).dot(truth.linear().col(0));
    EXPECT_NEAR(std::abs(alignment), 1.0, 1e-12) << error_deg;
  }
}

TEST(PoseCorrection, FullModeTakesDepthFromThePlaneAndPaperModeFromT1T2)
{
  // T1 and T2 are single depth samples; both read 2 mm too far along the
  // normal here. `full` puts the origin on the fitted plane, `paper` on C1.
  const Eigen::Isometry3d truth = truePose();
  MeasuredFace face = exactFace(truth);
  const Eigen::Vector3d depth_error_m = -2e-3 * face.normal;
  face.t1_m += depth_error_m;
  face.t2_m += depth_error_m;
  const PoseCorrection full = correctPose(truth, redBrick(), face, withMode(CorrectionMode::kFull));
  const PoseCorrection paper = correctPose(truth, redBrick(), face, withMode(CorrectionMode::kPaper));
  EXPECT_LT((full.corrected_pose.translation() - truth.translation()).norm(), 1e-12);
  EXPECT_LT((paper.corrected_pose.translation() - (truth.translation() + depth_error_m)).norm(), 1e-12);
}

// --- degenerate input --------------------------------------------------------

struct DegenerateCase
{
  std::string name;
  std::function<void(Eigen::Isometry3d&, MeasuredFace&)> spoil;
  std::string expected_message_part;
};

class DegenerateInput : public ::testing::TestWithParam<CorrectionMode>
{
};

TEST_P(DegenerateInput, IsRejectedWithAMessageNamingTheProblem)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<DegenerateCase> cases = {
      {"T1 equals T2", [](Eigen::Isometry3d&, MeasuredFace& f) { f.t2_m = f.t1_m; }, "T1 and T2 are 0.00 mm apart"},
      {"T1 too close to T2",
       [](Eigen::Isometry3d&, MeasuredFace& f) { f.t2_m = f.t1_m + 0.004 * (f.t2_m - f.t1_m).normalized(); },
       "less than the minimum"},
      {"T1 and T2 further apart than the brick",
       [](Eigen::Isometry3d&, MeasuredFace& f) { f.t2_m = f.t1_m + 0.5 * (f.t2_m - f.t1_m).normalized(); },
       "not on one top face"},
      {"NaN in T1", [nan](Eigen::Isometry3d&, MeasuredFace& f) { f.t1_m.x() = nan; }, "T1 is not finite"},
      {"Inf in T2", [inf](Eigen::Isometry3d&, MeasuredFace& f) { f.t2_m.z() = inf; }, "T2 is not finite"},
      {"NaN in centroid", [nan](Eigen::Isometry3d&, MeasuredFace& f) { f.centroid_m.y() = nan; },
       "centroid is not finite"},
      {"NaN in normal", [nan](Eigen::Isometry3d&, MeasuredFace& f) { f.normal.y() = nan; }, "normal is not finite"},
      {"NaN in pose", [nan](Eigen::Isometry3d& p, MeasuredFace&) { p.translation().x() = nan; },
       "pose is not finite"},
      {"Inf in pose rotation", [inf](Eigen::Isometry3d& p, MeasuredFace&) { p.linear()(0, 0) = inf; },
       "pose is not finite"},
      {"scaled pose", [](Eigen::Isometry3d& p, MeasuredFace&) { p.linear() *= 1.1; }, "not a rigid transform"},
      {"mirrored pose", [](Eigen::Isometry3d& p, MeasuredFace&) { p.linear().col(1) *= -1.0; },
       "not a rigid transform"},
      {"zero normal", [](Eigen::Isometry3d&, MeasuredFace& f) { f.normal.setZero(); }, "normal is zero"},
      {"normal away from the camera", [](Eigen::Isometry3d&, MeasuredFace& f) { f.normal = -f.normal; },
       "points away from the camera"},
      {"normal perpendicular to the line of sight",
       [](Eigen::Isometry3d&, MeasuredFace& f) {
         f.normal = f.centroid_m.cross(f.t2_m - f.t1_m).normalized();
       },
       "perpendicular to the line of sight"},
      {"T1->T2 along the normal",
       [](Eigen::Isometry3d&, MeasuredFace& f) { f.t2_m = f.t1_m + 0.2 * f.normal.normalized(); },
       "parallel to the face normal"},
  };
  for (const DegenerateCase& test_case : cases)
  {
    Eigen::Isometry3d pose = truePose();
    MeasuredFace face = exactFace(pose);
    test_case.spoil(pose, face);
    try
    {
      correctPose(pose, redBrick(), face, withMode(GetParam()));
      ADD_FAILURE() << test_case.name << ": accepted";
    }
    catch (const InputError& e)
    {
      EXPECT_NE(std::string(e.what()).find(test_case.expected_message_part), std::string::npos)
          << test_case.name << ": " << e.what();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(BothModes, DegenerateInput, ::testing::Values(CorrectionMode::kPaper, CorrectionMode::kFull),
                         [](const ::testing::TestParamInfo<CorrectionMode>& info) { return std::string(toString(info.param)); });

TEST(PoseCorrection, FullModeRejectsANormalFarFromThePose)
{
  // The face seen edge-on by the pose (normal perpendicular to its z axis):
  // no tilt correction should swing the pose by 90 deg.
  const Eigen::Isometry3d truth = truePose();
  const Eigen::Isometry3d pose = makePose(truth.linear() * rotY(90.0), truth.translation());
  try
  {
    correctPose(pose, redBrick(), exactFace(truth), withMode(CorrectionMode::kFull));
    FAIL() << "a 90 deg tilt was accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("from the registration pose's z axis"), std::string::npos) << e.what();
  }
}

TEST(PoseCorrection, PaperModeRejectsT1T2AlongThePoseZAxis)
{
  const Eigen::Isometry3d truth = truePose();
  const Eigen::Isometry3d pose = makePose(truth.linear() * rotY(90.0), truth.translation());
  try
  {
    correctPose(pose, redBrick(), exactFace(truth), withMode(CorrectionMode::kPaper));
    FAIL() << "T1->T2 along the pose z axis was accepted";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find("parallel to the registration pose's z axis"), std::string::npos)
        << e.what();
  }
}

TEST(PoseCorrection, BrickWithoutLengthIsAConfigError)
{
  BrickType brick = redBrick();
  brick.length_m = 0.0;
  const Eigen::Isometry3d truth = truePose();
  EXPECT_THROW(correctPose(truth, brick, exactFace(truth)), ConfigError);
}

// --- noise ---------------------------------------------------------------------

struct NoiseResiduals
{
  double yaw_rms_rad = 0.0;
  double yaw_max_rad = 0.0;
  double in_plane_rms_m = 0.0;
  double out_of_plane_rms_m = 0.0;
};

/// Corrects a randomly wrong pose (yaw up to 5 deg, offset up to 5 mm, no tilt)
/// from T1/T2 carrying isotropic gaussian noise, once per seed.
NoiseResiduals residualsUnderT1T2Noise(CorrectionMode mode, double sigma_m, int seeds)
{
  const Eigen::Isometry3d truth = truePose();
  const Eigen::Vector3d normal = truth.linear().col(2);
  double yaw_sum_sq = 0.0;
  double in_plane_sum_sq = 0.0;
  double out_of_plane_sum_sq = 0.0;
  NoiseResiduals residuals;
  for (int seed = 1; seed <= seeds; ++seed)
  {
    std::mt19937 random(static_cast<std::mt19937::result_type>(seed));
    std::normal_distribution<double> noise(0.0, sigma_m);
    std::uniform_real_distribution<double> yaw_error_deg(-5.0, 5.0);
    std::uniform_real_distribution<double> offset_error_m(-5e-3, 5e-3);
    const Eigen::Vector3d offset(offset_error_m(random), offset_error_m(random), offset_error_m(random));
    const Eigen::Isometry3d pose = makePose(truth.linear() * rotZ(yaw_error_deg(random)), truth.translation() + offset);
    MeasuredFace face = exactFace(truth);
    face.t1_m += Eigen::Vector3d(noise(random), noise(random), noise(random));
    face.t2_m += Eigen::Vector3d(noise(random), noise(random), noise(random));

    const PoseCorrection result = correctPose(pose, redBrick(), face, withMode(mode));
    // No tilt error and an exact normal: the residual rotation is a pure yaw.
    const double yaw_residual_rad = rotationAngleBetween(result.corrected_pose, truth);
    const Eigen::Vector3d position_residual_m = result.corrected_pose.translation() - truth.translation();
    const double out_of_plane_m = normal.dot(position_residual_m);
    yaw_sum_sq += yaw_residual_rad * yaw_residual_rad;
    residuals.yaw_max_rad = std::max(residuals.yaw_max_rad, yaw_residual_rad);
    out_of_plane_sum_sq += out_of_plane_m * out_of_plane_m;
    in_plane_sum_sq += position_residual_m.squaredNorm() - out_of_plane_m * out_of_plane_m;
  }
  residuals.yaw_rms_rad = std::sqrt(yaw_sum_sq / seeds);
  residuals.in_plane_rms_m = std::sqrt(in_plane_sum_sq / seeds);
  residuals.out_of_plane_rms_m = std::sqrt(out_of_plane_sum_sq / seeds);
  return residuals;
}

TEST(PoseCorrection, ResidualsUnderOneMillimetreNoiseMatchTheErrorPropagation)
{
  // With noise sigma on each coordinate of T1 and T2, a distance L apart:
  // the in-plane component across T1->T2 of (n2 - n1) has sigma*sqrt(2), so
  // the yaw residual has rms sigma*sqrt(2)/L (0.41 deg here); the midpoint
  // carries sigma/sqrt(2) per axis, so 2 in-plane axes give rms sigma and the
  // normal axis sigma/sqrt(2) in `paper` mode and 0 in `full` mode (depth
  // from the plane). Bounds of +-20% are ~5 standard errors of the rms over
  // 400 seeds.
  const double sigma_m = 1e-3;
  const int seeds = 400;
  const double expected_yaw_rms_rad = sigma_m * std::sqrt(2.0) / (2.0 * kHalfSeparationM);
  for (CorrectionMode mode : {CorrectionMode::kPaper, CorrectionMode::kFull})
  {
    const NoiseResiduals residuals = residualsUnderT1T2Noise(mode, sigma_m, seeds);
    EXPECT_GT(residuals.yaw_rms_rad, 0.8 * expected_yaw_rms_rad) << toString(mode);
    EXPECT_LT(residuals.yaw_rms_rad, 1.2 * expected_yaw_rms_rad) << toString(mode);
    EXPECT_LT(residuals.yaw_max_rad, 5.0 * expected_yaw_rms_rad) << toString(mode);
    EXPECT_GT(residuals.in_plane_rms_m, 0.8 * sigma_m) << toString(mode);
    EXPECT_LT(residuals.in_plane_rms_m, 1.2 * sigma_m) << toString(mode);
    if (mode == CorrectionMode::kFull)
    {
      EXPECT_LT(residuals.out_of_plane_rms_m, 1e-12);
    }
    else
    {
      EXPECT_GT(residuals.out_of_plane_rms_m, 0.8 * sigma_m / std::sqrt(2.0));
      EXPECT_LT(residuals.out_of_plane_rms_m, 1.2 * sigma_m / std::sqrt(2.0));
    }
  }
}

// --- plane fit -----------------------------------------------------------------

// --- mode names ------------------------------------------------------------------

TEST(CorrectionMode, NamesRoundTripAndUnknownNamesAreRejected)
{
  for (CorrectionMode mode : {CorrectionMode::kPaper, CorrectionMode::kFull})
    EXPECT_EQ(parseCorrectionMode(toString(mode)), mode);
  EXPECT_EQ(parseCorrectionMode("paper"), CorrectionMode::kPaper);
  try
  {
    parseCorrectionMode("Full ");
    FAIL() << "'Full ' accepted";
  }
  catch (const ConfigError& e)
  {
    EXPECT_NE(std::string(e.what()).find("paper, full"), std::string::npos) << e.what();
  }
}
}  // namespace brick_pose
