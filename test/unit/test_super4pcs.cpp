#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/registration/boundary_icp.h"
#include "brick_pose/registration/brick_symmetry.h"
#include "brick_pose/registration/model_cloud.h"
#include "brick_pose/registration/shell_pair_index.h"
#include "brick_pose/registration/super4pcs.h"

namespace brick_pose
{
namespace registration
{
namespace
{
BrickType redBrick() { return BrickCatalogue::mbzirc2020().at("red"); }

Eigen::Isometry3d randomPose(std::mt19937_64& rng, double min_distance_m, double max_distance_m)
{
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> distance(min_distance_m, max_distance_m);
  std::uniform_real_distribution<double> lateral(-0.2, 0.2);
  Eigen::Quaterniond q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = q.normalized().toRotationMatrix();
  pose.translation() = Eigen::Vector3d(lateral(rng), lateral(rng), distance(rng));
  return pose;
}

/// Like a depth image of the brick: each face sampled on a square grid of
/// `spacing_m` that is rotated and shifted at random relative to the brick
/// edges (so it never coincides with the model's grid).
PointSet sampleBrickSurface(const BrickType& brick, const std::vector<BrickSide>& sides, double spacing_m,
                            std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double l = brick.length_m;
  const double w = brick.width_m;
  const double h = brick.height_m;
  PointSet cloud;
  // Grid over the rectangle centre + a * u + b * v, |a| <= a_half, |b| <= b_half.
  auto addFace = [&](const Eigen::Vector3d& centre, const Eigen::Vector3d& u, double a_half, const Eigen::Vector3d& v,
                     double b_half, const Eigen::Vector3d& normal) {
    const double angle = 2.0 * M_PI * unit(rng);
    const Eigen::Vector2d offset(unit(rng) * spacing_m, unit(rng) * spacing_m);
    const Eigen::Rotation2Dd rotation(angle);
    const double reach = std::hypot(a_half, b_half) + spacing_m;
    for (double i = -reach; i <= reach; i += spacing_m)
      for (double j = -reach; j <= reach; j += spacing_m)
      {
        const Eigen::Vector2d ab = rotation * (Eigen::Vector2d(i, j) + offset);
        if (std::abs(ab.x()) <= a_half && std::abs(ab.y()) <= b_half)
        {
          cloud.points.push_back(centre + ab.x() * u + ab.y() * v);
          cloud.normals.push_back(normal);
        }
      }
  };
  const Eigen::Vector3d x = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d y = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  addFace(Eigen::Vector3d::Zero(), x, 0.5 * l, y, 0.5 * w, z);
  for (BrickSide side : sides)
  {
    switch (side)
    {
      case BrickSide::kPlusX:
        addFace({0.5 * l, 0.0, -0.5 * h}, y, 0.5 * w, z, 0.5 * h, x);
        break;
      case BrickSide::kMinusX:
        addFace({-0.5 * l, 0.0, -0.5 * h}, y, 0.5 * w, z, 0.5 * h, -x);
        break;
      case BrickSide::kPlusY:
        addFace({0.0, 0.5 * w, -0.5 * h}, x, 0.5 * l, z, 0.5 * h, y);
        break;
      case BrickSide::kMinusY:
        addFace({0.0, -0.5 * w, -0.5 * h}, x, 0.5 * l, z, 0.5 * h, -y);
        break;
    }
  }
  return cloud;
}

PointSet transformWithNoise(const PointSet& cloud, const Eigen::Isometry3d& pose, double sigma_m,
                            std::mt19937_64& rng)
{
  std::normal_distribution<double> noise(0.0, sigma_m);
  PointSet out;
  for (std::size_t i = 0; i < cloud.size(); ++i)
  {
    out.points.push_back(pose * cloud.points[i] + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
    if (cloud.hasNormals())
      out.normals.push_back(pose.linear() * cloud.normals[i]);
  }
  return out;
}

void addUniformOutliers(PointSet& cloud, double fraction, double margin_m, std::mt19937_64& rng)
{
  Eigen::Vector3d lower = cloud.points.front();
  Eigen::Vector3d upper = lower;
  for (const Eigen::Vector3d& p : cloud.points)
  {
    lower = lower.cwiseMin(p);
    upper = upper.cwiseMax(p);
  }
  lower.array() -= margin_m;
  upper.array() += margin_m;
  const int count = static_cast<int>(std::lround(fraction * cloud.size() / (1.0 - fraction)));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < count; ++i)
    cloud.points.push_back(lower + Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).cwiseProduct(upper - lower));
  cloud.normals.clear();
}

Super4PCSParams testParams(std::uint64_t seed)
{
  Super4PCSParams params;
  params.seed = seed;
  // Far beyond any run: max_bases bounds the search, so the result depends
  // on the seed alone, not on the machine (sanitizer builds are ~5x slower).
  params.max_time_s = 600.0;
  return params;
}

void expectPoseNear(const RegistrationResult& result, const Eigen::Isometry3d& truth, ModelSymmetry symmetry,
                    double max_rotation_deg, double max_translation_m)
{
  ASSERT_TRUE(result.success) << result.reason;
  const PoseError error = poseErrorModuloSymmetry(result.source_to_target, truth, symmetry);
  EXPECT_LT(error.rotation_deg, max_rotation_deg) << "LCP " << result.lcp_score << ", " << result.reason;
  EXPECT_LT(error.translation_m, max_translation_m) << "LCP " << result.lcp_score << ", " << result.reason;
}

std::vector<std::pair<int, int>> sorted(std::vector<std::pair<int, int>> pairs)
{
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}
}  // namespace

TEST(ShellPairIndex, FindsExactlyTheBruteForcePairsOnARandomCloud)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-0.2, 0.2);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 600; ++i)
    points.emplace_back(unit(rng), unit(rng), unit(rng));
  for (int i = 0; i < 200; ++i)  // a dense flat patch as well
    points.emplace_back(0.05 * unit(rng), 0.05 * unit(rng), 0.1);
  points.push_back(points[3]);  // a duplicate
  for (double cell_m : {0.002, 0.005, 0.03})
  {
    const ShellPairIndex index(points, cell_m);
    for (double radius_m : {0.0, 0.01, 0.07, 0.2, 0.45})
      for (double tolerance_m : {0.001, 0.005, 0.02})
      {
        const auto expected = bruteForcePairsInShell(points, radius_m, tolerance_m);
        const auto actual = sorted(index.pairsInShell(radius_m, tolerance_m));
        EXPECT_EQ(actual, expected) << "cell " << cell_m << " r " << radius_m << " tol " << tolerance_m;
      }
  }
}

