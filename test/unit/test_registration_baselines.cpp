#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/registration/brick_symmetry.h"
#include "brick_pose/registration/model_cloud.h"
#include "brick_pose/baselines/pcl_baselines.h"

namespace brick_pose
{
namespace registration
{
namespace
{
PointSet threeFaceView()
{
  ModelCloudParams options;
  options.spacing_m = 0.015;
  options.sides = {BrickSide::kPlusX, BrickSide::kPlusY};
  return buildBrickModelCloud(BrickCatalogue::mbzirc2020().at("red"), options);
}

PointSet transformed(const PointSet& cloud, const Eigen::Isometry3d& pose, double sigma_m, std::uint64_t seed)
{
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma_m);
  PointSet out;
  for (const Eigen::Vector3d& p : cloud.points)
    out.points.push_back(pose * p + Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
  return out;
}
}  // namespace

TEST(PclBaselines, IcpFromIdentityRefinesASmallOffset)
{
  const PointSet source = threeFaceView();
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.linear() = Eigen::AngleAxisd(0.06, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  truth.translation() = Eigen::Vector3d(0.01, -0.008, 0.005);
  const PointSet target = transformed(source, truth, 0.0005, 3);
  const RegistrationResult result = alignPclIcp(source, target, IcpParams());
  ASSERT_TRUE(result.success) << result.reason;
  const PoseError error = poseErrorModuloSymmetry(result.source_to_target, truth, ModelSymmetry::kNone);
  EXPECT_LT(error.rotation_deg, 0.5);
  EXPECT_LT(error.translation_m, 0.002);
  EXPECT_GT(result.lcp_score, 0.9);
  EXPECT_GT(result.elapsed_s, 0.0);
}

// PCL's 4PCS seeds std::rand from the clock, so only the contract is tested
// here (its accuracy is measured by bench_registration, not asserted).
TEST(PclBaselines, FpcsAndKfpcsFillTheSharedResult)
{
  const PointSet source = threeFaceView();
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.translation() = Eigen::Vector3d(0.0, 0.0, 1.0);
  const PointSet target = transformed(source, truth, 0.001, 4);
  PclFpcsParams params;
  params.sample_size = 100;
  for (const auto& align : {alignPclFpcs, alignPclKfpcs})
  {
    const RegistrationResult result = align(source, target, params);
    EXPECT_GE(result.lcp_score, 0.0);
    EXPECT_LE(result.lcp_score, 1.0);
    EXPECT_GT(result.elapsed_s, 0.0);
    EXPECT_FALSE(result.reason.empty());
    EXPECT_TRUE(result.source_to_target.matrix().allFinite());
  }
}

TEST(PclBaselines, RejectBadInputAndParameters)
{
  const PointSet good = threeFaceView();
  PointSet empty;
  EXPECT_THROW(alignPclFpcs(empty, good, PclFpcsParams()), InputError);
  EXPECT_THROW(alignPclKfpcs(good, empty, PclFpcsParams()), InputError);
  EXPECT_THROW(alignPclIcp(good, empty, IcpParams()), InputError);
  PclFpcsParams fpcs;
  fpcs.max_time_s = 0;
  EXPECT_THROW(alignPclFpcs(good, good, fpcs), ConfigError);
  fpcs = PclFpcsParams();
  fpcs.max_iterations = -1;
  EXPECT_THROW(alignPclFpcs(good, good, fpcs), ConfigError);
  fpcs = PclFpcsParams();
  fpcs.score_threshold = std::nan("");
  EXPECT_THROW(alignPclKfpcs(good, good, fpcs), ConfigError);
  IcpParams icp;
  icp.max_iterations = 0;
  EXPECT_THROW(alignPclIcp(good, good, icp), ConfigError);
}
}  // namespace registration
}  // namespace brick_pose
