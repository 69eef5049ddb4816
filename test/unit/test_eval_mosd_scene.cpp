// The mOSD loader: a real scene read into an RgbdFrame and its labels.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "brick_pose/common/errors.h"
#include "brick_pose/eval/mosd_scene.h"

namespace brick_pose
{
namespace
{
const std::string kDirectory = eval::mosdLearnDirectory(BRICK_POSE_SOURCE_DIR);

TEST(MosdScene, Learn0HasTheKinectsSizeAndIntrinsics)
{
  const eval::MosdScene scene = eval::loadMosdScene(kDirectory, "learn0");
  EXPECT_EQ(scene.name, "learn0");
  EXPECT_EQ(scene.frame.width_px(), 640);
  EXPECT_EQ(scene.frame.height_px(), 480);
  EXPECT_EQ(scene.frame.rgb.type(), CV_8UC3);
  EXPECT_EQ(scene.frame.depth_m.type(), CV_32FC1);
  EXPECT_EQ(scene.labels.type(), CV_16UC1);
  EXPECT_EQ(scene.labels.size(), scene.frame.depth_m.size());
  EXPECT_NEAR(scene.frame.camera.fx_px, 525.0, 1e-3);
  EXPECT_NEAR(scene.frame.camera.fy_px, 525.0, 1e-3);
  EXPECT_NEAR(scene.frame.camera.cx_px, 319.5, 1e-3);
  EXPECT_NEAR(scene.frame.camera.cy_px, 239.5, 1e-3);
}

TEST(MosdScene, DepthIsInMetresWithNanForNoDepthAndColourIsRgb)
{
  const eval::MosdScene scene = eval::loadMosdScene(kDirectory, "learn0");
  const cv::Mat raw_mm = cv::imread(kDirectory + "/learn0_depth.png", cv::IMREAD_ANYDEPTH);
  const cv::Mat bgr = cv::imread(kDirectory + "/learn0_color.png", cv::IMREAD_COLOR);
  ASSERT_EQ(raw_mm.type(), CV_16UC1);
  int holes = 0, valid = 0;
  for (int v = 0; v < raw_mm.rows; v += 7)
    for (int u = 0; u < raw_mm.cols; u += 7)
    {
      const int millimetres = raw_mm.at<std::uint16_t>(v, u);
      const float metres = scene.frame.depthAt(u, v);
      if (millimetres == 0)
      {
        EXPECT_TRUE(std::isnan(metres)) << u << "," << v;
        ++holes;
      }
      else
      {
        EXPECT_NEAR(metres, millimetres / 1000.0, 1e-6) << u << "," << v;
        ++valid;
      }
      const cv::Vec3b rgb = scene.frame.rgb.at<cv::Vec3b>(v, u);
      EXPECT_EQ(rgb[0], bgr.at<cv::Vec3b>(v, u)[2]);
      EXPECT_EQ(rgb[2], bgr.at<cv::Vec3b>(v, u)[0]);
    }
  EXPECT_GT(holes, 0);  // the Kinect leaves holes at edges and far away
  EXPECT_GT(valid, holes);
  // A table-top scene about a metre away.
  const float centre_depth = scene.frame.depthAt(320, 300);
  EXPECT_GT(centre_depth, 0.5f);
  EXPECT_LT(centre_depth, 2.0f);
}

TEST(MosdScene, LabelsHoldTheTableAndTheObjects)
{
  const eval::MosdScene scene = eval::loadMosdScene(kDirectory, "learn0");
  int table = 0, objects = 0;
  for (int pixel = 0; pixel < static_cast<int>(scene.labels.total()); ++pixel)
  {
    const std::uint16_t label = scene.labels.ptr<std::uint16_t>(0)[pixel];
    table += eval::isMosdTableLabel(label) ? 1 : 0;
    objects += eval::mosdObjectOfLabel(label) > 0 ? 1 : 0;
  }
  EXPECT_GT(table, 10000);
  EXPECT_GT(objects, 1000);
  EXPECT_EQ(eval::mosdObjectOfLabel(20), 2);
  EXPECT_EQ(eval::mosdObjectOfLabel(21), 2);
  EXPECT_EQ(eval::mosdObjectOfLabel(5), 0);
  EXPECT_TRUE(eval::isMosdTableLabel(1));
  EXPECT_FALSE(eval::isMosdTableLabel(0));
}

TEST(MosdScene, NamesListsTheTwentyFiveScenesInNumericOrder)
{
  const std::vector<std::string> names = eval::mosdSceneNames(kDirectory);
  ASSERT_EQ(names.size(), 25u);
  EXPECT_EQ(names.front(), "learn0");
  EXPECT_EQ(names[10], "learn10");
  EXPECT_EQ(names.back(), "learn24");
}

TEST(MosdScene, MissingSceneThrowsInputErrorNamingTheFile)
{
  try
  {
    eval::loadMosdScene(kDirectory, "learn99");
    FAIL() << "no error";
  }
  catch (const InputError& error)
  {
    EXPECT_NE(std::string(error.what()).find("learn99_camera.json"), std::string::npos) << error.what();
  }
}

TEST(MosdScene, CameraFileWithoutFxOrWithBadNumberIsRejected)
{
  const std::string path = ::testing::TempDir() + "/mosd_camera_test.json";
  std::ofstream(path) << "{\"width\": 640, \"height\": 480, \"fy\": 525, \"cx\": 319.5, \"cy\": 239.5}";
  EXPECT_THROW(eval::readMosdCamera(path), InputError);
  std::ofstream(path) << "{\"width\": 640, \"height\": 480, \"fx\": oops, \"fy\": 525, \"cx\": 319.5, \"cy\": 239.5}";
  EXPECT_THROW(eval::readMosdCamera(path), InputError);
  std::ofstream(path) << "{\"width\": 640, \"height\": 480, \"fx\": 0, \"fy\": 525, \"cx\": 319.5, \"cy\": 239.5}";
  EXPECT_THROW(eval::readMosdCamera(path), InputError);
  std::ofstream(path) << "{\"width\": 640, \"height\": 480, \"fx\": 525, \"fy\": 525, \"cx\": 319.5, \"cy\": 239.5}";
  EXPECT_NEAR(eval::readMosdCamera(path).fx_px, 525.0, 1e-9);
  std::remove(path.c_str());
}
}  // namespace
}  // namespace brick_pose