TEST(ShellPairIndex, EmptyAndTinyCloudsGiveNoPairs)
{
  const std::vector<Eigen::Vector3d> none;
  EXPECT_TRUE(ShellPairIndex(none, 0.01).pairsInShell(0.1, 0.01).empty());
  const std::vector<Eigen::Vector3d> two{{0, 0, 0}, {0.1, 0, 0}};
  const auto pairs = ShellPairIndex(two, 0.01).pairsInShell(0.1, 0.001);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], std::make_pair(0, 1));
}

TEST(Super4PCS, RecoversNoisyBrickFaceFromAnyRotation)
{
  const BrickType brick = redBrick();
  const PointSet model = buildBrickModelCloud(brick);
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 10; ++trial)
  {
    const Eigen::Isometry3d truth = randomPose(rng, 0.5, 2.0);
    const PointSet target = transformWithNoise(sampleBrickSurface(brick, {}, 0.005, rng), truth, 0.0015, rng);
    const RegistrationResult result = Super4PCS(testParams(100 + trial)).align(model, target);
    SCOPED_TRACE("trial " + std::to_string(trial));
    // The face's edges are only sampled every 5 mm, which bounds how well
    // the in-plane position and yaw can be known (typically < 1 deg, 3 mm).
    expectPoseNear(result, truth, ModelSymmetry::kHalfTurnZ, 3.0, 0.008);
  }
}

TEST(Super4PCS, WorksWithoutNormalsUpToTheRectangleSymmetry)
{
  const BrickType brick = redBrick();
  PointSet model = buildBrickModelCloud(brick);
  model.normals.clear();
  std::mt19937_64 rng(12);
  for (int trial = 0; trial < 4; ++trial)
  {
    const Eigen::Isometry3d truth = randomPose(rng, 0.5, 2.0);
    PointSet target = transformWithNoise(sampleBrickSurface(brick, {}, 0.005, rng), truth, 0.0015, rng);
    target.normals.clear();
    const RegistrationResult result = Super4PCS(testParams(200 + trial)).align(model, target);
    SCOPED_TRACE("trial " + std::to_string(trial));
    expectPoseNear(result, truth, ModelSymmetry::kRectangle, 4.0, 0.008);
  }
}

