// The direction a segment's outline runs along, on its plane.
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "brick_pose/common/angles.h"
#include "brick_pose/roi/outline_axis.h"
#include "brick_pose/segmentation/segment.h"
#include "synthetic_plate_scene.h"


namespace brick_pose
{
namespace
{
/// A frame of a plane facing the camera at 1 m (only the camera is read).
RgbdFrame frontoParallel(PlaneFit& plane)
{
  RgbdFrame frame;
  frame.camera = test::PlateScene::vgaCamera();
  frame.rgb = cv::Mat::zeros(480, 640, CV_8UC3);
  frame.depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(1.0f));
  plane.centroid_m = Eigen::Vector3d(0.0, 0.0, 1.0);
  plane.normal = Eigen::Vector3d(0.0, 0.0, -1.0);
  plane.valid = true;
  return frame;
}

/// A segment whose mask is the given polygons (image pixels) filled.
Segment maskOf(const std::vector<std::vector<cv::Point>>& polygons)
{
  Segment segment;
  segment.mask = cv::Mat::zeros(480, 640, CV_8UC1);
  cv::fillPoly(segment.mask, polygons, cv::Scalar(255));
  segment.bounding_box_px = cv::Rect(0, 0, 640, 480);
  return segment;
}

/// Corners of a w x h rectangle centred on `centre`, turned by `angle_rad`.
std::vector<cv::Point> turnedRectangle(cv::Point2d centre, double w, double h, double angle_rad)
{
  std::vector<cv::Point> corners;
  for (const auto& [x, y] : {std::pair{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}})
  {
    const double dx = x * w, dy = y * h;
    corners.emplace_back(static_cast<int>(std::lround(centre.x + dx * std::cos(angle_rad) - dy * std::sin(angle_rad))),
                         static_cast<int>(std::lround(centre.y + dx * std::sin(angle_rad) + dy * std::cos(angle_rad))));
  }
  return corners;
}

/// Angle of `direction` in the image plane, modulo a quarter turn, in degrees.
double imageAngleDeg(const Eigen::Vector3d& direction)
{
  const double angle = std::atan2(direction.y(), direction.x());
  return std::fmod(angle + 2.0 * kPi, 0.5 * kPi) * 180.0 / kPi;
}

/// Two 180 x 120 px rectangles side by side, the second moved 60 px along
/// its length, all turned by 20 degrees: a Z of two offset bricks.
std::vector<std::vector<cv::Point>> offsetPairTurned20Deg()
{
  const double turn = 20.0 * kPi / 180.0;
  const cv::Point2d along(std::cos(turn), std::sin(turn)), across(-std::sin(turn), std::cos(turn));
  const cv::Point2d centre(300.0, 240.0);
  return {turnedRectangle(centre - 60.0 * across, 180.0, 120.0, turn),
          turnedRectangle(centre + 60.0 * across + 60.0 * along, 180.0, 120.0, turn)};
}

TEST(OutlineAxis, OffsetRectanglesGiveTheirOwnAxisNotTheirHull)
{
  PlaneFit plane;
  const RgbdFrame frame = frontoParallel(plane);
  const Segment segment = maskOf(offsetPairTurned20Deg());
  const std::optional<OutlineAxis> axis = dominantOutlineAxis(frame, segment, plane);
  ASSERT_TRUE(axis.has_value());
  EXPECT_NEAR(imageAngleDeg(axis->direction), 20.0, 0.7);
  EXPECT_GT(axis->support, 0.8);
}

/// Bites and bumps of `radius_px` every `step_px` along each side of
/// `polygon`, alternately taken out of the mask and added to it: a depth edge
/// ragged with noise and fattening.
void rag(cv::Mat& mask, const std::vector<cv::Point>& polygon, int step_px, int radius_px)
{
  bool bite = true;
  for (std::size_t k = 0; k < polygon.size(); ++k)
  {
    const cv::Point2d a = polygon[k], b = polygon[(k + 1) % polygon.size()];
    const int count = static_cast<int>(cv::norm(b - a) / step_px);
    for (int n = 1; n < count; ++n, bite = !bite)
    {
      const cv::Point2d at = a + (b - a) * (static_cast<double>(n) / count);
      cv::circle(mask, cv::Point(static_cast<int>(at.x), static_cast<int>(at.y)), radius_px,
                 cv::Scalar(bite ? 0 : 255), cv::FILLED);
    }
  }
}

TEST(OutlineAxis, ARaggedOutlineStillGivesItsAxis)
{
  // Touching rows frame 122 (VGA, sunlight): two reds side by side in a Z,
  // their outline ragged with the sensor's noise. Much of it broke into
  // pieces of a few pixels at every angle; the stretches along the sides
  // held 0.59 of its length, short of the 0.6 asked, so the tiling kept the
  // quad's axis, 5 degrees off the bricks, and fitted one brick of the two.
  // Without the short pieces they hold 0.69. Here: 0.73, and 0.49 with them.
  PlaneFit plane;
  const RgbdFrame frame = frontoParallel(plane);
  const std::vector<std::vector<cv::Point>> pair = offsetPairTurned20Deg();
  Segment segment = maskOf(pair);
  for (const std::vector<cv::Point>& rectangle : pair) rag(segment.mask, rectangle, 20, 4);
  const std::optional<OutlineAxis> axis = dominantOutlineAxis(frame, segment, plane);
  ASSERT_TRUE(axis.has_value());
  EXPECT_NEAR(imageAngleDeg(axis->direction), 20.0, 1.0);
  // The pieces counted, the sides hold too little of the outline.
  OutlineAxisParams every_piece;
  every_piece.min_stretch_px = 0.0;
  EXPECT_FALSE(dominantOutlineAxis(frame, segment, plane, every_piece).has_value());
}

TEST(OutlineAxis, SidesAlongTheImageBorderDoNotVote)
{
  // A layer turned by 20 degrees running out of the image at its top-left
  // corner: the two longest sides of the mask are the image's own edges.
  PlaneFit plane;
  const RgbdFrame frame = frontoParallel(plane);
  const Segment segment = maskOf({turnedRectangle({40.0, 40.0}, 700.0, 500.0, 20.0 * kDegToRad)});
  const std::optional<OutlineAxis> axis = dominantOutlineAxis(frame, segment, plane);
  ASSERT_TRUE(axis.has_value());
  EXPECT_NEAR(imageAngleDeg(axis->direction), 20.0, 0.7);
}

TEST(OutlineAxis, ARoundOutlineHasNoAxis)
{
  PlaneFit plane;
  const RgbdFrame frame = frontoParallel(plane);
  Segment segment;
  segment.mask = cv::Mat::zeros(480, 640, CV_8UC1);
  cv::circle(segment.mask, cv::Point(320, 240), 120, cv::Scalar(255), cv::FILLED);
  segment.bounding_box_px = cv::Rect(0, 0, 640, 480);
  EXPECT_FALSE(dominantOutlineAxis(frame, segment, plane).has_value());
}

TEST(OutlineAxis, NoOutlineOrNoPlaneGivesNothing)
{
  PlaneFit plane;
  const RgbdFrame frame = frontoParallel(plane);
  EXPECT_FALSE(dominantOutlineAxis(frame, maskOf({}), plane).has_value());
  PlaneFit invalid;
  EXPECT_FALSE(dominantOutlineAxis(frame, maskOf({turnedRectangle({320.0, 240.0}, 100.0, 60.0, 0.3)}), invalid)
                   .has_value());
}
}  // namespace
}  // namespace brick_pose
