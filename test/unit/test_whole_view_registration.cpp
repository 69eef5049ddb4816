#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/registration/brick_symmetry.h"
#include "brick_pose/registration/model_cloud.h"
#include "brick_pose/registration/model_symmetry.h"
#include "brick_pose/registration/super4pcs.h"
#include "brick_pose/registration/view_consistency.h"
#include "brick_pose/registration/whole_view_registration.h"

namespace brick_pose
{
namespace registration
{
namespace
{
BrickType brickOf(const std::string& name) { return BrickCatalogue::mbzirc2020().at(name); }

BrickType cardboardBox()
{
  BrickType box;
  box.name = "cardboard";
  box.length_m = 0.40;
  box.width_m = 0.30;
  box.height_m = 0.20;
  return box;
}

/// A camera-frame pose that shows the brick from above and a side: the brick
/// centre 0.8-1.4 m in front of the camera, tilted towards it.
Eigen::Isometry3d viewPose(std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double yaw = 2.0 * M_PI * unit(rng);
  const double tilt = (30.0 + 40.0 * unit(rng)) * M_PI / 180.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  // Brick z towards the camera (-z of the camera), then tilted about camera x.
  pose.linear() = Eigen::AngleAxisd(M_PI - tilt, Eigen::Vector3d::UnitX()).toRotationMatrix() *
                  Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = Eigen::Vector3d(0.1 * (unit(rng) - 0.5), 0.1 * (unit(rng) - 0.5), 0.8 + 0.6 * unit(rng));
  return pose;
}

/// What a camera at the origin sees of the brick at `pose`: every face turned
/// towards it (cosine > 0.2), sampled on a jittered 5 mm grid, with noise.
PointSet visibleSurface(const BrickType& brick, const Eigen::Isometry3d& pose, double sigma_m, std::mt19937_64& rng)
{
  const PointSet surface = buildCuboidSurfaceCloud(brick, 0.005);
  std::normal_distribution<double> noise(0.0, sigma_m);
  std::uniform_real_distribution<double> jitter(-0.002, 0.002);
  PointSet view;
  for (std::size_t i = 0; i < surface.size(); ++i)
  {
    const Eigen::Vector3d p = pose * (surface.points[i] + Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng)).cwiseProduct(
                                                               Eigen::Vector3d::Ones() - surface.normals[i].cwiseAbs()));
    const Eigen::Vector3d n = pose.linear() * surface.normals[i];
    if (n.dot(-p.normalized()) > 0.2)
      view.points.push_back(p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
  }
  return view;
}

Super4PCSParams viewParams(std::uint64_t seed)
{
  Super4PCSParams params;
  params.seed = seed;
  params.view.mode = ViewMode::kOn;
  params.max_time_s = 60.0;  // the work budget bounds the tests, not the clock
  return params;
}
}  // namespace

TEST(CuboidSymmetries, CountsFollowTheEqualDimensions)
{
  EXPECT_EQ(cuboidSymmetries(cardboardBox().dimensions_m()).size(), 4u);
  EXPECT_EQ(cuboidSymmetries(brickOf("red").dimensions_m()).size(), 8u);  // 0.2 x 0.2 cross-section
  EXPECT_EQ(cuboidSymmetries(Eigen::Vector3d(0.2, 0.2, 0.2)).size(), 24u);
  for (const Eigen::Isometry3d& symmetry : cuboidSymmetries(brickOf("red").dimensions_m()))
    EXPECT_TRUE((symmetry * Eigen::Vector3d(0.0, 0.0, -0.1)).isApprox(Eigen::Vector3d(0.0, 0.0, -0.1)));
}

TEST(CuboidSymmetries, PoseErrorForgivesOnlyTrueSymmetries)
{
  const Eigen::Vector3d dims = brickOf("red").dimensions_m();
  const std::vector<Eigen::Isometry3d> symmetries = cuboidSymmetries(dims);
  const Eigen::Isometry3d truth = Eigen::Translation3d(0.1, 0.0, 1.0) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY());
  for (const Eigen::Isometry3d& symmetry : symmetries)
  {
    const PoseError error = poseErrorModuloSymmetries(truth * symmetry, truth, symmetries);
    EXPECT_NEAR(error.rotation_deg, 0.0, 1e-6);
    EXPECT_NEAR(error.translation_m, 0.0, 1e-9);
  }
  // A quarter turn about z is no symmetry of a 0.3 x 0.2 x 0.2 brick.
  Eigen::Isometry3d turned = truth;
  turned.linear() = truth.linear() * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_NEAR(poseErrorModuloSymmetries(turned, truth, symmetries).rotation_deg, 90.0, 1e-6);
}