TEST(Super4PCS, RecoversNoisyThreeFaceCuboidView)
{
  const BrickType brick = redBrick();
  const std::vector<BrickSide> sides{BrickSide::kPlusX, BrickSide::kPlusY};
  ModelCloudParams options;
  options.sides = sides;
  const PointSet model = buildBrickModelCloud(brick, options);
  std::mt19937_64 rng(13);
  for (int trial = 0; trial < 4; ++trial)
  {
    const Eigen::Isometry3d truth = randomPose(rng, 0.5, 2.0);
    const PointSet target = transformWithNoise(sampleBrickSurface(brick, sides, 0.006, rng), truth, 0.0015, rng);
    const RegistrationResult result = Super4PCS(testParams(300 + trial)).align(model, target);
    SCOPED_TRACE("trial " + std::to_string(trial));
    // Three faces fix the pose completely: no symmetry to forgive.
    expectPoseNear(result, truth, ModelSymmetry::kNone, 2.0, 0.005);
  }
}

TEST(Super4PCS, RecoversHalfOverlappingCuboidView)
{
  // The long green brick seen from a corner, against the part of that view
  // beyond the middle of the long edge: the end face and half of the top and
  // side faces, 57 % of the model. (Cut shorter, the part would be a cube
  // corner, which fits the model after a third of a turn about its diagonal
  // as well as it does at the right pose: no score can tell those apart.)
  const BrickType brick = BrickCatalogue::mbzirc2020().at("green");
  const std::vector<BrickSide> sides{BrickSide::kPlusX, BrickSide::kPlusY};
  ModelCloudParams options;
  options.sides = sides;
  const PointSet model = buildBrickModelCloud(brick, options);
  int kept_model_points = 0;
  for (const Eigen::Vector3d& p : model.points)
    kept_model_points += p.x() >= 0.0 ? 1 : 0;
  const double overlap = static_cast<double>(kept_model_points) / model.size();
  ASSERT_GT(overlap, 0.5);
  ASSERT_LT(overlap, 0.6);

  std::mt19937_64 rng(14);
  for (int trial = 0; trial < 4; ++trial)
  {
    const PointSet view = sampleBrickSurface(brick, sides, 0.006, rng);
    std::vector<int> beyond_middle;
    for (std::size_t i = 0; i < view.size(); ++i)
      if (view.points[i].x() >= 0.0)
        beyond_middle.push_back(static_cast<int>(i));
    const Eigen::Isometry3d truth = randomPose(rng, 0.5, 2.0);
    const PointSet target = transformWithNoise(view.subset(beyond_middle), truth, 0.0015, rng);
    Super4PCSParams params = testParams(400 + trial);
    params.overlap = overlap;
    // The wrong third-of-a-turn fit still covers about 50 % of the model:
    // only stop early above that.
    params.good_enough_ratio = 0.95;
    params.max_bases = 1000;  // a base must fall inside the kept part
    const RegistrationResult result = Super4PCS(params).align(model, target);
    SCOPED_TRACE("trial " + std::to_string(trial));
    expectPoseNear(result, truth, ModelSymmetry::kNone, 2.0, 0.005);
  }
}

TEST(Super4PCS, ToleratesTwentyPercentOutliers)
{
  const BrickType brick = redBrick();
  const PointSet model = buildBrickModelCloud(brick);
  std::mt19937_64 rng(15);
  for (int trial = 0; trial < 4; ++trial)
  {
    const Eigen::Isometry3d truth = randomPose(rng, 0.5, 2.0);
    PointSet target = transformWithNoise(sampleBrickSurface(brick, {}, 0.005, rng), truth, 0.0015, rng);
    addUniformOutliers(target, 0.2, 0.05, rng);  // also drops the normals
    const RegistrationResult result = Super4PCS(testParams(500 + trial)).align(model, target);
    SCOPED_TRACE("trial " + std::to_string(trial));
    expectPoseNear(result, truth, ModelSymmetry::kRectangle, 3.0, 0.008);
  }
}

