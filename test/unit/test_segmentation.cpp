// Segmentation: HSV plate masks (including hue wrap-around) and colour-free
// region growing on synthetic plates.
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/segmentation/hsv_segmenter.h"
#include "brick_pose/segmentation/region_growing_segmenter.h"
#include "synthetic_plate_scene.h"

namespace brick_pose
{
namespace
{
cv::Mat hsvOf(const cv::Mat& rgb)
{
  cv::Mat hsv;
  cv::cvtColor(rgb, hsv, cv::COLOR_RGB2HSV);
  return hsv;
}

/// Frame with flat depth from an RGB image.
RgbdFrame flatFrame(const cv::Mat& rgb, float depth_m = 1.0f)
{
  PinholeCamera camera = test::PlateScene::vgaCamera();
  camera.width_px = rgb.cols;
  camera.height_px = rgb.rows;
  camera.cx_px = 0.5 * (rgb.cols - 1);
  camera.cy_px = 0.5 * (rgb.rows - 1);
  return makeRgbdFrame(rgb, cv::Mat(rgb.size(), CV_32FC1, cv::Scalar(depth_m)), camera, {});
}

/// Ratio of shared to joint pixels of a segment and a full-image mask.
double intersectionOverUnion(const Segment& segment, const cv::Mat& truth)
{
  cv::Mat placed = cv::Mat::zeros(truth.size(), CV_8UC1);
  segment.mask.copyTo(placed(segment.bounding_box_px));
  const double shared = cv::countNonZero(placed & truth);
  const double joint = cv::countNonZero(placed | truth);
  return shared / joint;
}

TEST(HsvSegmenter, FindsTheDrawnPlateAndNotTheBackground)
{
  cv::Mat rgb(240, 320, CV_8UC3, cv::Scalar(128, 128, 128));
  const cv::RotatedRect plate({160.0f, 120.0f}, {150.0f, 50.0f}, 25.0f);
  cv::Point2f corners[4];
  plate.points(corners);
  std::vector<cv::Point> polygon(corners, corners + 4);
  cv::fillConvexPoly(rgb, polygon, cv::Scalar(30, 170, 50));  // green plate_rgb
  cv::Mat truth = cv::Mat::zeros(rgb.size(), CV_8UC1);
  cv::fillConvexPoly(truth, polygon, cv::Scalar(255));
  cv::circle(rgb, {20, 20}, 2, cv::Scalar(30, 170, 50), cv::FILLED);  // speckle below min area

  const std::vector<Segment> segments = HsvSegmenter().segment(flatFrame(rgb), BrickCatalogue::mbzirc2020());
  ASSERT_EQ(segments.size(), 1u);
  const Segment& segment = segments.front();
  EXPECT_EQ(segment.type_name, "green");
  EXPECT_GT(intersectionOverUnion(segment, truth), 0.98);
  EXPECT_EQ(static_cast<int>(segment.pixel_indices.size()), segment.area_px);
  for (const int index : segment.pixel_indices) ASSERT_TRUE(truth.at<std::uint8_t>(index / 320, index % 320)) << index;
}

TEST(HsvSegmenter, SkipsTypesWithoutAPlateColour)
{
  cv::Mat rgb(240, 320, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::rectangle(rgb, cv::Rect(100, 80, 120, 60), cv::Scalar(30, 170, 50), cv::FILLED);  // green plate_rgb
  BrickType carton = BrickCatalogue::mbzirc2020().at("green");
  carton.name = "carton";
  carton.plate_hsv.reset();  // a plain box: for colour-free segmentation only
  const BrickCatalogue catalogue({BrickCatalogue::mbzirc2020().at("green"), carton});
  const std::vector<Segment> segments = HsvSegmenter().segment(flatFrame(rgb), catalogue);
  ASSERT_EQ(segments.size(), 1u);
  EXPECT_EQ(segments.front().type_name, "green");
  EXPECT_TRUE(HsvSegmenter().segment(flatFrame(rgb), BrickCatalogue({carton})).empty());
}

TEST(HsvSegmenter, MaskExcludesGreyAndOtherColours)
{
  cv::Mat rgb(1, 4, CV_8UC3);
  rgb.at<cv::Vec3b>(0, 0) = {128, 128, 128};
  rgb.at<cv::Vec3b>(0, 1) = {25, 60, 200};   // blue
  rgb.at<cv::Vec3b>(0, 2) = {30, 170, 50};   // green
  rgb.at<cv::Vec3b>(0, 3) = {150, 205, 160}; // green brick body: too pale
  const cv::Mat mask = HsvSegmenter::thresholdHsv(hsvOf(rgb), *BrickCatalogue::mbzirc2020().at("green").plate_hsv);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 0), 0);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 1), 0);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 2), 255);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 3), 0);
}