TEST(CuboidSurfaceCloud, CoversSixFacesOnceWithOutwardNormals)
{
  const BrickType brick = cardboardBox();
  const PointSet cloud = buildCuboidSurfaceCloud(brick, 0.01);
  ASSERT_EQ(cloud.normals.size(), cloud.size());
  const Eigen::Vector3d centre(0.0, 0.0, -0.5 * brick.height_m);
  int per_axis[3] = {0, 0, 0};
  for (std::size_t i = 0; i < cloud.size(); ++i)
  {
    EXPECT_GT(cloud.normals[i].dot(cloud.points[i] - centre), 0.0);
    int axis = 0;
    cloud.normals[i].cwiseAbs().maxCoeff(&axis);
    ++per_axis[axis];
    for (std::size_t j = i + 1; j < cloud.size(); ++j)
      ASSERT_GT((cloud.points[i] - cloud.points[j]).norm(), 1e-9) << "duplicate point " << i;
  }
  // 41 x 31 on top and bottom, 41 x 19 on the long sides, 29 x 19 on the ends.
  EXPECT_EQ(per_axis[2], 2 * 41 * 31);
  EXPECT_EQ(per_axis[1], 2 * 41 * 19);
  EXPECT_EQ(per_axis[0], 2 * 29 * 19);
}

TEST(ModelSymmetries, FindsTheCrossSectionQuarterTurnsOnlyOnAWholeModel)
{
  const PointSet whole = buildCuboidSurfaceCloud(brickOf("red"), 0.01);
  const PointGrid grid(whole.points, 0.008);
  ModelSymmetries found = findModelSymmetries(whole, grid, whole, 0.008);
  EXPECT_TRUE(found.box_like);
  EXPECT_EQ(found.symmetries.size(), 8u);
  EXPECT_EQ(found.alternatives.size(), 2u);  // 24 / 8 classes, less the identity's
  EXPECT_TRUE(found.centre_m.isApprox(Eigen::Vector3d(0.0, 0.0, -0.1), 1e-9));

  ModelCloudParams options;
  options.sides = {BrickSide::kPlusX, BrickSide::kPlusY};
  const PointSet partial = buildBrickModelCloud(brickOf("red"), options);
  const PointGrid partial_grid(partial.points, 0.008);
  found = findModelSymmetries(partial, partial_grid, partial, 0.008);
  EXPECT_EQ(found.symmetries.size(), 1u);
}

TEST(ViewConsistency, RejectsANearSymmetricPoseAndAPoseInFreeSpace)
{
  const BrickType brick = brickOf("red");
  std::mt19937_64 rng(5);
  const Eigen::Isometry3d truth = viewPose(rng);
  PointSet scan = visibleSurface(brick, truth, 0.001, rng);
  PointSet model = buildCuboidSurfaceCloud(brick, 0.005);
  // Exact normals of the scan, turned to the camera.
  scan.normals.clear();
  const PointSet surface = buildCuboidSurfaceCloud(brick, 0.005);
  std::vector<int> all;
  for (std::size_t i = 0; i < scan.size(); ++i)
  {
    int nearest = 0;
    double best = 1e9;
    const Eigen::Vector3d local = truth.inverse() * scan.points[i];
    for (std::size_t m = 0; m < surface.size(); ++m)
      if ((surface.points[m] - local).squaredNorm() < best)
      {
        best = (surface.points[m] - local).squaredNorm();
        nearest = static_cast<int>(m);
      }
    scan.normals.push_back(truth.linear() * surface.normals[nearest]);
    all.push_back(static_cast<int>(i));
  }
  ViewConsistencyParams check;
  check.match_radius_m = 0.008;
  const ViewConsistency consistency(model, model, scan, all, check);

  const ViewScore right = consistency.evaluate(truth);
  EXPECT_GT(right.target_coverage, 0.95);
  EXPECT_GT(right.model_coverage, 0.9);
  EXPECT_LT(right.free_space_violation, 0.02);

  // A quarter turn about the brick's z through its centre: a 0.2 x 0.3 box.
  Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
  turn.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const ViewScore turned = consistency.evaluate(truth * turn);
  EXPECT_LT(turned.combined(), right.combined() - 0.15);

  // The whole brick 10 cm closer to the camera: it hides what the camera saw.
  Eigen::Isometry3d closer = truth;
  closer.translation() -= 0.1 * truth.translation().normalized();
  const ViewScore in_front = consistency.evaluate(closer);
  EXPECT_GT(in_front.free_space_violation, 0.5);
}

