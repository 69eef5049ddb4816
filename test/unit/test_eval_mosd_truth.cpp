// Ground truth measured from mOSD labels: the table, the boxes' faces, the
// tops' sizes and whether they are whole in view. Checked on a real scene
// for plausibility and on rig frames dressed as mOSD scenes against the
// rig's exact truth.
#include <cmath>

#include <gtest/gtest.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/eval/mosd_scene.h"
#include "brick_pose/eval/mosd_truth.h"
#include "brick_pose/eval/rig_as_mosd.h"
#include "brick_pose/eval/rig_truth.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace
{
constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;
const std::string kDirectory = eval::mosdLearnDirectory(BRICK_POSE_SOURCE_DIR);

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return std::atan2(a.cross(b).norm(), a.dot(b)) * kDegPerRad;
}

const eval::MosdBox* boxOf(const eval::MosdTruth& truth, int object)
{
  for (const eval::MosdBox& box : truth.boxes)
    if (box.object == object) return &box;
  return nullptr;
}

class MosdLearn0 : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    scene_ = new eval::MosdScene(eval::loadMosdScene(kDirectory, "learn0"));
    truth_ = new eval::MosdTruth(eval::extractMosdTruth(*scene_));
  }
  static void TearDownTestSuite()
  {
    delete truth_;
    delete scene_;
  }
  static eval::MosdScene* scene_;
  static eval::MosdTruth* truth_;
};
eval::MosdScene* MosdLearn0::scene_ = nullptr;
eval::MosdTruth* MosdLearn0::truth_ = nullptr;

TEST_F(MosdLearn0, TableIsAPlaneBelowTheCameraWithUpFacingIt)
{
  ASSERT_TRUE(truth_->has_table);
  EXPECT_LT(truth_->table.rms_m, 0.01);
  EXPECT_NEAR(truth_->up.norm(), 1.0, 1e-9);
  // The camera looks down at the table: up faces the camera and points
  // toward the top of the image (-y in the optical frame).
  EXPECT_LT(truth_->up.dot(truth_->table.centroid_m), 0.0);
  EXPECT_LT(truth_->up.y(), -0.3);
  const double camera_height_m = truth_->table.signedDistance(Eigen::Vector3d::Zero());
  EXPECT_GT(camera_height_m, 0.3);  // the camera is above the table ...
  EXPECT_LT(camera_height_m, 2.0);  // ... by less than 2 m
}

TEST_F(MosdLearn0, FrontBoxIsACerealBoxStandingUprightWithAWholeTop)
{
  // learn0: a box standing upright in front of another, taller than it.
  ASSERT_EQ(truth_->boxes.size(), 2u);
  const eval::MosdBox* front = boxOf(*truth_, 2);
  ASSERT_NE(front, nullptr);
  ASSERT_TRUE(front->has_top);
  EXPECT_TRUE(front->top_whole) << front->not_whole_reason;
  // A cereal box standing upright: a narrow top, tall.
  EXPECT_GT(front->top.length_m, 0.12);
  EXPECT_LT(front->top.length_m, 0.18);
  EXPECT_GT(front->top.width_m, 0.04);
  EXPECT_LT(front->top.width_m, 0.08);
  EXPECT_GT(front->height_m, 0.20);
  EXPECT_LT(front->height_m, 0.30);
  // Its top is horizontal (within the tilt test), its sides vertical.
  EXPECT_LT(angleDeg(front->top.normal, truth_->up), 5.0);
  int sides = 0;
  for (const eval::MosdFace& face : front->faces)
    if (face.role == eval::FaceRole::kSide)
    {
      ++sides;
      EXPECT_NEAR(angleDeg(face.plane.normal, front->top.normal), 90.0, 5.0);
    }
  EXPECT_GE(sides, 1);
}

TEST_F(MosdLearn0, BackBoxTopIsHiddenByTheFrontBox)
{
  const eval::MosdBox* back = boxOf(*truth_, 3);
  ASSERT_NE(back, nullptr);
  ASSERT_TRUE(back->has_top);
  EXPECT_FALSE(back->top_whole);
  EXPECT_FALSE(back->top_uncertain);
  EXPECT_NE(back->not_whole_reason.find("hidden by object 2"), std::string::npos) << back->not_whole_reason;
}

TEST_F(MosdLearn0, SceneTruthMapsPixelsToFacesWithRoles)
{
  const eval::SceneTruth& scene = truth_->scene;
  ASSERT_EQ(scene.face_index.size(), scene_->labels.size());
  int tops = 0, whole_tops = 0, sides = 0, supports = 0;
  for (const eval::FaceTruth& face : scene.faces)
  {
    tops += face.role == eval::FaceRole::kTop ? 1 : 0;
    whole_tops += face.role == eval::FaceRole::kTop && face.whole_in_view ? 1 : 0;
    sides += face.role == eval::FaceRole::kSide ? 1 : 0;
    supports += face.role == eval::FaceRole::kSupport ? 1 : 0;
  }
  EXPECT_EQ(tops, 2);
  EXPECT_EQ(whole_tops, 1);
  EXPECT_GE(sides, 2);
  EXPECT_EQ(supports, 1);
  // Every face pixel is a labelled pixel with depth; table pixels are the support.
  const auto* labels = scene_->labels.ptr<std::uint16_t>(0);
  for (int pixel = 0; pixel < static_cast<int>(scene.face_index.total()); ++pixel)
  {
    const int face = scene.faceAt(pixel);
    if (face < 0) continue;
    const eval::FaceTruth& truth = scene.faces[static_cast<std::size_t>(face)];
    if (truth.role == eval::FaceRole::kSupport) ASSERT_TRUE(eval::isMosdTableLabel(labels[pixel]));
    else ASSERT_EQ(eval::mosdObjectOfLabel(labels[pixel]), truth.object_id);
  }
}

