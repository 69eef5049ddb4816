#include <gtest/gtest.h>

#include <map>

#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pose/brick_pose_estimator.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/registration/brick_symmetry.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace
{
struct RenderedCase
{
  sim::SyntheticFrame synthetic;
  RgbdFrame frame;
};

RenderedCase render(const sim::Scene& scene, std::uint64_t seed)
{
  const sim::SyntheticRig rig(PinholeCamera::d415Color1280x720(), sim::SensorModel());
  RenderedCase rendered{rig.render(scene, seed), {}};
  rendered.frame = makeRgbdFrame(rendered.synthetic.rgb, rendered.synthetic.depth_mm, rendered.synthetic.camera,
                                 FrameHeader{0, "camera_color_optical_frame"});
  return rendered;
}

/// The truth instance under the candidate's centre pixel.
const sim::BrickTruth* truthOf(const RenderedCase& rendered, const BrickCandidate& candidate)
{
  const int u = static_cast<int>(std::lround(candidate.centroid_px.x()));
  const int v = static_cast<int>(std::lround(candidate.centroid_px.y()));
  const int label = rendered.synthetic.instance_labels.at<unsigned short>(v, u);
  return label > 0 ? &rendered.synthetic.truth[label - 1] : nullptr;
}

/// The pipeline's defaults without the wall-clock budget: max_bases bounds
/// Super4PCS, so a slow machine (a sanitizer build in CI) gets the same
/// result as a fast one.
BrickPoseEstimatorParams untimedParams()
{
  BrickPoseEstimatorParams params;
  params.super4pcs.max_time_s = 600.0;
  params.partial_face_max_time_s = 600.0;
  return params;
}

sim::Scene singleBrickScene(const std::string& type, std::uint64_t seed)
{
  sim::SceneParams params;
  params.types = {type};
  params.min_distance_m = 0.7;
  params.max_distance_m = 1.2;
  return sim::SceneGenerator(BrickCatalogue::mbzirc2020(), params).generate(seed);
}
}  // namespace

TEST(BrickPoseEstimator, SingleBricksWithinOneDegreeAndThreeMillimetres)
{
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  const FrontEnd front_end(catalogue);
  const BrickPoseEstimator estimator(catalogue, untimedParams());
  int checked = 0;
  for (const std::string type : {"red", "green"})
    for (std::uint64_t seed = 1; seed <= 3; ++seed)
    {
      const RenderedCase rendered = render(singleBrickScene(type, seed), seed);
      const FrontEndResult result = front_end.process(rendered.frame);
      ASSERT_EQ(result.candidates.size(), 1u) << type << " seed " << seed;
      const BrickPoseEstimate estimate = estimator.estimate(result.candidates[0]);
      const sim::BrickTruth* truth = truthOf(rendered, result.candidates[0]);
      ASSERT_NE(truth, nullptr);
      const auto error = registration::poseErrorModuloSymmetry(estimate.pose, truth->camera_T_brick);
      EXPECT_LT(error.rotation_deg, 1.0) << type << " seed " << seed;
      EXPECT_LT(error.translation_mm(), 3.0) << type << " seed " << seed;
      EXPECT_EQ(estimate.refinement, RefinementMethod::kCorrection);
      EXPECT_GT(estimate.registration.result.lcp_score, 0.5);
      ++checked;
    }
  EXPECT_EQ(checked, 6);
}

TEST(BrickPoseEstimator, ABoxOnItsSideIsPlacedAtItsFaceUpWithTheDepthBelowIt)
{
  // A plain box lying on a long side, seen obliquely: the pose is the face
  // up's (its centre, z out of it), the dimensions that face's and the
  // box's width below it, and the type stays the catalogue's.
  const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(R"(bricks:
  - {name: box_small, length_m: 0.30, width_m: 0.20, height_m: 0.15}
)");
  const BrickType& type = catalogue.types().front();
  sim::Scene scene;
  sim::PlacedBrick box{type, Eigen::Isometry3d::Identity()};
  box.world_T_brick.linear() = (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) *
                                Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitX()))
                                   .toRotationMatrix();
  box.world_T_brick.translation() = Eigen::Vector3d(0.0, 0.0, type.width_m);
  scene.bricks.push_back(box);
  scene.world_T_camera = sim::lookAt(Eigen::Vector3d(0.0, 0.0, 0.1), 1.1, 60.0, 20.0);
  const RenderedCase rendered = render(scene, 3);
  ASSERT_TRUE(rendered.synthetic.truth[0].resting_face.has_value());
  FrontEndParams params;
  params.mode = SegmentationMode::kColourFree;
  const FrontEndResult result = FrontEnd(catalogue, params).process(rendered.frame);
  ASSERT_EQ(result.candidates.size(), 1u);
  EXPECT_EQ(result.candidates[0].type_name, "box_small lying on a side");
  const BrickPoseEstimate estimate = BrickPoseEstimator(catalogue, untimedParams()).estimate(result.candidates[0]);
  EXPECT_EQ(estimate.catalogue_type, "box_small");
  EXPECT_EQ(estimate.resting, Resting::kOnSide);
  EXPECT_NEAR(estimate.dimensions_m.x(), 0.30, 1e-9);
  EXPECT_NEAR(estimate.dimensions_m.y(), 0.15, 1e-9);
  EXPECT_NEAR(estimate.dimensions_m.z(), 0.20, 1e-9);
  const auto error =
      registration::poseErrorModuloSymmetry(estimate.pose, rendered.synthetic.truth[0].resting_face->camera_T_face);
  EXPECT_LT(error.rotation_deg, 1.0);
  EXPECT_LT(error.translation_mm(), 3.0);
}