TEST(BoundaryIcp, FindsTheEdgesOfAFaceWithTheirOutwardDirections)
{
  const BrickType brick = BrickCatalogue::mbzirc2020().at("green");
  const PointSet model = buildBrickModelCloud(brick);  // 1 cm grid, edges included
  const double half_l = 0.5 * brick.length_m;
  const double half_w = 0.5 * brick.width_m;
  std::mt19937_64 rng(21);
  for (const bool given_normals : {true, false})
  {
    SCOPED_TRACE(given_normals ? "model normals" : "estimated normals");
    const std::vector<Eigen::Vector3d> none;
    const SurfaceBoundary boundary = findSurfaceBoundary(model.points, given_normals ? model.normals : none,
                                                         neighbourhoodRadius(model.points, 20, rng));
    int edge_points = 0;
    for (const Eigen::Vector3d& p : model.points)
      edge_points += (std::abs(std::abs(p.x()) - half_l) < 1e-6 || std::abs(std::abs(p.y()) - half_w) < 1e-6) ? 1 : 0;
    EXPECT_GE(static_cast<int>(boundary.size()), edge_points * 9 / 10);
    for (std::size_t k = 0; k < boundary.size(); ++k)
    {
      const Eigen::Vector3d& p = boundary.points[k];
      const bool on_end = std::abs(std::abs(p.x()) - half_l) < 1e-6;
      const bool on_side = std::abs(std::abs(p.y()) - half_w) < 1e-6;
      ASSERT_TRUE(on_end || on_side) << "interior point flagged: " << p.transpose();
      // Away from the corners the outward direction is the edge's normal.
      const Eigen::Vector3d expected = on_end && !on_side ? Eigen::Vector3d(p.x() > 0 ? 1 : -1, 0, 0)
                                                          : Eigen::Vector3d(0, p.y() > 0 ? 1 : -1, 0);
      if (on_end != on_side)
      {
        EXPECT_GT(boundary.outward[k].dot(expected), 0.9) << p.transpose();
      }
      EXPECT_LT(std::abs(boundary.outward[k].z()), 0.1);
    }
  }
}

TEST(BoundaryIcp, PointsOnSurfaceDropsPointsOffTheSurface)
{
  const PointSet model = buildBrickModelCloud(redBrick());
  std::mt19937_64 rng(22);
  std::normal_distribution<double> noise(0.0, 0.001);
  std::vector<Eigen::Vector3d> target;
  for (const Eigen::Vector3d& p : model.points)
    target.push_back(p + Eigen::Vector3d(0.003, 0.002, noise(rng)));
  const std::size_t on_surface_count = target.size();
  for (int i = 0; i < 20; ++i)  // "flying pixels" 3-6 cm below the face
    target.push_back(Eigen::Vector3d(0.16 + 0.002 * i, 0.0, -0.03 - 0.0015 * i));
  const OrientedPoints kept = pointsOnSurface(model.points, model.normals, target, Eigen::Isometry3d::Identity(),
                                              0.02, 0.1, 3.0, 0.001);
  EXPECT_GE(kept.size(), on_surface_count * 97 / 100);
  EXPECT_LE(kept.size(), on_surface_count);
  for (std::size_t k = 0; k < kept.size(); ++k)
  {
    EXPECT_GT(kept.points[k].z(), -0.01);
    EXPECT_NEAR(kept.normals[k].z(), 1.0, 1e-9);
  }
}

