// Issue 14: the front end reuses a keyframe's result only while the scene is
// unchanged. Fresh sensor noise on a static pile must not count as a change
// (or the reuse never happens); a brick moved by a millimetre or turned by
// half a degree, a new light, a moved camera must (or a stale pose is
// published).

#include <cstdio>

#include <gtest/gtest.h>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/frame/scene_change.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace
{
const BrickCatalogue& catalogue()
{
  static const BrickCatalogue bricks = BrickCatalogue::mbzirc2020();
  return bricks;
}

sim::Scene sceneOf(sim::SceneKind kind, std::uint64_t seed)
{
  return sim::SceneGenerator(catalogue(), sim::SceneParams::defaultsFor(kind)).generate(seed);
}

SceneSignature signatureOf(const sim::Scene& scene, const sim::SensorModel& sensor, std::uint64_t noise_seed)
{
  const sim::SyntheticRig rig(PinholeCamera::d415Color1280x720(), sensor);
  const sim::SyntheticFrame rendered = rig.render(scene, noise_seed);
  const RgbdFrame frame = makeRgbdFrame(rendered.rgb, rendered.depth_mm, rendered.camera, FrameHeader{0, "camera"});
  return SceneSignature::of(frame, SceneChangeParams());
}

/// A scene of `kind` with a whole top in view (the first such seed from 3),
/// and that brick: the one a robot picks, whose move must not go unseen.
std::pair<sim::Scene, std::size_t> sceneWithAWholeTop(sim::SceneKind kind, const sim::SensorModel& sensor)
{
  const sim::SyntheticRig rig(PinholeCamera::d415Color1280x720(), sensor);
  for (std::uint64_t seed = 3;; ++seed)
  {
    sim::Scene scene = sceneOf(kind, seed);
    for (const sim::BrickTruth& truth : rig.render(scene, 100).truth)
      if (truth.top_face_complete) return {scene, static_cast<std::size_t>(truth.instance_id - 1)};
  }
}
}  // namespace

sim::SensorModel lowLightD4xx()
{
  sim::SensorModel sensor = sim::SensorModel::d4xx();
  sensor.lighting = sim::Lighting::kLowLight;
  return sensor;
}

const sim::SceneKind kPileKinds[] = {sim::SceneKind::kUnorganisedPile, sim::SceneKind::kTouchingRows,
                                     sim::SceneKind::kPalletStack, sim::SceneKind::kTableBoxes};

TEST(SceneChange, FreshSensorNoiseOnAStaticSceneIsNoChange)
{
  const SceneChangeParams params;
  for (const sim::SensorModel& sensor : {sim::SensorModel(), sim::SensorModel::d4xx(), lowLightD4xx()})
    for (sim::SceneKind kind : kPileKinds)
      for (std::uint64_t scene_seed : {3u, 5u})
      {
        const sim::Scene scene = sceneOf(kind, scene_seed);
        const SceneSignature keyframe = signatureOf(scene, sensor, 100);
        const SceneChange change = compareScenes(keyframe, signatureOf(scene, sensor, 101), params);
        std::printf("static %s seed %d: %d blocks\n", sim::toString(kind).c_str(), static_cast<int>(scene_seed),
                    change.changed_blocks);
        EXPECT_FALSE(change.changed) << sim::toString(kind) << " " << scene_seed << ": " << change.reason;
        EXPECT_LE(change.changed_blocks, params.max_changed_blocks / 2)
            << sim::toString(kind) << " " << scene_seed << ": the margin to the limit is thin";
      }
}