TEST(HsvSegmenter, RedHueRangeWrapsThroughZero)
{
  const HsvRange red = *BrickCatalogue::mbzirc2020().at("red").plate_hsv;
  ASSERT_TRUE(red.wrapsHue());
  cv::Mat hsv(1, 5, CV_8UC3);
  hsv.at<cv::Vec3b>(0, 0) = {178, 200, 200};  // just below 180
  hsv.at<cv::Vec3b>(0, 1) = {2, 200, 200};    // just above 0
  hsv.at<cv::Vec3b>(0, 2) = {90, 200, 200};   // cyan: inside [7, 170], outside the wrapped range
  hsv.at<cv::Vec3b>(0, 3) = {0, 60, 200};     // pale: saturation too low
  hsv.at<cv::Vec3b>(0, 4) = {170, 120, 25};   // the range's own corner
  const cv::Mat mask = HsvSegmenter::thresholdHsv(hsv, red);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 0), 255);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 1), 255);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 2), 0);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 3), 0);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 4), 255);

  // And a whole red plate is found as "red".
  cv::Mat rgb(200, 200, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::rectangle(rgb, cv::Rect(50, 60, 90, 60), cv::Scalar(200, 25, 25), cv::FILLED);
  const auto segments = HsvSegmenter().segment(flatFrame(rgb), BrickCatalogue::mbzirc2020());
  ASSERT_EQ(segments.size(), 1u);
  EXPECT_EQ(segments[0].type_name, "red");
  EXPECT_EQ(segments[0].area_px, 90 * 60);
}