/// A square face 1 m in front of the camera, turned towards it, sampled on a
/// grid of `spacing_m` starting at `offset_m`.
PointSet facingSquare(double spacing_m, double offset_m)
{
  PointSet face;
  for (double x = -0.1 + offset_m; x <= 0.1; x += spacing_m)
    for (double y = -0.1 + offset_m; y <= 0.1; y += spacing_m)
    {
      face.points.emplace_back(x, y, 1.0);
      face.normals.emplace_back(0.0, 0.0, -1.0);
    }
  return face;
}

// An evenly thinned scan leaves gaps of about two spacings between its points:
// a face seen whole must count as seen although some of its model points have
// no scan point within the match radius.
TEST(ViewConsistency, AFaceSeenWholeByAThinnedScanCountsAsSeen)
{
  const PointSet model = facingSquare(0.002, 0.001);
  const PointSet scan = facingSquare(0.01, 0.0);
  std::vector<int> all(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i)
    all[i] = static_cast<int>(i);
  ViewConsistencyParams check;
  check.match_radius_m = 0.0045;
  const ViewConsistency at_match_radius(model, model, scan, all, check);
  const ViewScore narrow = at_match_radius.evaluate(Eigen::Isometry3d::Identity());
  EXPECT_LT(narrow.model_coverage, 0.75);
  EXPECT_GT(narrow.target_coverage, 0.99);

  check.seen_radius_m = 1.5 * check.match_radius_m;
  const ViewConsistency at_seen_radius(model, model, scan, all, check);
  const ViewScore wide = at_seen_radius.evaluate(Eigen::Isometry3d::Identity());
  EXPECT_GT(wide.model_coverage, 0.9);
  EXPECT_DOUBLE_EQ(wide.target_coverage, narrow.target_coverage);

  // Moved by a face's width, the face is not seen however wide the radius.
  Eigen::Isometry3d moved = Eigen::Isometry3d::Identity();
  moved.translation().x() = 0.25;
  EXPECT_LT(at_seen_radius.evaluate(moved).model_coverage, 0.01);
}

TEST(WholeViewRegistration, RecoversCuboidViewsUpToTheirTrueSymmetries)
{
  for (const BrickType& brick : {brickOf("red"), cardboardBox(), brickOf("green")})
  {
    const PointSet model = buildCuboidSurfaceCloud(brick, 0.01);
    const std::vector<Eigen::Isometry3d> symmetries = cuboidSymmetries(brick.dimensions_m());
    std::mt19937_64 rng(17);
    int claimed = 0;
    for (int trial = 0; trial < 3; ++trial)
    {
      const Eigen::Isometry3d truth = viewPose(rng);
      const PointSet scan = visibleSurface(brick, truth, 0.0015, rng);
      const RegistrationResult result = Super4PCS(viewParams(100 + trial)).align(model, scan);
      SCOPED_TRACE(brick.name + " trial " + std::to_string(trial) + ": " + result.reason);
      EXPECT_TRUE(result.view_checked);
      EXPECT_EQ(result.true_symmetries, static_cast<int>(symmetries.size()));
      const PoseError error = poseErrorModuloSymmetries(result.source_to_target, truth, symmetries);
      // Never a confident wrong answer; a right one is found.
      EXPECT_LT(error.rotation_deg, 3.0);
      EXPECT_LT(error.translation_m, 0.008);
      if (result.success)
      {
        ++claimed;
        EXPECT_GE(result.confidence, viewParams(0).view.min_confidence);
      }
    }
    EXPECT_GE(claimed, 2) << brick.name;
  }
}

/// The camera looks along the brick's long axis at its -x end face, 1 m
/// away and level with it: it sees that 0.2 x 0.2 face alone.
Eigen::Isometry3d endOnPose(const BrickType& brick)
{
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  // Brick x along the line of sight, brick z up (camera -y).
  pose.linear() << 0.0, -1.0, 0.0, 0.0, 0.0, -1.0, 1.0, 0.0, 0.0;
  const Eigen::Vector3d centre_in_brick(0.0, 0.0, -0.5 * brick.height_m);
  const Eigen::Vector3d centre_in_camera(0.01, 0.02, 1.0 + 0.5 * brick.length_m);
  pose.translation() = centre_in_camera - pose.linear() * centre_in_brick;
  return pose;
}

