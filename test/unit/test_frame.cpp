// Frame construction: encodings, validation messages and inverse projection.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/frame/organized_cloud.h"

namespace brick_pose
{
namespace
{
PinholeCamera smallCamera(int width = 8, int height = 6)
{
  PinholeCamera camera;
  camera.width_px = width;
  camera.height_px = height;
  camera.fx_px = 10.0;
  camera.fy_px = 12.0;
  camera.cx_px = 3.5;
  camera.cy_px = 2.5;
  return camera;
}

cv::Mat colourImage(int width = 8, int height = 6) { return cv::Mat(height, width, CV_8UC3, cv::Scalar(10, 20, 30)); }

cv::Mat depthMillimetres(int width = 8, int height = 6, std::uint16_t value = 1500)
{
  return cv::Mat(height, width, CV_16UC1, cv::Scalar(value));
}

/// Runs `build` and returns the InputError message ("" if none was thrown).
template <typename Build>
std::string inputErrorOf(Build build)
{
  try
  {
    build();
  }
  catch (const InputError& error)
  {
    return error.what();
  }
  return "";
}

TEST(FrameBuilder, ConvertsMillimetresAndMarksZeroAsHole)
{
  cv::Mat depth = depthMillimetres();
  depth.at<std::uint16_t>(2, 3) = 0;
  const RgbdFrame frame = makeRgbdFrame(colourImage(), depth, smallCamera(), {42, "cam"});
  ASSERT_EQ(frame.depth_m.type(), CV_32FC1);
  EXPECT_FLOAT_EQ(frame.depthAt(0, 0), 1.5f);
  EXPECT_TRUE(std::isnan(frame.depthAt(3, 2)));
  EXPECT_EQ(frame.stamp_ns, 42);
  EXPECT_EQ(frame.frame_id, "cam");
  EXPECT_DOUBLE_EQ(frame.stampSeconds(), 42e-9);
}

TEST(FrameBuilder, KeepsMetresAndMarksNonFiniteAsHole)
{
  cv::Mat depth(6, 8, CV_32FC1, cv::Scalar(0.75));
  depth.at<float>(1, 1) = std::numeric_limits<float>::quiet_NaN();
  depth.at<float>(1, 2) = -1.0f;
  depth.at<float>(1, 3) = std::numeric_limits<float>::infinity();
  const RgbdFrame frame = makeRgbdFrame(colourImage(), depth, smallCamera(), {});
  EXPECT_FLOAT_EQ(frame.depthAt(0, 0), 0.75f);
  EXPECT_TRUE(std::isnan(frame.depthAt(1, 1)));
  EXPECT_TRUE(std::isnan(frame.depthAt(2, 1)));
  EXPECT_TRUE(std::isnan(frame.depthAt(3, 1)));
}

TEST(FrameBuilder, ConvertsBgrToRgb)
{
  const cv::Mat bgr(6, 8, CV_8UC3, cv::Scalar(1, 2, 3));  // B=1 G=2 R=3
  const RgbdFrame frame = makeRgbdFrame(imageViewOf(bgr, "bgr8"), imageViewOf(depthMillimetres(), "16UC1"), smallCamera(), {});
  EXPECT_EQ(frame.rgb.at<cv::Vec3b>(0, 0), cv::Vec3b(3, 2, 1));
  const RgbdFrame from_mat = makeRgbdFrame(bgr, depthMillimetres(), smallCamera(), {}, true);
  EXPECT_EQ(from_mat.rgb.at<cv::Vec3b>(5, 7), cv::Vec3b(3, 2, 1));
}

TEST(FrameBuilder, RejectsWrongDepthEncoding)
{
  const cv::Mat colour = colourImage();
  const cv::Mat depth8(6, 8, CV_8UC1, cv::Scalar(1));
  const std::string message = inputErrorOf(
      [&] { makeRgbdFrame(imageViewOf(colour, "rgb8"), imageViewOf(depth8, "8UC1"), smallCamera(), {}); });
  EXPECT_NE(message.find("depth encoding"), std::string::npos) << message;
  EXPECT_NE(message.find("8UC1"), std::string::npos) << message;
  const std::string from_mat = inputErrorOf([&] { makeRgbdFrame(colour, depth8, smallCamera(), {}); });
  EXPECT_NE(from_mat.find("depth encoding"), std::string::npos) << from_mat;
}

TEST(FrameBuilder, RejectsWrongColourEncoding)
{
  const cv::Mat mono(6, 8, CV_8UC1, cv::Scalar(1));
  const cv::Mat depth = depthMillimetres();
  const std::string message =
      inputErrorOf([&] { makeRgbdFrame(imageViewOf(mono, "mono8"), imageViewOf(depth, "16UC1"), smallCamera(), {}); });
  EXPECT_NE(message.find("colour encoding"), std::string::npos) << message;
  const std::string from_mat = inputErrorOf([&] { makeRgbdFrame(mono, depth, smallCamera(), {}); });
  EXPECT_NE(from_mat.find("colour encoding"), std::string::npos) << from_mat;
}

TEST(FrameBuilder, RejectsColourDepthSizeMismatch)
{
  const std::string message =
      inputErrorOf([&] { makeRgbdFrame(colourImage(8, 6), depthMillimetres(4, 6), smallCamera(), {}); });
  EXPECT_NE(message.find("colour size 8x6 differs from depth size 4x6"), std::string::npos) << message;
}

TEST(FrameBuilder, RejectsZeroOrNanFocalLengthNamingTheField)
{
  PinholeCamera camera = smallCamera();
  camera.fx_px = 0.0;
  std::string message = inputErrorOf([&] { makeRgbdFrame(colourImage(), depthMillimetres(), camera, {}); });
  EXPECT_NE(message.find("fx"), std::string::npos) << message;
  camera = smallCamera();
  camera.fy_px = std::numeric_limits<double>::quiet_NaN();
  message = inputErrorOf([&] { makeRgbdFrame(colourImage(), depthMillimetres(), camera, {}); });
  EXPECT_NE(message.find("fy"), std::string::npos) << message;
}

TEST(FrameBuilder, RejectsIntrinsicsOfAnotherImageSize)
{
  const std::string message =
      inputErrorOf([&] { makeRgbdFrame(colourImage(), depthMillimetres(), smallCamera(16, 12), {}); });
  EXPECT_NE(message.find("intrinsics size 16x12 differs from the image size 8x6"), std::string::npos) << message;
}

TEST(FrameBuilder, RejectsAllNanDepth)
{
  const cv::Mat depth(6, 8, CV_32FC1, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  const std::string message = inputErrorOf([&] { makeRgbdFrame(colourImage(), depth, smallCamera(), {}); });
  EXPECT_NE(message.find("all NaN"), std::string::npos) << message;
}

TEST(FrameBuilder, RejectsAllZeroDepth)
{
  const std::string message =
      inputErrorOf([&] { makeRgbdFrame(colourImage(), depthMillimetres(8, 6, 0), smallCamera(), {}); });
  EXPECT_NE(message.find("all zero"), std::string::npos) << message;
}

TEST(FrameBuilder, RejectsEmptyImages)
{
  std::string message = inputErrorOf([&] { makeRgbdFrame(cv::Mat(), depthMillimetres(), smallCamera(), {}); });
  EXPECT_NE(message.find("colour image is empty"), std::string::npos) << message;
  message = inputErrorOf([&] { makeRgbdFrame(colourImage(), cv::Mat(), smallCamera(), {}); });
  EXPECT_NE(message.find("depth image is empty"), std::string::npos) << message;
  ImageView empty_depth;
  empty_depth.encoding = "16UC1";
  const cv::Mat colour = colourImage();
  message = inputErrorOf([&] { makeRgbdFrame(imageViewOf(colour, "rgb8"), empty_depth, smallCamera(), {}); });
  EXPECT_NE(message.find("depth image is empty"), std::string::npos) << message;
}

TEST(OrganizedCloud, InverseProjectsEveryPixelAndKeepsHolesAsNan)
{
  cv::Mat depth = depthMillimetres(8, 6, 2000);
  depth.at<std::uint16_t>(4, 6) = 0;
  cv::Mat colour = colourImage();
  colour.at<cv::Vec3b>(1, 2) = cv::Vec3b(200, 100, 50);
  const PinholeCamera camera = smallCamera();
  const RgbdFrame frame = makeRgbdFrame(colour, depth, camera, {0, "cam"});
  const auto cloud = makeOrganizedCloud(frame);
  ASSERT_EQ(cloud->width, 8u);
  ASSERT_EQ(cloud->height, 6u);
  EXPECT_FALSE(cloud->is_dense);
  const pcl::PointXYZRGB& p = cloud->at(2, 1);  // (column, row)
  EXPECT_NEAR(p.x, (2 - camera.cx_px) * 2.0 / camera.fx_px, 1e-6);
  EXPECT_NEAR(p.y, (1 - camera.cy_px) * 2.0 / camera.fy_px, 1e-6);
  EXPECT_NEAR(p.z, 2.0, 1e-6);
  EXPECT_EQ(p.r, 200);
  EXPECT_EQ(p.g, 100);
  EXPECT_EQ(p.b, 50);
  EXPECT_TRUE(std::isnan(cloud->at(6, 4).z));
  EXPECT_TRUE(std::isnan(cloud->at(6, 4).x));
}

TEST(OrganizedCloud, FillReusesACloudAcrossFrames)
{
  pcl::PointCloud<pcl::PointXYZRGB> cloud;
  fillOrganizedCloud(makeRgbdFrame(colourImage(), depthMillimetres(8, 6, 1000), smallCamera(), {}), cloud);
  const pcl::PointXYZRGB* storage = cloud.points.data();
  cv::Mat depth = depthMillimetres(8, 6, 3000);
  depth.at<std::uint16_t>(0, 0) = 0;
  fillOrganizedCloud(makeRgbdFrame(colourImage(), depth, smallCamera(), {7000, "cam"}), cloud);
  EXPECT_EQ(cloud.points.data(), storage);
  EXPECT_TRUE(std::isnan(cloud.at(0, 0).x));
  EXPECT_NEAR(cloud.at(7, 5).z, 3.0, 1e-6);
  EXPECT_NEAR(cloud.at(7, 5).x, (7 - 3.5) * 3.0 / 10.0, 1e-6);
  EXPECT_EQ(cloud.header.stamp, 7u);  // microseconds
}

TEST(OrganizedCloud, BackProjectsSelectedPixelsSkippingHoles)
{
  cv::Mat depth = depthMillimetres(8, 6, 1000);
  depth.at<std::uint16_t>(0, 1) = 0;
  const RgbdFrame frame = makeRgbdFrame(colourImage(), depth, smallCamera(), {});
  std::vector<int> kept;
  const auto cloud = backProjectPixels(frame, {0, 1, 8 * 5 + 7}, &kept);
  ASSERT_EQ(cloud->size(), 2u);
  EXPECT_EQ(kept, (std::vector<int>{0, 47}));
  EXPECT_NEAR((*cloud)[1].x, (7 - 3.5) * 1.0 / 10.0, 1e-6);
  EXPECT_NEAR((*cloud)[1].y, (5 - 2.5) * 1.0 / 12.0, 1e-6);
  EXPECT_THROW(backProjectPixels(frame, {48}), InputError);
}

TEST(OrganizedCloud, StridedCloudRemembersSourcePixels)
{
  const RgbdFrame frame = makeRgbdFrame(colourImage(), depthMillimetres(), smallCamera(), {});
  std::vector<int> source;
  const auto cloud = makeStridedCloud(frame, 3, source);
  ASSERT_EQ(cloud->width, 3u);
  ASSERT_EQ(cloud->height, 2u);
  ASSERT_EQ(source.size(), 6u);
  EXPECT_EQ(source[4], 3 * 8 + 3);
  EXPECT_NEAR(cloud->at(1, 1).x, (3 - 3.5) * 1.5 / 10.0, 1e-6);
}

TEST(OrganizedCloud, BlockMedianCloudSurvivesDropoutsAndKeepsEdges)
{
  // 8x6 image in 2x2 blocks: a hole-riddled block, an empty block and a
  // block straddling a depth edge (median, not a blend).
  cv::Mat depth = depthMillimetres(8, 6, 1000);
  depth.at<std::uint16_t>(0, 0) = 0;
  depth.at<std::uint16_t>(1, 1) = 0;  // block (0,0): two of four valid
  depth(cv::Rect(2, 0, 2, 2)).setTo(0);  // block (1,0): none valid
  depth.at<std::uint16_t>(2, 4) = 3000;  // block (2,1): 1, 1, 1, 3 m
  const RgbdFrame frame = makeRgbdFrame(colourImage(), depth, smallCamera(), {});
  std::vector<int> source;
  const auto cloud = makeBlockMedianCloud(frame, 2, source);
  ASSERT_EQ(cloud->width, 4u);
  ASSERT_EQ(cloud->height, 3u);
  EXPECT_NEAR(cloud->at(0, 0).z, 1.0, 1e-6);
  EXPECT_TRUE(std::isnan(cloud->at(1, 0).z));
  EXPECT_NEAR(cloud->at(2, 1).z, 1.0, 1e-6);
  // Back-projected through the block centre (pixel-centre coordinates 4.5, 2.5).
  EXPECT_NEAR(cloud->at(2, 1).x, (4.5 - 3.5) * 1.0 / 10.0, 1e-6);
  EXPECT_NEAR(cloud->at(2, 1).y, (2.5 - 2.5) * 1.0 / 12.0, 1e-6);
  EXPECT_EQ(source[1 * 4 + 2], 3 * 8 + 5);
}

TEST(OrganizedCloud, FullSizeFrameMatchesPinholeBackProjection)
{
  const PinholeCamera camera = PinholeCamera::d415Color1280x720();
  cv::Mat depth(720, 1280, CV_32FC1);
  cv::randu(depth, 0.5, 2.0);
  const RgbdFrame frame = makeRgbdFrame(cv::Mat(720, 1280, CV_8UC3, cv::Scalar::all(0)), depth, camera, {});
  const auto cloud = makeOrganizedCloud(frame);
  for (const auto& [u, v] : {std::pair<int, int>{0, 0}, {1279, 719}, {640, 360}, {17, 555}})
  {
    const Eigen::Vector3d expected = camera.backProject(u, v, depth.at<float>(v, u));
    const auto& p = cloud->at(u, v);
    EXPECT_NEAR(p.x, expected.x(), 1e-5);
    EXPECT_NEAR(p.y, expected.y(), 1e-5);
    EXPECT_NEAR(p.z, expected.z(), 1e-6);
  }
}
}  // namespace
}  // namespace brick_pose