TEST(HsvSegmenter, SeparatePlatesAreSeparateSegmentsAndHolesHaveNoIndices)
{
  cv::Mat rgb(200, 300, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::rectangle(rgb, cv::Rect(20, 20, 100, 40), cv::Scalar(25, 60, 200), cv::FILLED);
  cv::rectangle(rgb, cv::Rect(150, 100, 120, 50), cv::Scalar(25, 60, 200), cv::FILLED);
  RgbdFrame frame = flatFrame(rgb);
  frame.depth_m(cv::Rect(30, 30, 10, 10)).setTo(std::numeric_limits<float>::quiet_NaN());
  const auto segments = HsvSegmenter().segment(frame, BrickCatalogue::mbzirc2020());
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_EQ(segments[0].area_px, 120 * 50);  // largest first
  EXPECT_EQ(segments[1].area_px, 100 * 40);
  EXPECT_EQ(static_cast<int>(segments[1].pixel_indices.size()), 100 * 40 - 100);
  EXPECT_EQ(segments[0].type_name, "blue");
}

TEST(HsvSegmenter, TouchingPlatesAtDifferentDepthsAreSeparate)
{
  // A plate on a lower layer seen right next to one on the upper layer: one
  // colour blob, two depths, and the stereo shadow (no depth) between them.
  cv::Mat rgb(200, 300, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::rectangle(rgb, cv::Rect(40, 50, 200, 100), cv::Scalar(25, 60, 200), cv::FILLED);
  RgbdFrame frame = flatFrame(rgb, 1.2f);
  frame.depth_m(cv::Rect(140, 0, 160, 200)).setTo(1.0f);
  EXPECT_EQ(HsvSegmenter().segment(frame, BrickCatalogue::mbzirc2020()).size(), 2u);
  frame.depth_m(cv::Rect(136, 0, 8, 200)).setTo(std::numeric_limits<float>::quiet_NaN());
  const auto segments = HsvSegmenter().segment(frame, BrickCatalogue::mbzirc2020());
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_GT(segments[0].area_px + segments[1].area_px, 200 * 100 - 20 * 100);

  HsvSegmenterParams no_cut;
  no_cut.depth_jump_m = 0.0;
  EXPECT_EQ(HsvSegmenter(no_cut).segment(frame, BrickCatalogue::mbzirc2020()).size(), 1u);
}

TEST(HsvSegmenter, FullResolutionSearchFindsTheSameSegments)
{
  cv::Mat rgb(240, 320, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::rectangle(rgb, cv::Rect(31, 41, 101, 47), cv::Scalar(245, 140, 15), cv::FILLED);
  HsvSegmenterParams full;
  full.coarse_factor = 1;
  const auto coarse = HsvSegmenter().segment(flatFrame(rgb), BrickCatalogue::mbzirc2020());
  const auto fine = HsvSegmenter(full).segment(flatFrame(rgb), BrickCatalogue::mbzirc2020());
  ASSERT_EQ(coarse.size(), 1u);
  ASSERT_EQ(fine.size(), 1u);
  EXPECT_EQ(coarse[0].type_name, "orange");
  EXPECT_EQ(coarse[0].area_px, 101 * 47);
  EXPECT_EQ(coarse[0].pixel_indices, fine[0].pixel_indices);
}

TEST(HsvSegmenter, MorphologyRemovesSpeckleAndFillsPinholes)
{
  HsvSegmenter segmenter;
  cv::Mat mask = cv::Mat::zeros(100, 100, CV_8UC1);
  cv::rectangle(mask, cv::Rect(20, 20, 50, 40), cv::Scalar(255), cv::FILLED);
  mask.at<std::uint8_t>(40, 40) = 0;  // glare pinhole
  mask.at<std::uint8_t>(5, 5) = 255;  // speckle
  segmenter.cleanMask(mask);
  EXPECT_EQ(mask.at<std::uint8_t>(40, 40), 255);
  EXPECT_EQ(mask.at<std::uint8_t>(5, 5), 0);
  EXPECT_EQ(cv::countNonZero(mask), 50 * 40);
}

TEST(RegionGrowingSegmenter, FindsThePlanarPatchWithoutColour)
{
  test::PlateScene scene;
  scene.camera = test::PlateScene::vgaCamera();
  scene.centre_m = Eigen::Vector3d(0.02, 0.01, 1.0);
  scene.rotation = test::PlateScene::facingCamera(0.4, 0.5);
  scene.plate_rgb = scene.background_rgb;  // no colour cue at all
  scene.depth_noise_m = 0.001;
  const RgbdFrame frame = scene.frame();

  // Truth footprint: pixels whose depth is in front of the background.
  cv::Mat truth = cv::Mat::zeros(frame.depth_m.size(), CV_8UC1);
  for (int v = 0; v < truth.rows; ++v)
    for (int u = 0; u < truth.cols; ++u)
      if (frame.depthAt(u, v) < scene.centre_m.z() + 0.2) truth.at<std::uint8_t>(v, u) = 255;

  const std::vector<Segment> segments = RegionGrowingSegmenter().segment(frame);
  ASSERT_GE(segments.size(), 1u);
  double best_iou = 0.0;
  for (const Segment& segment : segments)
  {
    EXPECT_TRUE(segment.type_name.empty());
    best_iou = std::max(best_iou, intersectionOverUnion(segment, truth));
  }
  EXPECT_GT(best_iou, 0.95);
}

TEST(RegionGrowingSegmenter, ABlockSpansOneAngleAtEveryResolutionAndABadFocalLengthCannotMultiplyThem)
{
  const RegionGrowingSegmenter segmenter;
  // The D415's colour modes (920 px at 1280x720, 613 px at 848x480 and
  // 640x480) and a Kinect's VGA (525 px).
  EXPECT_EQ(segmenter.strideFor(920.0, 1280, 720), 6);
  EXPECT_EQ(segmenter.strideFor(613.3, 848, 480), 4);
  EXPECT_EQ(segmenter.strideFor(613.3, 640, 480), 4);
  EXPECT_EQ(segmenter.strideFor(525.0, 640, 480), 3);
  // A focal length of 1 px, none, or not a number: no more blocks than
  // region growing can take.
  for (const double fx_px : {1.0, 0.0, -50.0, std::nan("")})
  {
    const int stride_px = segmenter.strideFor(fx_px, 1280, 720);
    EXPECT_GE(stride_px, 1);
    EXPECT_LE((1280.0 / stride_px) * (720.0 / stride_px), RegionGrowingSegmenter::kMaxBlocks) << fx_px;
  }
  RegionGrowingParams coarse;
  coarse.block_angle_mrad = 9.8;  // the 6 px blocks of before, at 613 px
  EXPECT_EQ(RegionGrowingSegmenter(coarse).strideFor(613.3, 640, 480), 6);
  coarse.block_angle_mrad = 0.0;
  EXPECT_THROW(RegionGrowingSegmenter{coarse}, ConfigError);
}
}  // namespace
}  // namespace brick_pose