TEST(BrickPoseEstimator, OccludedFaceStillRegisters)
{
  // A red brick across the middle of a blue one hides part of the blue plate.
  sim::Scene scene;
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  sim::PlacedBrick blue{catalogue.at("blue"), Eigen::Isometry3d::Identity()};
  blue.world_T_brick.translation() = Eigen::Vector3d(0.0, 0.0, 0.2);
  sim::PlacedBrick red{catalogue.at("red"), Eigen::Isometry3d::Identity()};
  red.world_T_brick.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  red.world_T_brick.translation() = Eigen::Vector3d(0.35, 0.0, 0.4);
  scene.bricks = {blue, red};
  scene.world_T_camera = sim::lookAt(Eigen::Vector3d(0.0, 0.0, 0.2), 1.3, 75.0, 20.0);
  const RenderedCase rendered = render(scene, 3);
  ASSERT_LT(rendered.synthetic.truth[0].visible_fraction, 0.95);
  const FrontEndResult result = FrontEnd(catalogue).process(rendered.frame);
  const BrickPoseEstimator estimator(catalogue, untimedParams());
  bool registered_blue = false;
  for (const BrickCandidate& candidate : result.candidates)
    if (candidate.type_name == "blue")
      registered_blue = estimator.registerCandidate(candidate).result.success;
  EXPECT_TRUE(registered_blue);
}

TEST(BrickPoseEstimator, RefinementMethodsShareOneRegistration)
{
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  const RenderedCase rendered = render(singleBrickScene("green", 7), 7);
  const FrontEndResult result = FrontEnd(catalogue).process(rendered.frame);
  ASSERT_EQ(result.candidates.size(), 1u);
  BrickPoseEstimatorParams params = untimedParams();
  params.refinement = RefinementMethod::kNone;
  const BrickPoseEstimator none(catalogue, params);
  const BrickRegistration registration = none.registerCandidate(result.candidates[0]);
  EXPECT_TRUE(none.refine(result.candidates[0], registration).pose.isApprox(registration.pose));
  params.refinement = RefinementMethod::kIcp;
  const BrickPoseEstimate icp = BrickPoseEstimator(catalogue, params).refine(result.candidates[0], registration);
  EXPECT_EQ(icp.refinement, RefinementMethod::kIcp);
  EXPECT_TRUE(icp.pose.linear().isUnitary(1e-9));
}

TEST(BrickPoseEstimator, UnknownTypeAndEmptySegmentAreInputErrors)
{
  const BrickPoseEstimator estimator(BrickCatalogue::mbzirc2020(), BrickPoseEstimatorParams());
  BrickCandidate candidate;
  candidate.type_name = "purple";
  EXPECT_THROW(estimator.registerCandidate(candidate), InputError);
  candidate.type_name = "red";
  candidate.points.reset(new pcl::PointCloud<pcl::PointXYZ>);
  EXPECT_THROW(estimator.registerCandidate(candidate), InputError);
}

TEST(BrickPoseEstimator, BadBudgetsAndStopRatiosNameTheParameter)
{
  const auto error_of = [](const BrickPoseEstimatorParams& params) {
    try
    {
      BrickPoseEstimator(BrickCatalogue::mbzirc2020(), params);
    }
    catch (const ConfigError& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  BrickPoseEstimatorParams params;
  params.partial_face_max_time_s = 0.0;
  EXPECT_NE(error_of(params).find("partial_face_max_time_s"), std::string::npos);
  params = BrickPoseEstimatorParams();
  params.correction_good_enough_ratio = 1.5;
  EXPECT_NE(error_of(params).find("correction_good_enough_ratio"), std::string::npos);
}

TEST(PipelineConfig, ParametersAreReadAndErrorsNameThem)
{
  const std::map<std::string, std::string> values = {
      {"mode", "region_growing"}, {"voxel_leaf_m", "0"}, {"refinement", "icp"}, {"correction_mode", "paper"},
      {"max_time_s", "0.05"}, {"partial_face_max_time_s", "0.02"}, {"correction_good_enough_ratio", "0.7"}};
  const ParamLookup lookup = [&values](const std::string& name) -> std::optional<std::string> {
    const auto found = values.find(name);
    return found == values.end() ? std::nullopt : std::optional<std::string>(found->second);
  };
  const FrontEndParams front_end = frontEndParamsFrom(lookup);
  EXPECT_EQ(front_end.mode, SegmentationMode::kRegionGrowing);
  EXPECT_FALSE(front_end.cloud.voxel_enabled);
  const BrickPoseEstimatorParams estimator = estimatorParamsFrom(lookup);
  EXPECT_EQ(estimator.refinement, RefinementMethod::kIcp);
  EXPECT_EQ(estimator.correction.mode, CorrectionMode::kPaper);
  EXPECT_DOUBLE_EQ(estimator.super4pcs.max_time_s, 0.05);
  EXPECT_DOUBLE_EQ(estimator.partial_face_max_time_s, 0.02);
  EXPECT_DOUBLE_EQ(estimator.correction_good_enough_ratio, 0.7);

  const auto error_of = [](const std::string& name, const std::string& value) {
    try
    {
      const ParamLookup bad = [&](const std::string& asked) -> std::optional<std::string> {
        return asked == name ? std::optional<std::string>(value) : std::nullopt;
      };
      frontEndParamsFrom(bad);
      estimatorParamsFrom(bad);
    }
    catch (const ConfigError& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of("mode", "magic").find("magic"), std::string::npos);
  EXPECT_NE(error_of("refinement", "gradient").find("gradient"), std::string::npos);
  EXPECT_NE(error_of("voxel_leaf_m", "fine").find("voxel_leaf_m"), std::string::npos);
  EXPECT_NE(error_of("seed", "-1").find("seed"), std::string::npos);
}
}  // namespace brick_pose
