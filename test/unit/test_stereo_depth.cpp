// The D4xx depth model: the stereo window closes seams and narrow gaps and
// fattens steps, disparity quantisation grows with z^2, aligned depth is
// misregistered against colour, rounded box edges leave a faint crease.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "brick_pose/common/errors.h"
#include "brick_pose/sim/d415_modes.h"
#include "brick_pose/sim/rig_config.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace sim
{
namespace
{
BrickType largeBox()
{
  BrickType box;
  box.name = "box_large";
  box.length_m = 0.40;
  box.width_m = 0.30;
  box.height_m = 0.25;
  box.plate_rgb = box.body_rgb = {{186, 146, 102}};
  return box;
}

/// Two large boxes on the floor side by side along y, `gap_m` apart, seen
/// from straight above at `distance_m` (image u runs along world y).
Scene twoBoxes(double gap_m, double distance_m, double edge_radius_m = 0.0)
{
  Scene scene;
  const BrickType box = largeBox();
  for (const double side : {-1.0, 1.0})
  {
    PlacedBrick placed{box, Eigen::Isometry3d::Identity()};
    placed.world_T_brick.translation() = Eigen::Vector3d(0.0, side * 0.5 * (box.width_m + gap_m), box.height_m);
    scene.bricks.push_back(placed);
  }
  scene.world_T_camera = lookAt(Eigen::Vector3d(0.0, 0.0, box.height_m), distance_m, 89.9, 0.0);
  scene.edge_radius_m = edge_radius_m;
  return scene;
}

/// A sensor without randomness in depth: no noise, holes or flying pixels.
SensorModel noiseless(SensorModel sensor)
{
  sensor.subpixel_px = 0.0;
  sensor.dropout_probability = 0.0;
  sensor.flying_pixel_probability = 0.0;
  return sensor;
}

SensorModel windowOnly()
{
  SensorModel sensor = noiseless(SensorModel::d4xx());
  sensor.disparity_step_px = 0.0;
  sensor.depth_offset_u_px = sensor.depth_offset_v_px = 0;
  return sensor;
}

const PinholeCamera kVga = d415ColourMode("640x480");

/// Pixels of the image row through the centre that lie between the boxes
/// and see deeper than their tops by `depth_m` or more in the ideal depth.
std::vector<int> gapPixels(const SyntheticFrame& frame, double depth_m)
{
  std::vector<int> columns;
  const int v = frame.camera.height_px / 2;
  const double top_m = frame.truth[0].camera_T_brick.translation().z();
  for (int u = frame.camera.width_px / 4; u < 3 * frame.camera.width_px / 4; ++u)
  {
    const float clean = frame.depth_clean_m.at<float>(v, u);
    if (!std::isnan(clean) && clean > top_m + depth_m) columns.push_back(u);
  }
  return columns;
}
}  // namespace

TEST(StereoDepth, SeamGapIsInIdealDepthButNotAfterTheStereoWindow)
{
  // 3 mm at 1.0 m is ~1.8 px at 640x480: the floor shows through in the
  // ideal depth.
  const Scene scene = twoBoxes(0.003, 1.0);
  const SyntheticFrame ideal = SyntheticRig(kVga, noiseless(SensorModel())).render(scene, 3);
  const SyntheticFrame d4xx = SyntheticRig(kVga, windowOnly()).render(scene, 3);
  const std::vector<int> gap = gapPixels(ideal, 0.05);
  ASSERT_FALSE(gap.empty()) << "the ideal depth sees into the gap";
  const int v = kVga.height_px / 2;
  const double top_mm = 1000.0 * ideal.truth[0].camera_T_brick.translation().z();
  int ideal_gap_or_hole = 0;
  for (const int u : gap)
  {
    const unsigned short ideal_mm = ideal.depth_mm.at<unsigned short>(v, u);
    ideal_gap_or_hole += (ideal_mm == 0 || ideal_mm > top_mm + 50.0) ? 1 : 0;
    const unsigned short measured_mm = d4xx.depth_mm.at<unsigned short>(v, u);
    EXPECT_NEAR(measured_mm, top_mm, 3.0) << "column " << u << ": the window closes the gap";
  }
  EXPECT_EQ(ideal_gap_or_hole, static_cast<int>(gap.size())) << "ideal: a hole or the floor in the gap";
}

TEST(StereoDepth, WideGapStaysOpen)
{
  // 4 cm (~25 px): much wider than the window and the fattening.
  const Scene scene = twoBoxes(0.04, 1.0);
  const SyntheticFrame d4xx = SyntheticRig(kVga, windowOnly()).render(scene, 3);
  const std::vector<int> gap = gapPixels(d4xx, 0.1);
  ASSERT_GT(gap.size(), 15u);
  const int v = kVga.height_px / 2;
  const double top_mm = 1000.0 * d4xx.truth[0].camera_T_brick.translation().z();
  int deep = 0;
  for (const int u : gap)
  {
    const unsigned short measured_mm = d4xx.depth_mm.at<unsigned short>(v, u);
    deep += measured_mm == 0 || measured_mm > top_mm + 100.0 ? 1 : 0;
  }
  EXPECT_GE(deep, static_cast<int>(gap.size()) - 2 * windowOnly().edge_fattening_px);
}

TEST(StereoDepth, StepsFattenTowardTheForegroundByTheFatteningWidth)
{
  Scene scene = twoBoxes(0.0, 1.2);
  scene.bricks.pop_back();  // one box, y in [-0.30, 0]: its +y edge is in the image centre
  SensorModel sensor = windowOnly();
  sensor.stereo_shadow = false;
  const SyntheticFrame ideal = SyntheticRig(kVga, noiseless(SensorModel())).render(scene, 5);
  const SyntheticFrame d4xx = SyntheticRig(kVga, sensor).render(scene, 5);
  const int v = kVga.height_px / 2;
  // The box's last column along the row, from the ideal labels.
  int edge_u = -1;
  for (int u = 0; u < kVga.width_px; ++u)
    if (ideal.instance_labels.at<unsigned short>(v, u) == 1) edge_u = u;
  ASSERT_GT(edge_u, 0);
  const double top_mm = 1000.0 * ideal.truth[0].camera_T_brick.translation().z();
  int fattened = 0;
  for (int u = edge_u + 1; u <= edge_u + 10; ++u)
  {
    EXPECT_GT(ideal.depth_mm.at<unsigned short>(v, u), top_mm + 200.0) << "ideal: floor right after the edge";
    fattened += std::abs(d4xx.depth_mm.at<unsigned short>(v, u) - top_mm) < 5.0 ? 1 : 0;
  }
  EXPECT_EQ(fattened, sensor.edge_fattening_px);
}

TEST(StereoDepth, DisparityQuantisationStepGrowsWithDepthSquared)
{
  SensorModel sensor;
  sensor.disparity_step_px = 1.0 / 32.0;
  const double fx_px = kVga.fx_px;
  // Mean spacing of the distinct depths the quantiser returns near z.
  auto levelSpacing = [&](double z_m) {
    std::set<double> levels;
    for (double z = z_m - 0.05; z <= z_m + 0.05; z += 1e-5)
      levels.insert(sensor.quantisedDepth(z, fx_px));
    return (*levels.rbegin() - *levels.begin()) / (levels.size() - 1);
  };
  const double focal_baseline = fx_px * sensor.baseline_m;
  for (const double z : {1.0, 2.0, 3.0})
    EXPECT_NEAR(levelSpacing(z), z * z * sensor.disparity_step_px / focal_baseline, 0.03 * levelSpacing(z)) << z;
  EXPECT_NEAR(levelSpacing(2.0) / levelSpacing(1.0), 4.0, 0.1);
  sensor.disparity_step_px = 0.0;
  EXPECT_DOUBLE_EQ(sensor.quantisedDepth(1.2345, fx_px), 1.2345) << "off: unchanged";
}

TEST(StereoDepth, RenderedFloorShowsTheQuantisationSteps)
{
  // The floor seen 10 degrees from face-on: its depth changes by under a
  // millimetre a row, finer than the steps.
  auto floorAt = [](double distance_m, const SensorModel& sensor) {
    Scene scene;
    scene.world_T_camera = lookAt(Eigen::Vector3d::Zero(), distance_m, 80.0, 0.0);
    return SyntheticRig(kVga, sensor).render(scene, 1).depth_mm;
  };
  auto medianSpacingNear = [](const cv::Mat& depth_mm, int centre_mm) {
    std::set<int> values;
    for (int v = 0; v < depth_mm.rows; ++v)
      for (int u = 0; u < depth_mm.cols; ++u)
      {
        const int d = depth_mm.at<unsigned short>(v, u);
        if (std::abs(d - centre_mm) <= 100) values.insert(d);
      }
    std::vector<int> spacing;
    for (auto it = std::next(values.begin()); it != values.end(); ++it)
      spacing.push_back(*it - *std::prev(it));
    if (spacing.empty()) return 0;
    std::nth_element(spacing.begin(), spacing.begin() + spacing.size() / 2, spacing.end());
    return spacing[spacing.size() / 2];
  };
  SensorModel quantised = noiseless(SensorModel());
  quantised.disparity_step_px = 1.0 / 32.0;
  const double focal_baseline = kVga.fx_px * quantised.baseline_m;
  // 1/32 px at 640x480 is ~8.3 mm of depth at 3 m and ~2.1 mm at 1.5 m.
  EXPECT_NEAR(medianSpacingNear(floorAt(3.0, quantised), 3000), 1000.0 * 9.0 / 32.0 / focal_baseline, 1.0);
  EXPECT_NEAR(medianSpacingNear(floorAt(1.5, quantised), 1500), 1000.0 * 2.25 / 32.0 / focal_baseline, 1.0);
  EXPECT_EQ(medianSpacingNear(floorAt(3.0, noiseless(SensorModel())), 3000), 1) << "unquantised: every millimetre";
}

TEST(StereoDepth, MisregistrationShiftsDepthAgainstColour)
{
  const Scene scene = twoBoxes(0.02, 1.2);
  SensorModel sensor = SensorModel::d4xx();
  sensor.depth_offset_u_px = sensor.depth_offset_v_px = 0;
  const SyntheticFrame aligned = SyntheticRig(kVga, sensor).render(scene, 9);
  sensor.depth_offset_u_px = 2;
  sensor.depth_offset_v_px = -1;
  const SyntheticFrame shifted = SyntheticRig(kVga, sensor).render(scene, 9);
  EXPECT_EQ(cv::norm(aligned.rgb, shifted.rgb, cv::NORM_INF), 0.0) << "colour stays";
  const cv::Rect source(0, 1, kVga.width_px - 2, kVga.height_px - 1);
  const cv::Rect target(2, 0, kVga.width_px - 2, kVga.height_px - 1);
  EXPECT_EQ(cv::norm(aligned.depth_mm(source), shifted.depth_mm(target), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(aligned.depth_mm, shifted.depth_mm, cv::NORM_L1), 0.0);
  EXPECT_EQ(cv::countNonZero(shifted.depth_mm.colRange(0, 2)), 0) << "shifted in from outside: no depth";
}

TEST(StereoDepth, RoundedEdgesLeaveADarkLineAndAFaintCrease)
{
  // Zero gap: only the rounding marks the seam.
  const Scene scene = twoBoxes(0.0, 1.0, 0.004);
  const SyntheticFrame ideal = SyntheticRig(kVga, noiseless(SensorModel())).render(scene, 2);
  const SyntheticFrame d4xx = SyntheticRig(kVga, windowOnly()).render(scene, 2);
  const int v = kVga.height_px / 2;
  // The seam's column: where the instance label changes along the row.
  int seam_u = -1;
  for (int u = 1; u < kVga.width_px; ++u)
    if (ideal.instance_labels.at<unsigned short>(v, u - 1) == 1 && ideal.instance_labels.at<unsigned short>(v, u) == 2)
      seam_u = u;
  ASSERT_GT(seam_u, 0);
  const int face_u = seam_u + 60;  // on the flat of the second box
  const double seam_grey = cv::mean(ideal.rgb(cv::Rect(seam_u - 1, v - 5, 2, 10)))[0];
  const double face_grey = cv::mean(ideal.rgb(cv::Rect(face_u, v - 5, 2, 10)))[0];
  EXPECT_LT(seam_grey, 0.85 * face_grey) << "a dark line at the seam";

  auto creaseMm = [&](const cv::Mat& depth_mm) {
    double deepest = 0.0;
    for (int u = seam_u - 2; u <= seam_u + 1; ++u)
      deepest = std::max(deepest, static_cast<double>(depth_mm.at<unsigned short>(v, u)));
    return deepest - depth_mm.at<unsigned short>(v, face_u);
  };
  cv::Mat clean_mm;
  ideal.depth_clean_m.convertTo(clean_mm, CV_16UC1, 1000.0);
  const double clean_crease = creaseMm(clean_mm), measured_crease = creaseMm(d4xx.depth_mm);
  EXPECT_GE(clean_crease, 2.0) << "the rounded edges dip by millimetres";
  EXPECT_LT(measured_crease, clean_crease) << "the window flattens the crease";
  EXPECT_GE(measured_crease, 0.0);
}

TEST(StereoDepth, SameSeedSameFrameWithTheD4xxModel)
{
  SceneParams params = SceneParams::defaultsFor(SceneKind::kTouchingRows);
  const SceneGenerator generator(BrickCatalogue::mbzirc2020(), params);
  const SyntheticRig rig(kVga, SensorModel::d4xx());
  const SyntheticFrame a = rig.render(generator.generate(4), 17);
  const SyntheticFrame b = rig.render(generator.generate(4), 17);
  const SyntheticFrame c = rig.render(generator.generate(4), 18);
  EXPECT_EQ(cv::norm(a.rgb, b.rgb, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.depth_mm, b.depth_mm, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a.depth_mm, c.depth_mm, cv::NORM_L1), 0.0);
}

namespace
{
RigConfig configFrom(const std::map<std::string, std::string>& values)
{
  return rigConfigFrom([values](const std::string& name) -> std::optional<std::string> {
    const auto found = values.find(name);
    if (found == values.end()) return std::nullopt;
    return found->second;
  });
}

std::string errorOf(const std::map<std::string, std::string>& values)
{
  try
  {
    configFrom(values);
  }
  catch (const ConfigError& e)
  {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(StereoDepth, NamedResolutionsAndDepthModelsFromParameters)
{
  const RigConfig vga = configFrom({{"resolution", "640x480"}});
  EXPECT_EQ(vga.camera.width_px, 640);
  EXPECT_EQ(vga.camera.height_px, 480);
  EXPECT_NEAR(vga.camera.fx_px, 613.3, 0.1);
  EXPECT_DOUBLE_EQ(vga.camera.cx_px, 320.0);
  const RigConfig wide = configFrom({{"resolution", "848x480"}, {"fx", "600"}});
  EXPECT_DOUBLE_EQ(wide.camera.cx_px, 424.0);
  EXPECT_DOUBLE_EQ(wide.camera.fx_px, 600.0) << "named parameters override the mode";
  const RigConfig hd = configFrom({{"resolution", "1280x720"}});
  EXPECT_DOUBLE_EQ(hd.camera.fx_px, PinholeCamera::d415Color1280x720().fx_px);

  const RigConfig d4xx = configFrom({{"depth_model", "d4xx"}, {"edge_fattening_px", "1"}});
  EXPECT_EQ(d4xx.sensor.stereo_window_px, 7);
  EXPECT_EQ(d4xx.sensor.edge_fattening_px, 1);
  EXPECT_DOUBLE_EQ(d4xx.sensor.disparity_step_px, 1.0 / 32.0);
  EXPECT_EQ(configFrom({}).sensor.stereo_window_px, 1) << "ideal by default";

  EXPECT_NE(errorOf({{"resolution", "800x600"}}).find("'resolution'"), std::string::npos);
  EXPECT_NE(errorOf({{"depth_model", "kinect"}}).find("'depth_model'"), std::string::npos);
  EXPECT_NE(errorOf({{"stereo_window_px", "4"}}).find("stereo_window_px"), std::string::npos);
  EXPECT_NE(errorOf({{"edge_fattening_px", "-1"}}).find("edge_fattening_px"), std::string::npos);
  EXPECT_NE(errorOf({{"disparity_step_px", "2"}}).find("disparity_step_px"), std::string::npos);
  EXPECT_NE(errorOf({{"depth_offset_u_px", "40"}}).find("depth_offset_u_px"), std::string::npos);
  EXPECT_NE(errorOf({{"edge_radius_m", "-0.1"}}).find("edge_radius_m"), std::string::npos);
}
}  // namespace sim
}  // namespace brick_pose