TEST(SceneChange, AWholeTopShifted5mmOrTurned2DegIsAChange)
{
  const SceneChangeParams params;
  const struct
  {
    const char* what;
    Eigen::Vector3d shift_m;
    double yaw_deg;
  } moves[] = {{"shifted 5 mm sideways", {0.0, 0.005, 0.0}, 0.0},
               {"shifted 5 mm lengthwise", {0.005, 0.0, 0.0}, 0.0},
               {"turned 2 deg", {0.0, 0.0, 0.0}, 2.0},
               {"shifted 2 cm and turned 5 deg", {0.0, 0.02, 0.0}, 5.0}};
  for (const sim::SensorModel& sensor : {sim::SensorModel::d4xx(), lowLightD4xx()})
    for (sim::SceneKind kind : kPileKinds)
    {
      const auto [scene, picked] = sceneWithAWholeTop(kind, sensor);
      const SceneSignature keyframe = signatureOf(scene, sensor, 100);
      for (const auto& move : moves)
      {
        sim::Scene moved = scene;
        sim::PlacedBrick& brick = moved.bricks[picked];
        brick.world_T_brick.translate(move.shift_m);
        brick.world_T_brick.rotate(Eigen::AngleAxisd(move.yaw_deg * kDegToRad, Eigen::Vector3d::UnitZ()));
        const SceneChange change = compareScenes(keyframe, signatureOf(moved, sensor, 101), params);
        std::printf("%s, %s: %d blocks\n", sim::toString(kind).c_str(), move.what, change.changed_blocks);
        EXPECT_GT(change.changed_blocks, 2 * params.max_changed_blocks)
            << sim::toString(kind) << ", " << move.what << ": a change, but the margin is thin";
        EXPECT_TRUE(change.changed) << sim::toString(kind) << ", " << move.what << ": " << change.changed_blocks
                                    << " blocks";
      }
    }
}

TEST(SceneChange, ANewLightAMovedCameraAndANewUpAreChanges)
{
  const SceneChangeParams params;
  const sim::Scene scene = sceneOf(sim::SceneKind::kUnorganisedPile, 4);
  const SceneSignature keyframe = signatureOf(scene, sim::SensorModel(), 100);

  sim::SensorModel low_light;
  low_light.lighting = sim::Lighting::kLowLight;
  EXPECT_TRUE(compareScenes(keyframe, signatureOf(scene, low_light, 101), params).changed) << "new lighting";

  sim::Scene camera_moved = scene;
  camera_moved.world_T_camera.translate(Eigen::Vector3d(0.005, 0.0, 0.0));
  EXPECT_TRUE(compareScenes(keyframe, signatureOf(camera_moved, sim::SensorModel(), 101), params).changed)
      << "camera moved 5 mm";

  const sim::SyntheticRig rig(PinholeCamera::d415Color1280x720(), sim::SensorModel());
  const sim::SyntheticFrame rendered = rig.render(scene, 101);
  RgbdFrame frame = makeRgbdFrame(rendered.rgb, rendered.depth_mm, rendered.camera, FrameHeader{0, "camera"});
  frame.up_in_camera = Eigen::Vector3d(0.0, -1.0, 0.0);
  const SceneChange up_appeared = compareScenes(keyframe, SceneSignature::of(frame, params), params);
  EXPECT_TRUE(up_appeared.changed);
  EXPECT_EQ(up_appeared.reason, "up direction");

  EXPECT_EQ(compareScenes(SceneSignature(), keyframe, params).reason, "no keyframe");
  cv::Mat small_rgb(360, 640, CV_8UC3, cv::Scalar(0, 0, 0));
  cv::Mat small_depth(360, 640, CV_32FC1, cv::Scalar(1.0f));
  RgbdFrame small = frame;
  small.rgb = small_rgb;
  small.depth_m = small_depth;
  EXPECT_EQ(compareScenes(keyframe, SceneSignature::of(small, params), params).reason, "image size");
}

TEST(SceneChange, BadParametersAndBadFramesAreNamed)
{
  SceneChangeParams params;
  params.block_px = 1;
  EXPECT_THROW(params.validate(), ConfigError);
  params = SceneChangeParams();
  params.valid_fraction_change = 2.0;
  EXPECT_THROW(params.validate(), ConfigError);
  EXPECT_NO_THROW(SceneChangeParams().validate());

  RgbdFrame frame;
  frame.rgb = cv::Mat(4, 4, CV_8UC3, cv::Scalar(0, 0, 0));
  frame.depth_m = cv::Mat(4, 5, CV_32FC1, cv::Scalar(1.0f));
  EXPECT_THROW(SceneSignature::of(frame, SceneChangeParams()), InputError);
}
}  // namespace brick_pose