// The failure mode: on a long face point-to-plane leaves the slide
// along the face free and the hybrid ICP stops within a dead zone of about
// the sample spacing. The boundary pairs take the slide from the end edges.
TEST(BoundaryIcp, SlidesALongFaceIntoPlace)
{
  const BrickType brick = BrickCatalogue::mbzirc2020().at("orange");  // 1.8 m x 0.2 m
  const PointSet model = buildBrickModelCloud(brick);
  std::mt19937_64 rng(23);
  for (int trial = 0; trial < 4; ++trial)
  {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const Eigen::Isometry3d truth = randomPose(rng, 0.5, 2.0);
    const PointSet target = transformWithNoise(sampleBrickSurface(brick, {}, 0.012, rng), truth, 0.002, rng);
    Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();  // in the brick frame
    offset.translation() = Eigen::Vector3d(trial % 2 ? 0.04 : -0.03, 0.008, 0.003);
    offset.linear() = Eigen::AngleAxisd(0.03, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Isometry3d start = truth * offset;

    const SurfaceBoundary source_boundary =
        findSurfaceBoundary(model.points, model.normals, neighbourhoodRadius(model.points, 20, rng));
    const OrientedPoints on_surface =
        pointsOnSurface(model.points, model.normals, target.points, start, 0.02, 0.15, 3.0, 0.002);
    const SurfaceBoundary target_boundary =
        findSurfaceBoundary(on_surface.points, on_surface.normals, neighbourhoodRadius(on_surface.points, 20, rng));
    BoundaryIcpParams options;
    options.plane_radius_m = options.final_plane_radius_m = 0.03;
    options.boundary_radius_m = 0.15;
    options.final_boundary_radius_m = 0.025;
    const Eigen::Isometry3d refined =
        refineBoundaryIcp(model.points, model.normals, source_boundary, target.points, target_boundary, start, options);
    const PoseError error = poseErrorModuloSymmetry(refined, truth, ModelSymmetry::kHalfTurnZ);
    EXPECT_LT(error.translation_m, 0.003);
    EXPECT_LT(error.rotation_deg, 0.3);
  }
}

TEST(Super4PCS, RecoversALongFaceAlongItsAxis)
{
  const BrickType brick = BrickCatalogue::mbzirc2020().at("orange");
  const PointSet model = buildBrickModelCloud(brick);
  std::mt19937_64 rng(24);
  for (int trial = 0; trial < 4; ++trial)
  {
    const Eigen::Isometry3d truth = randomPose(rng, 0.5, 2.0);
    const PointSet target = transformWithNoise(sampleBrickSurface(brick, {}, 0.012, rng), truth, 0.002, rng);
    const RegistrationResult result = Super4PCS(testParams(600 + trial)).align(model, target);
    SCOPED_TRACE("trial " + std::to_string(trial));
    // Within the bench's success bounds with a wide margin: the 4-point pose
    // alone is often several centimetres off along the face.
    expectPoseNear(result, truth, ModelSymmetry::kHalfTurnZ, 1.0, 0.004);
  }
}

TEST(Super4PCS, RefinesTinyAndSparseCloudsWithoutBreaking)
{
  // Too few points for a boundary (the boundary stage must fall back to
  // plain point-to-plane) and a source without normals.
  for (const int side : {3, 5, 8})
  {
    PointSet patch;
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j)
        patch.points.emplace_back(0.02 * i, 0.03 * j, 0.001 * ((i * 7 + j * 3) % 5));
    Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
    truth.translation() = Eigen::Vector3d(0.01, -0.02, 1.0);
    PointSet target;
    for (const Eigen::Vector3d& p : patch.points)
      target.points.push_back(truth * p);
    Super4PCSParams params = testParams(700 + side);
    params.max_bases = 50;
    const RegistrationResult result = Super4PCS(params).align(patch, target);
    SCOPED_TRACE("side " + std::to_string(side));
    EXPECT_TRUE(result.source_to_target.matrix().allFinite());
    EXPECT_GE(result.lcp_score, 0.0);
    EXPECT_LE(result.lcp_score, 1.0);
  }
}

TEST(Super4PCS, SameSeedGivesIdenticalResult)
{
  const BrickType brick = redBrick();
  const PointSet model = buildBrickModelCloud(brick);
  std::mt19937_64 rng(16);
  const Eigen::Isometry3d truth = randomPose(rng, 0.5, 2.0);
  const PointSet target = transformWithNoise(sampleBrickSurface(brick, {}, 0.005, rng), truth, 0.0015, rng);
  const RegistrationResult first = Super4PCS(testParams(42)).align(model, target);
  const RegistrationResult second = Super4PCS(testParams(42)).align(model, target);
  EXPECT_TRUE(first.source_to_target.matrix() == second.source_to_target.matrix());
  EXPECT_EQ(first.lcp_score, second.lcp_score);
  EXPECT_EQ(first.bases_tried, second.bases_tried);
  EXPECT_EQ(first.candidates_verified, second.candidates_verified);
  EXPECT_EQ(first.reason, second.reason);
}

TEST(Super4PCS, StopsAtTheTimeBudget)
{
  const BrickType brick = redBrick();
  const PointSet model = buildBrickModelCloud(brick);
  Super4PCSParams params = testParams(1);
  params.max_time_s = 1e-9;
  const RegistrationResult result = Super4PCS(params).align(model, model);
  EXPECT_FALSE(result.success);
  EXPECT_NE(result.reason.find("time budget"), std::string::npos) << result.reason;
  EXPECT_EQ(result.bases_tried, 0);
}

TEST(Super4PCS, ReportsFailureWhenNothingMatches)
{
  // A target far smaller than the model's bases holds no congruent set.
  const BrickType brick = redBrick();
  const PointSet model = buildBrickModelCloud(brick);
  PointSet tiny;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      tiny.points.emplace_back(0.002 * i, 0.002 * j, 0.0);
  Super4PCSParams params = testParams(3);
  params.max_bases = 20;
  const RegistrationResult result = Super4PCS(params).align(model, tiny);
  EXPECT_FALSE(result.success);
  EXPECT_FALSE(result.reason.empty());
}

