#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "brick_pose/common/errors.h"
#include <map>

#include "brick_pose/sim/rig_config.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace sim
{
namespace
{
/// A brick lying flat on the ground, seen from `distance_m` at 70 degrees
/// elevation; its top-face centre is the look-at target.
Scene flatBrickScene(const std::string& type, double distance_m, double yaw_deg)
{
  Scene scene;
  PlacedBrick brick{BrickCatalogue::mbzirc2020().at(type), Eigen::Isometry3d::Identity()};
  brick.world_T_brick.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  brick.world_T_brick.translation() = Eigen::Vector3d(0.0, 0.0, brick.type.height_m);
  scene.bricks.push_back(brick);
  scene.world_T_camera = lookAt(brick.world_T_brick.translation(), distance_m, 70.0, 30.0);
  return scene;
}

SyntheticRig defaultRig(SensorModel sensor = SensorModel())
{
  return SyntheticRig(PinholeCamera::d415Color1280x720(), sensor);
}

double medianDepthMm(const cv::Mat& depth_mm, int u, int v, int radius)
{
  std::vector<double> values;
  for (int dv = -radius; dv <= radius; ++dv)
    for (int du = -radius; du <= radius; ++du)
    {
      const unsigned short d = depth_mm.at<unsigned short>(v + dv, u + du);
      if (d > 0) values.push_back(d);
    }
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}
}  // namespace

TEST(SyntheticRig, FaceCentreHasTheTrueDepthWithinNoise)
{
  const SyntheticRig rig = defaultRig();
  const SyntheticFrame frame = rig.render(flatBrickScene("green", 1.0, 20.0), 7);
  ASSERT_EQ(frame.truth.size(), 1u);
  const Eigen::Vector3d centre = frame.truth[0].camera_T_brick.translation();
  EXPECT_NEAR(centre.norm(), 1.0, 1e-9);
  const Eigen::Vector2d pixel = frame.camera.project(centre);
  const int u = static_cast<int>(std::lround(pixel.x())), v = static_cast<int>(std::lround(pixel.y()));
  EXPECT_EQ(frame.instance_labels.at<unsigned short>(v, u), 1);
  EXPECT_EQ(frame.face_labels.at<unsigned char>(v, u), static_cast<unsigned char>(CuboidFace::kTop));
  // The face is tilted, so the true depth varies across the window: compare
  // against the noise-free render at the same pixels.
  const double clean_mm = 1000.0 * frame.depth_clean_m.at<float>(v, u);
  EXPECT_NEAR(clean_mm, 1000.0 * centre.z(), 1.0);
  EXPECT_NEAR(medianDepthMm(frame.depth_mm, u, v, 1), clean_mm, 3.0 * rig.sensor().axialSigma(1.0, 920.0) * 1000.0);
}

TEST(SyntheticRig, DepthNoiseMatchesTheD415Model)
{
  SensorModel sensor;
  sensor.flying_pixel_probability = 0.0;
  const SyntheticRig rig = defaultRig(sensor);
  const SyntheticFrame frame = rig.render(flatBrickScene("blue", 1.0, 0.0), 3);
  double sum_sq = 0.0;
  int count = 0;
  for (int v = 0; v < frame.depth_mm.rows; ++v)
    for (int u = 0; u < frame.depth_mm.cols; ++u)
    {
      const unsigned short measured = frame.depth_mm.at<unsigned short>(v, u);
      const float clean = frame.depth_clean_m.at<float>(v, u);
      if (measured == 0 || frame.instance_labels.at<unsigned short>(v, u) != 1 ||
          frame.face_labels.at<unsigned char>(v, u) != static_cast<unsigned char>(CuboidFace::kTop))
        continue;
      // Normalise each residual by the model's sigma at its own depth.
      const double sigma_mm = 1000.0 * sensor.axialSigma(clean, 920.0);
      const double residual = (measured - 1000.0 * clean) / sigma_mm;
      sum_sq += residual * residual;
      ++count;
    }
  ASSERT_GT(count, 10000);
  // Quantisation to whole millimetres adds 1/12 mm^2 of variance on ~1.6 mm.
  const double normalised_sigma = std::sqrt(sum_sq / count);
  EXPECT_GT(normalised_sigma, 0.85);
  EXPECT_LT(normalised_sigma, 1.25);
  EXPECT_NEAR(sensor.axialSigma(1.0, 920.0), 0.00158, 0.0001);
}

TEST(SyntheticRig, TopFaceCornersBackProjectOntoTheTrueCorners)
{
  SensorModel sensor;
  const SyntheticRig rig = defaultRig(sensor);
  const SyntheticFrame frame = rig.render(flatBrickScene("red", 0.8, 37.0), 11);
  const auto corners = topFaceCornersInCamera(frame.truth[0]);
  const unsigned char top = static_cast<unsigned char>(CuboidFace::kTop);
  for (const Eigen::Vector3d& corner : corners)
  {
    const Eigen::Vector2d projected = frame.camera.project(corner);
    // The rendered top-face pixel nearest to the true corner.
    double best_distance_px = 1e9;
    Eigen::Vector2i best(-1, -1);
    for (int v = static_cast<int>(projected.y()) - 4; v <= static_cast<int>(projected.y()) + 4; ++v)
      for (int u = static_cast<int>(projected.x()) - 4; u <= static_cast<int>(projected.x()) + 4; ++u)
        if (frame.face_labels.at<unsigned char>(v, u) == top && frame.instance_labels.at<unsigned short>(v, u) == 1)
        {
          // Chebyshev distance: "within one pixel" in either direction.
          const double distance = (Eigen::Vector2d(u, v) - projected).cwiseAbs().maxCoeff();
          if (distance < best_distance_px)
          {
            best_distance_px = distance;
            best = Eigen::Vector2i(u, v);
          }
        }
    EXPECT_LE(best_distance_px, 1.0) << "corner pixel " << projected.transpose();
    const Eigen::Vector3d back =
        frame.camera.backProject(best.x(), best.y(), frame.depth_clean_m.at<float>(best.y(), best.x()));
    const double pixel_size_m = corner.z() / frame.camera.fx_px;
    // At most one pixel off in u and in v: sqrt(2) pixel sizes in 3D.
    EXPECT_LE((back - corner).norm(), std::sqrt(2.0) * pixel_size_m) << "3D corner " << corner.transpose();
  }
  EXPECT_NEAR(frame.truth[0].visible_fraction, 1.0, 0.02);
}

TEST(SyntheticRig, TheGroundFrameIsWhereTheScenesBricksStand)
{
  // Every brick of a pile rests on the ground or on another: seen from the
  // ground frame the frame gives, its top is its height, or more, above
  // z = 0, and its bottom at 0 or on something; the lowest bottom is 0.
  SceneParams params;
  params.kind = SceneKind::kOrganisedPile;
  const Scene scene = SceneGenerator(BrickCatalogue::mbzirc2020(), params).generate(7);
  SensorModel sensor;
  const SyntheticFrame frame = defaultRig(sensor).render(scene, 7);
  ASSERT_EQ(frame.truth.size(), scene.bricks.size());
  const Eigen::Isometry3d ground_T_camera = frame.camera_T_ground.inverse();
  double lowest_bottom_m = 1e9;
  for (const BrickTruth& truth : frame.truth)
  {
    const Eigen::Isometry3d ground_T_brick = ground_T_camera * truth.camera_T_brick;
    // Flat in a pile: the brick's z is the ground's.
    EXPECT_GT(ground_T_brick.linear().col(2).z(), std::cos(15.0 * M_PI / 180.0));
    const double bottom_m = ground_T_brick.translation().z() - truth.dimensions_m.z();
    EXPECT_GT(bottom_m, -1e-6);
    lowest_bottom_m = std::min(lowest_bottom_m, bottom_m);
  }
  EXPECT_NEAR(lowest_bottom_m, 0.0, 0.01);
}

TEST(SyntheticRig, SameSeedGivesIdenticalFrames)
{
  SceneParams params;
  params.kind = SceneKind::kUnorganisedPile;
  const SceneGenerator generator(BrickCatalogue::mbzirc2020(), params);
  const SyntheticRig rig = defaultRig();
  const SyntheticFrame a = rig.render(generator.generate(5), 99);
  const SyntheticFrame b = rig.render(generator.generate(5), 99);
  const SyntheticFrame c = rig.render(generator.generate(5), 100);
  EXPECT_EQ(cv::norm(a.rgb, b.rgb, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.depth_mm, b.depth_mm, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a.depth_mm, c.depth_mm, cv::NORM_L1), 0.0) << "another seed, other noise";
  ASSERT_EQ(a.truth.size(), b.truth.size());
  for (std::size_t i = 0; i < a.truth.size(); ++i)
    EXPECT_TRUE(a.truth[i].camera_T_brick.isApprox(b.truth[i].camera_T_brick, 0.0));
}

TEST(SyntheticRig, OcclusionLowersTheVisibleFraction)
{
  Scene scene = flatBrickScene("blue", 1.2, 0.0);
  // A red brick lying across the middle of the blue one.
  PlacedBrick cover{BrickCatalogue::mbzirc2020().at("red"), Eigen::Isometry3d::Identity()};
  cover.world_T_brick.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  cover.world_T_brick.translation() = Eigen::Vector3d(0.0, 0.0, 0.4);
  scene.bricks.push_back(cover);
  const SyntheticFrame frame = defaultRig().render(scene, 1);
  ASSERT_EQ(frame.truth.size(), 2u);
  EXPECT_LT(frame.truth[0].visible_fraction, 0.9);
  EXPECT_GT(frame.truth[0].visible_fraction, 0.5);
  EXPECT_NEAR(frame.truth[1].visible_fraction, 1.0, 0.02);
}

TEST(SyntheticRig, LightingModesChangeColourAndHoles)
{
  const Scene scene = flatBrickScene("orange", 1.5, 10.0);
  SensorModel sensor;
  const double normal_mean = cv::mean(defaultRig(sensor).render(scene, 4).rgb)[0];
  sensor.lighting = Lighting::kLowLight;
  const double low_mean = cv::mean(defaultRig(sensor).render(scene, 4).rgb)[0];
  EXPECT_LT(low_mean, 0.5 * normal_mean);

  sensor.lighting = Lighting::kNormal;
  const int normal_holes = cv::countNonZero(defaultRig(sensor).render(scene, 4).depth_mm == 0);
  sensor.lighting = Lighting::kSunlight;
  const int sunlight_holes = cv::countNonZero(defaultRig(sensor).render(scene, 4).depth_mm == 0);
  EXPECT_GT(sunlight_holes, normal_holes);
}

TEST(SyntheticRig, StereoShadowLeavesHolesBesideBricks)
{
  SensorModel sensor;
  sensor.dropout_probability = 0.0;
  const Scene scene = flatBrickScene("green", 0.7, 90.0);
  const int with_shadow = cv::countNonZero(defaultRig(sensor).render(scene, 2).depth_mm == 0);
  sensor.stereo_shadow = false;
  const int without_shadow = cv::countNonZero(defaultRig(sensor).render(scene, 2).depth_mm == 0);
  EXPECT_GT(with_shadow, without_shadow + 100);
}

TEST(SceneGenerator, PilesRestOnTheGroundAndOnEachOther)
{
  for (SceneKind kind : {SceneKind::kSingle, SceneKind::kOrganisedPile, SceneKind::kUnorganisedPile})
  {
    SceneParams params;
    params.kind = kind;
    params.min_distance_m = 0.4;
    params.max_distance_m = 2.5;
    const SceneGenerator generator(BrickCatalogue::mbzirc2020(), params);
    for (std::uint64_t seed = 0; seed < 20; ++seed)
    {
      const Scene scene = generator.generate(seed);
      ASSERT_FALSE(scene.bricks.empty());
      double lowest = 1e9;
      for (const PlacedBrick& brick : scene.bricks)
        for (const Eigen::Vector3d& corner : cuboidCornersInBrick(brick.type))
          lowest = std::min(lowest, (brick.world_T_brick * corner).z());
      EXPECT_NEAR(lowest, 0.0, 1e-9) << toString(kind) << " seed " << seed;
      const double camera_height = scene.world_T_camera.translation().z();
      EXPECT_GT(camera_height, 0.2) << "camera above the pile";
    }
  }
}

TEST(SceneGenerator, OrganisedPileStacksLayers)
{
  SceneParams params;
  params.kind = SceneKind::kOrganisedPile;
  params.max_layers = 3;
  const SceneGenerator generator(BrickCatalogue::mbzirc2020(), params);
  bool saw_stack = false;
  for (std::uint64_t seed = 0; seed < 20 && !saw_stack; ++seed)
    for (const PlacedBrick& brick : generator.generate(seed).bricks)
      saw_stack |= brick.world_T_brick.translation().z() > 1.5 * brick.type.height_m;
  EXPECT_TRUE(saw_stack);
}

TEST(SyntheticRig, BadParametersNameTheField)
{
  PinholeCamera camera = PinholeCamera::d415Color1280x720();
  camera.fy_px = 0.0;
  try
  {
    SyntheticRig rig(camera, SensorModel());
    FAIL();
  }
  catch (const ConfigError& e)
  {
    EXPECT_NE(std::string(e.what()).find("fy"), std::string::npos) << e.what();
  }
  SensorModel sensor;
  sensor.dropout_probability = -0.1;
  EXPECT_THROW(SyntheticRig(PinholeCamera::d415Color1280x720(), sensor), ConfigError);
  SceneParams params;
  params.types = {"purple"};
  try
  {
    SceneGenerator generator(BrickCatalogue::mbzirc2020(), params);
    FAIL();
  }
  catch (const ConfigError& e)
  {
    EXPECT_NE(std::string(e.what()).find("purple"), std::string::npos) << e.what();
  }
  EXPECT_THROW(lightingFromString("dusk"), ConfigError);
  EXPECT_THROW(sceneKindFromString("heap"), ConfigError);
}
}  // namespace sim
}  // namespace brick_pose