TEST(MosdTruth, LabelImageOfTheWrongSizeIsRejected)
{
  eval::MosdScene scene = eval::loadMosdScene(kDirectory, "learn0");
  scene.labels = cv::Mat(10, 10, CV_16UC1, cv::Scalar(1));
  EXPECT_THROW(eval::extractMosdTruth(scene), InputError);
}

TEST(MosdTruth, SceneWithoutTablePointsIsRejected)
{
  eval::MosdScene scene = eval::loadMosdScene(kDirectory, "learn0");
  scene.labels.setTo(20);
  EXPECT_THROW(eval::extractMosdTruth(scene), InputError);
}

TEST(MosdTruth, BadParametersAreRejected)
{
  eval::MosdTruthParams params;
  params.max_up_tilt_deg = 60.0;
  EXPECT_THROW(params.validate(), ConfigError);
  params = eval::MosdTruthParams();
  params.faces.min_face_points = 1;
  EXPECT_THROW(params.validate(), ConfigError);
}

/// A single box of mOSD size on the ground, seen obliquely by a 640x480
/// camera with the Kinect's intrinsics and D415 noise.
sim::SyntheticFrame renderedBox(const BrickCatalogue& catalogue, std::uint64_t seed, sim::Scene& scene)
{
  sim::SceneParams params;
  params.min_distance_m = 0.8;
  params.max_distance_m = 1.1;
  params.min_elevation_deg = 40.0;
  params.max_elevation_deg = 60.0;
  scene = sim::SceneGenerator(catalogue, params).generate(seed);
  PinholeCamera camera;
  camera.width_px = 640;
  camera.height_px = 480;
  camera.fx_px = camera.fy_px = 525.0;
  camera.cx_px = 319.5;
  camera.cy_px = 239.5;
  return sim::SyntheticRig(camera, sim::SensorModel()).render(scene, seed);
}

TEST(MosdTruth, MeasuresRigBoxesLikeTheRigsExactTruth)
{
  const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(R"(bricks:
  - {name: upright, length_m: 0.15, width_m: 0.06, height_m: 0.24, plate_rgb: [220, 180, 40], body_rgb: [200, 60, 50], hsv_min: [0, 0, 0], hsv_max: [180, 255, 255]}
  - {name: flat, length_m: 0.20, width_m: 0.13, height_m: 0.05, plate_rgb: [60, 120, 200], body_rgb: [230, 230, 230], hsv_min: [0, 0, 0], hsv_max: [180, 255, 255]}
)");
  int checked = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed)
  {
    sim::Scene scene;
    const sim::SyntheticFrame frame = renderedBox(catalogue, seed, scene);
    const sim::BrickTruth& brick = frame.truth.front();
    const Eigen::Vector3d up = scene.world_T_camera.linear().transpose() * Eigen::Vector3d::UnitZ();
    const eval::SceneTruth exact = eval::rigSceneTruth(frame, up);
    const eval::MosdTruth measured = eval::extractMosdTruth(eval::mosdSceneFromRig(frame, "rig"));
    ASSERT_EQ(measured.boxes.size(), 1u) << "seed " << seed;
    const eval::MosdBox& box = measured.boxes.front();
    ASSERT_TRUE(box.has_top) << "seed " << seed;
    EXPECT_LT(angleDeg(measured.up, up), 1.0) << "seed " << seed;
    EXPECT_EQ(box.top_whole, exact.faces.front().whole_in_view) << "seed " << seed << ": " << box.not_whole_reason;
    if (!box.top_whole) continue;
    ++checked;
    EXPECT_NEAR(box.top.length_m, brick.dimensions_m.x(), 0.008) << "seed " << seed;
    EXPECT_NEAR(box.top.width_m, brick.dimensions_m.y(), 0.008) << "seed " << seed;
    EXPECT_NEAR(box.height_m, brick.dimensions_m.z(), 0.008) << "seed " << seed;
    EXPECT_LT((box.top.centre_m - brick.camera_T_brick.translation()).norm(), 0.008) << "seed " << seed;
    EXPECT_LT(angleDeg(box.top.normal, brick.camera_T_brick.linear().col(2)), 2.0) << "seed " << seed;
    const double axis_deg = angleDeg(box.top.long_axis, brick.camera_T_brick.linear().col(0));
    EXPECT_LT(std::min(axis_deg, 180.0 - axis_deg), 3.0) << "seed " << seed;
  }
  EXPECT_GE(checked, 4);
}
}  // namespace
}  // namespace brick_pose