void expectInputError(const PointSet& source, const PointSet& target, const std::string& expected_words)
{
  try
  {
    Super4PCS().align(source, target);
    FAIL() << "accepted input that should be rejected (" << expected_words << ")";
  }
  catch (const InputError& e)
  {
    EXPECT_NE(std::string(e.what()).find(expected_words), std::string::npos) << e.what();
  }
}

TEST(Super4PCS, RejectsDegenerateInputWithAClearMessage)
{
  const PointSet good = buildBrickModelCloud(redBrick());
  PointSet empty;
  expectInputError(empty, good, "source cloud is empty");
  expectInputError(good, empty, "target cloud is empty");

  PointSet three;
  three.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  expectInputError(three, good, "at least 4");

  PointSet collinear;
  for (int i = 0; i < 50; ++i)
    collinear.points.emplace_back(0.01 * i, 0.02 * i, -0.005 * i);
  expectInputError(good, collinear, "collinear");

  PointSet identical;
  identical.points.assign(20, Eigen::Vector3d(0.3, 0.1, 1.2));
  expectInputError(identical, good, "identical");

  PointSet with_nan = good;
  with_nan.points[7].y() = std::numeric_limits<double>::quiet_NaN();
  expectInputError(with_nan, good, "NaN/Inf coordinate at point 7");

  PointSet with_inf = good;
  with_inf.points[3].z() = std::numeric_limits<double>::infinity();
  expectInputError(good, with_inf, "NaN/Inf coordinate at point 3");

  PointSet far_away = good;
  far_away.points[5].x() = 3.0e9;  // millimetres read as metres, say
  expectInputError(good, far_away, "beyond 1e6 m at point 5");

  PointSet bad_normals = good;
  bad_normals.normals.pop_back();
  expectInputError(bad_normals, good, "normals for");

  PointSet nan_normal = good;
  nan_normal.normals[2].x() = std::numeric_limits<double>::quiet_NaN();
  expectInputError(good, nan_normal, "NaN/Inf normal at point 2");
}

TEST(Super4PCS, RejectsBadParametersWithConfigError)
{
  Super4PCSParams params;
  params.overlap = 0.0;
  EXPECT_THROW(Super4PCS{params}, ConfigError);
  params = Super4PCSParams();
  params.delta_m = -0.001;
  EXPECT_THROW(Super4PCS{params}, ConfigError);
  params = Super4PCSParams();
  params.sample_size = 3;
  EXPECT_THROW(Super4PCS{params}, ConfigError);
  params = Super4PCSParams();
  params.max_time_s = 0.0;
  EXPECT_THROW(Super4PCS{params}, ConfigError);
  params = Super4PCSParams();
  params.max_normal_difference_deg = 200.0;
  try
  {
    Super4PCS{params};
    FAIL() << "accepted max_normal_difference_deg = 200";
  }
  catch (const ConfigError& e)
  {
    EXPECT_NE(std::string(e.what()).find("max_normal_difference_deg"), std::string::npos) << e.what();
  }
}

TEST(Super4PCS, PclOverloadsMatchThePointSetApi)
{
  const BrickType brick = redBrick();
  const PointSet model = buildBrickModelCloud(brick);
  std::mt19937_64 rng(17);
  const Eigen::Isometry3d truth = randomPose(rng, 0.5, 2.0);
  const PointSet target = transformWithNoise(sampleBrickSurface(brick, {}, 0.005, rng), truth, 0.0015, rng);
  const Super4PCSParams params = testParams(5);
  const RegistrationResult direct = Super4PCS(params).align(model, target);
  // PCL clouds hold floats: the result is close to, not bit-identical with,
  // the double-precision call.
  const RegistrationResult via_pcl = alignSuper4PCS(toPclPointNormal(model), toPclPointNormal(target), params);
  ASSERT_TRUE(via_pcl.success) << via_pcl.reason;
  const PoseError error = poseErrorModuloSymmetry(via_pcl.source_to_target, truth, ModelSymmetry::kHalfTurnZ);
  EXPECT_LT(error.rotation_deg, 2.0);
  EXPECT_LT(error.translation_m, 0.006);
  EXPECT_TRUE(direct.success);
}
}  // namespace registration
}  // namespace brick_pose