namespace brick_pose
{
namespace sim
{
namespace
{
ParamLookup lookupFrom(const std::map<std::string, std::string>& values)
{
  return [values](const std::string& name) -> std::optional<std::string> {
    const auto found = values.find(name);
    if (found == values.end()) return std::nullopt;
    return found->second;
  };
}

std::string configErrorOf(const std::map<std::string, std::string>& values)
{
  try
  {
    rigConfigFrom(lookupFrom(values));
  }
  catch (const ConfigError& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(RigConfig, ReadsEveryKindOfParameter)
{
  const RigConfig config = rigConfigFrom(lookupFrom({{"scene", "organised_pile"},
                                                     {"types", "red, blue"},
                                                     {"seed", "42"},
                                                     {"lighting", "low_light"},
                                                     {"fx", "610.5"},
                                                     {"stereo_shadow", "false"},
                                                     {"catalogue_path", BRICK_POSE_SOURCE_DIR "/config/bricks.yaml"}}));
  EXPECT_EQ(config.scene.kind, SceneKind::kOrganisedPile);
  EXPECT_EQ(config.scene.types, (std::vector<std::string>{"red", "blue"}));
  EXPECT_EQ(config.seed, 42u);
  EXPECT_EQ(config.sensor.lighting, Lighting::kLowLight);
  EXPECT_DOUBLE_EQ(config.camera.fx_px, 610.5);
  EXPECT_FALSE(config.sensor.stereo_shadow);
}

TEST(RigConfig, ErrorsNameTheParameter)
{
  EXPECT_NE(configErrorOf({{"types", "purple"}}).find("'types'"), std::string::npos);
  EXPECT_NE(configErrorOf({{"types", "purple"}}).find("purple"), std::string::npos);
  EXPECT_NE(configErrorOf({{"fx", "0"}}).find("fx"), std::string::npos);
  EXPECT_NE(configErrorOf({{"fy", "abc"}}).find("'fy'"), std::string::npos);
  EXPECT_NE(configErrorOf({{"seed", "-3"}}).find("seed"), std::string::npos);
  EXPECT_NE(configErrorOf({{"lighting", "dusk"}}).find("dusk"), std::string::npos);
  EXPECT_NE(configErrorOf({{"stereo_shadow", "maybe"}}).find("stereo_shadow"), std::string::npos);
  EXPECT_NE(configErrorOf({{"catalogue_path", "/no/such.yaml"}}).find("/no/such.yaml"), std::string::npos);
  EXPECT_EQ(configErrorOf({}), "") << "defaults are valid";
  EXPECT_NE(configErrorOf({{"scene", "heap"}}).find("'scene'"), std::string::npos);
  EXPECT_NE(configErrorOf({{"scene", "pallet_layer"}, {"max_gap_m", "-1"}}).find("max_gap_m"), std::string::npos);
  EXPECT_NE(configErrorOf({{"max_table_boxes", "0"}}).find("max_table_boxes"), std::string::npos);
  EXPECT_NE(configErrorOf({{"zero_gap_probability", "2"}}).find("zero_gap_probability"), std::string::npos);
}

TEST(RigConfig, SceneKindBringsItsDefaultsAndParametersOverrideThem)
{
  const RigConfig pallet = rigConfigFrom(lookupFrom({{"scene", "pallet_layer"}}));
  EXPECT_EQ(pallet.scene.kind, SceneKind::kPalletLayer);
  EXPECT_DOUBLE_EQ(pallet.scene.min_distance_m, SceneParams::defaultsFor(SceneKind::kPalletLayer).min_distance_m);
  const RigConfig table = rigConfigFrom(
      lookupFrom({{"scene", "table_boxes"}, {"min_distance_m", "0.9"}, {"upright_probability", "1"}, {"max_gap_m", "0"}}));
  EXPECT_EQ(table.scene.kind, SceneKind::kTableBoxes);
  EXPECT_DOUBLE_EQ(table.scene.min_distance_m, 0.9);
  EXPECT_DOUBLE_EQ(table.scene.max_elevation_deg, 60.0) << "oblique by default";
  EXPECT_DOUBLE_EQ(table.scene.upright_probability, 1.0);
  EXPECT_DOUBLE_EQ(table.scene.max_gap_m, 0.0);
  const RigConfig oblique = rigConfigFrom(lookupFrom({{"scene", "organised_pile"}, {"view", "oblique"}}));
  EXPECT_DOUBLE_EQ(oblique.scene.min_elevation_deg, 20.0);
  EXPECT_DOUBLE_EQ(oblique.scene.max_elevation_deg, 60.0);
  const RigConfig steeper =
      rigConfigFrom(lookupFrom({{"view", "oblique"}, {"max_elevation_deg", "50"}}));
  EXPECT_DOUBLE_EQ(steeper.scene.max_elevation_deg, 50.0) << "elevation parameters override the view";
  EXPECT_NE(configErrorOf({{"view", "side"}}).find("'view'"), std::string::npos);
}
}  // namespace sim
}  // namespace brick_pose
