// The small shared helpers that replaced per-file copies: parameter checks,
// parameter binding tables, the union-find root, segments cut from masks and
// their tightly boxed variant, the point grid that rebuilds as a fit's radius
// shrinks, the inline pixel rounding.

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/common/param_parsing.h"
#include "brick_pose/common/rounding.h"
#include "brick_pose/common/union_find.h"
#include "brick_pose/registration/point_grid.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
namespace
{
std::string errorOf(const std::function<void()>& action)
{
  try
  {
    action();
  }
  catch (const ConfigError& e)
  {
    return e.what();
  }
  return "";
}

struct TwoFields
{
  double gain = 1.5;
  int count = 3;
  bool enabled = false;
  void validate() const { ParamCheck("two fields").require(count >= 1, "count", "must be >= 1"); }
};

ParamBindings bindTwoFields(TwoFields& fields)
{
  return {{"gain", &fields.gain}, {"count", &fields.count}, {"enabled", &fields.enabled}};
}
}  // namespace

TEST(ParamCheck, NamesTheStructTheFieldAndTheRule)
{
  const ParamCheck check("roi filter");
  EXPECT_EQ(errorOf([&] { check.require(true, "min_points", "must be >= 3"); }), "");
  EXPECT_EQ(errorOf([&] { check.require(false, "min_points", "must be >= 3"); }), "roi filter: min_points must be >= 3");
  EXPECT_EQ(errorOf([&] { check.require(false, "stride_px", "must be >= 1", 0.0); }),
            "roi filter: stride_px must be >= 1, got 0");
  EXPECT_EQ(errorOf([&] { check.inRange(2.0, 0.0, 1.0, "ratio"); }), "roi filter: ratio must be in [0, 1], got 2");
  EXPECT_NE(errorOf([&] { check.inRange(std::nan(""), 0.0, 1.0, "ratio"); }), "") << "NaN is never in range";
  EXPECT_EQ(errorOf([&] { check.inRange(1.0, 0.0, 1.0, "ratio"); }), "");
}

TEST(ParamBindings, ReadWhatIsSetKeepDefaultsAndReportTheValuesInEffect)
{
  const TwoFields read = readValidated(mapParamLookup({{"count", "7"}, {"enabled", "true"}}), bindTwoFields);
  EXPECT_EQ(read.gain, 1.5) << "unset: the default stands";
  EXPECT_EQ(read.count, 7);
  EXPECT_TRUE(read.enabled);
  TwoFields copy = read;
  const auto values = boundValues(bindTwoFields(copy));
  EXPECT_EQ(values.at("gain"), "1.5");
  EXPECT_EQ(values.at("count"), "7");
  EXPECT_EQ(values.at("enabled"), "true");
}

TEST(ParamBindings, BadTextAndFailedValidationNameTheParameter)
{
  EXPECT_NE(errorOf([] { readValidated(mapParamLookup({{"gain", "fast"}}), bindTwoFields); }).find("'gain'"),
            std::string::npos);
  EXPECT_EQ(errorOf([] { readValidated(mapParamLookup({{"count", "0"}}), bindTwoFields); }),
            "two fields: count must be >= 1");
}

TEST(UnionFind, FindsTheRootAndHalvesThePath)
{
  std::vector<int> parent = {0, 0, 1, 2, 4};  // a chain 3 -> 2 -> 1 -> 0, and 4 alone
  EXPECT_EQ(findRoot(parent, 3), 0);
  EXPECT_EQ(parent[3], 1) << "3 now points at its grandparent";
  EXPECT_EQ(findRoot(parent, 4), 4);
}

TEST(SegmentFromMask, CountsTheMaskAndIndexesOnlyPixelsWithDepth)
{
  cv::Mat depth_m(10, 20, CV_32FC1, cv::Scalar(1.0f));
  depth_m.at<float>(3, 6) = std::numeric_limits<float>::quiet_NaN();
  const cv::Rect box_px(5, 2, 3, 2);  // u 5..7, v 2..3
  cv::Mat mask = cv::Mat::zeros(box_px.size(), CV_8UC1);
  mask.at<std::uint8_t>(0, 0) = 255;  // (u 5, v 2)
  mask.at<std::uint8_t>(1, 1) = 255;  // (u 6, v 3): no depth
  mask.at<std::uint8_t>(1, 2) = 255;  // (u 7, v 3)
  const Segment segment = segmentFromMask(mask, box_px, depth_m, "blue");
  EXPECT_EQ(segment.type_name, "blue");
  EXPECT_EQ(segment.area_px, 3);
  EXPECT_EQ(segment.bounding_box_px, box_px);
  EXPECT_EQ(segment.pixel_indices, (std::vector<int>{2 * 20 + 5, 3 * 20 + 7}));
}