// A lone end face covers any part of a side as well as the end: the search
// can match it all along the sides and spend its whole budget there. The
// other orientations of its first such leader, placed on the scan, hold the
// answer: the search stops there, well inside its budget.
TEST(WholeViewRegistration, ALoneEndFaceIsFoundEndOnInsideTheBudget)
{
  for (const BrickType& brick : {brickOf("red"), brickOf("blue")})
  {
    const PointSet model = buildCuboidSurfaceCloud(brick, 0.01);
    const std::vector<Eigen::Isometry3d> symmetries = cuboidSymmetries(brick.dimensions_m());
    const Eigen::Isometry3d truth = endOnPose(brick);
    std::mt19937_64 rng(31);
    const PointSet scan = visibleSurface(brick, truth, 0.0015, rng);
    for (int seed = 1; seed <= 3; ++seed)
    {
      const Super4PCSParams params = viewParams(seed);
      const RegistrationResult result = Super4PCS(params).align(model, scan);
      SCOPED_TRACE(brick.name + " seed " + std::to_string(seed) + ": " + result.reason);
      const PoseError error = poseErrorModuloSymmetries(result.source_to_target, truth, symmetries);
      EXPECT_LT(error.rotation_deg, 3.0);
      EXPECT_LT(error.translation_m, 0.008);
      EXPECT_TRUE(result.success);
      EXPECT_LT(result.candidates_verified, params.view.max_candidates);
    }
  }
}

TEST(WholeViewRegistration, SameSeedGivesIdenticalResult)
{
  const BrickType brick = brickOf("red");
  std::mt19937_64 rng(23);
  const PointSet model = buildCuboidSurfaceCloud(brick, 0.01);
  const PointSet scan = visibleSurface(brick, viewPose(rng), 0.0015, rng);
  const RegistrationResult first = Super4PCS(viewParams(7)).align(model, scan);
  const RegistrationResult second = Super4PCS(viewParams(7)).align(model, scan);
  EXPECT_TRUE(first.source_to_target.matrix() == second.source_to_target.matrix());
  EXPECT_EQ(first.confidence, second.confidence);
  EXPECT_EQ(first.candidates_verified, second.candidates_verified);
  EXPECT_EQ(first.success, second.success);
}

TEST(WholeViewRegistration, SaysItIsNotSureOfAViewThatFitsNothing)
{
  // A flat disc is no view of a brick: nothing explains it as a brick face
  // with the faces the pose turns towards the camera seen.
  const PointSet model = buildCuboidSurfaceCloud(brickOf("red"), 0.01);
  PointSet disc;
  for (double r = 0.0; r <= 0.5; r += 0.01)
    for (double a = 0.0; a < 2.0 * M_PI; a += 0.02 / std::max(r, 0.01))
      disc.points.emplace_back(r * std::cos(a), r * std::sin(a), 1.0);
  const RegistrationResult result = Super4PCS(viewParams(3)).align(model, disc);
  EXPECT_FALSE(result.success);
  EXPECT_NE(result.reason.find("no pose covers"), std::string::npos) << result.reason;
}

TEST(WholeViewRegistration, AutoModeChoosesByTheModel)
{
  EXPECT_TRUE(isMultiFaceModel(buildCuboidSurfaceCloud(brickOf("red"), 0.02)));
  EXPECT_FALSE(isMultiFaceModel(buildBrickModelCloud(brickOf("red"))));
  PointSet points_only = buildCuboidSurfaceCloud(brickOf("red"), 0.02);
  points_only.normals.clear();
  EXPECT_TRUE(isMultiFaceModel(points_only));
}

TEST(WholeViewRegistration, RejectsBadViewParameters)
{
  Super4PCSParams params;
  params.view.min_confidence = 1.5;
  EXPECT_THROW(params.validate(), ConfigError);
  params = Super4PCSParams();
  params.view.viewpoint_m.x() = std::nan("");
  EXPECT_THROW(params.validate(), ConfigError);
  params = Super4PCSParams();
  params.view.max_candidates = 0;
  EXPECT_THROW(params.validate(), ConfigError);
}
}  // namespace registration
}  // namespace brick_pose