TEST(CroppedSegmentFromMask, BoxesThePixelsTightlyAndKeepsThemAndTheirOrder)
{
  cv::Mat depth_m(10, 20, CV_32FC1, cv::Scalar(1.0f));
  depth_m.at<float>(4, 9) = std::numeric_limits<float>::quiet_NaN();
  const cv::Rect box_px(5, 2, 8, 6);  // u 5..12, v 2..7
  cv::Mat mask = cv::Mat::zeros(box_px.size(), CV_8UC1);
  mask.at<std::uint8_t>(1, 3) = 255;  // (u 8, v 3)
  mask.at<std::uint8_t>(2, 4) = 255;  // (u 9, v 4): no depth
  mask.at<std::uint8_t>(3, 2) = 255;  // (u 7, v 5)
  const Segment whole = segmentFromMask(mask, box_px, depth_m, "red");
  const Segment cropped = croppedSegmentFromMask(mask, box_px, depth_m, "red");
  EXPECT_EQ(cropped.bounding_box_px, cv::Rect(7, 3, 3, 3));
  ASSERT_EQ(cropped.mask.size(), cropped.bounding_box_px.size());
  EXPECT_EQ(cv::countNonZero(cropped.mask), 3);
  EXPECT_EQ(cropped.mask.at<std::uint8_t>(0, 1), 255) << "(u 8, v 3)";
  EXPECT_EQ(cropped.area_px, whole.area_px);
  EXPECT_EQ(cropped.pixel_indices, whole.pixel_indices);
  EXPECT_EQ(cropped.type_name, "red");

  const Segment empty = croppedSegmentFromMask(cv::Mat::zeros(box_px.size(), CV_8UC1), box_px, depth_m, "red");
  EXPECT_EQ(empty.bounding_box_px, box_px) << "nothing to box: the box stays";
  EXPECT_EQ(empty.area_px, 0);
}

TEST(PointGrid, ShrinkingRebuildsOnlyWhenTheCellsAreTooCoarse)
{
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 50; ++i) points.emplace_back(0.002 * i, 0.0, 1.0);
  registration::PointGrid grid(points, 0.02);
  const double coarse_radius_m = grid.maxRadius();
  grid.shrinkTo(0.9 * coarse_radius_m);
  EXPECT_EQ(grid.maxRadius(), coarse_radius_m) << "a small shrink keeps the cells";
  grid.shrinkTo(0.003);
  EXPECT_LT(grid.maxRadius(), 0.5 * coarse_radius_m);
  EXPECT_GE(grid.maxRadius(), 0.003);
  EXPECT_EQ(grid.nearestWithin(Eigen::Vector3d(0.0201, 0.0, 1.0), 0.003), 10) << "same answers after the rebuild";
}

TEST(RoundToInt, AgreesWithLroundOnHalvesNeighboursLargeValuesAndNan)
{
  std::vector<double> values = {0.0, -0.0, 0.5, -0.5, 1.5, -1.5, 2.5, -2.5, 1279.5, -3.4999999, 0.49999999999999994,
                                -0.49999999999999994, 4503599627370495.5, 4503599627370497.0, 1e15 + 0.5, -1e15 - 0.5,
                                1e19, -1e19, std::numeric_limits<double>::quiet_NaN(),
                                std::numeric_limits<double>::infinity()};
  for (double half = -700.5; half <= 700.5; half += 1.0)
  {
    values.push_back(half);
    values.push_back(std::nextafter(half, 0.0));
    values.push_back(std::nextafter(half, half > 0.0 ? 1e9 : -1e9));
  }
  for (int k = 0; k < 2000; ++k) values.push_back(std::sin(k * 1.234567) * 1500.0);  // pixel coordinates
  for (const double value : values)
    EXPECT_EQ(roundToInt(value), static_cast<int>(std::lround(value))) << "value " << value;
  EXPECT_EQ(roundToInt(2.5), 3);
  EXPECT_EQ(roundToInt(-2.5), -3);
  EXPECT_EQ(roundToInt(0.49999999999999994), 0);
}
}  // namespace brick_pose
