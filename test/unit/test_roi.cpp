// ROI filtration: plane fit, OBB, least-area quadrilateral and the 3D
// geometry of a candidate on synthetic plates with exact truth.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/roi/inset_fill.h"
#include "brick_pose/roi/least_area_quad.h"
#include "brick_pose/roi/oriented_bounding_box.h"
#include "brick_pose/geometry/plane_fit.h"
#include "brick_pose/roi/plate_splitter.h"
#include "brick_pose/roi/roi_filter.h"
#include "brick_pose/segmentation/hsv_segmenter.h"
#include "brick_pose/segmentation/segment.h"
#include "synthetic_plate_scene.h"

namespace brick_pose
{
namespace
{
double degrees(double radians) { return radians * 180.0 / M_PI; }

/// Grid of points on a rectangle L x W with frame `rotation` at `centre`.
pcl::PointCloud<pcl::PointXYZ> rectanglePoints(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& centre,
                                               double length_m, double width_m, double step_m,
                                               double noise_m = 0.0, unsigned seed = 3)
{
  std::mt19937 generator(seed);
  std::normal_distribution<double> noise(0.0, noise_m > 0.0 ? noise_m : 1.0);
  pcl::PointCloud<pcl::PointXYZ> cloud;
  for (double x = -0.5 * length_m; x <= 0.5 * length_m + 1e-9; x += step_m)
    for (double y = -0.5 * width_m; y <= 0.5 * width_m + 1e-9; y += step_m)
    {
      const double z = noise_m > 0.0 ? noise(generator) : 0.0;
      const Eigen::Vector3d p = centre + rotation * Eigen::Vector3d(x, y, z);
      cloud.push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
    }
  return cloud;
}

/// Mask of a quadrilateral in image pixels, sampled at pixel centres, with
/// an optional notch (a polygon removed from it) and spur (a convex polygon
/// added to it).
cv::Mat rasterise(const std::array<Eigen::Vector2d, 4>& quad, cv::Size size,
                  const std::vector<Eigen::Vector2d>& notch = {}, const std::vector<Eigen::Vector2d>& spur = {})
{
  auto inside = [](const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& p) {
    bool positive = false, negative = false;
    for (std::size_t k = 0; k < polygon.size(); ++k)
    {
      const Eigen::Vector2d a = polygon[k], b = polygon[(k + 1) % polygon.size()];
      const double c = (b - a).x() * (p - a).y() - (b - a).y() * (p - a).x();
      positive |= c > 0.0;
      negative |= c < 0.0;
    }
    return !(positive && negative);
  };
  const std::vector<Eigen::Vector2d> polygon(quad.begin(), quad.end());
  cv::Mat mask = cv::Mat::zeros(size, CV_8UC1);
  for (int v = 0; v < size.height; ++v)
    for (int u = 0; u < size.width; ++u)
    {
      const Eigen::Vector2d p(u, v);
      const bool in_quad = inside(polygon, p) && !(notch.size() >= 3 && inside(notch, p));
      if (in_quad || (spur.size() >= 3 && inside(spur, p))) mask.at<std::uint8_t>(v, u) = 255;
    }
  return mask;
}

/// Largest distance from each truth corner to the nearest fitted corner.
double worstCornerErrorPx(const QuadCorners& fitted, const std::array<Eigen::Vector2d, 4>& truth)
{
  double worst = 0.0;
  for (const auto& t : truth)
  {
    double nearest = 1e9;
    for (const auto& f : fitted) nearest = std::min(nearest, (f - t).norm());
    worst = std::max(worst, nearest);
  }
  return worst;
}

std::array<Eigen::Vector2d, 4> rotatedRectangle(const Eigen::Vector2d& centre, double length, double width, double angle)
{
  const Eigen::Vector2d a(std::cos(angle), std::sin(angle)), b(-std::sin(angle), std::cos(angle));
  return {centre + 0.5 * length * a + 0.5 * width * b, centre + 0.5 * length * a - 0.5 * width * b,
          centre - 0.5 * length * a - 0.5 * width * b, centre - 0.5 * length * a + 0.5 * width * b};
}

TEST(PlaneFit, RecoversTiltedPlaneTowardCameraDespiteOutliers)
{
  const Eigen::Matrix3d rotation = test::PlateScene::facingCamera(0.3, 0.4);
  const Eigen::Vector3d centre(0.1, -0.05, 1.2);
  pcl::PointCloud<pcl::PointXYZ> cloud = rectanglePoints(rotation, centre, 0.6, 0.2, 0.005, 0.002);
  for (int i = 0; i < 40; ++i)  // flying pixels 10-30 cm behind the plate
    cloud.push_back(pcl::PointXYZ(0.1f + 0.001f * i, -0.05f, 1.3f + 0.005f * i));
  const PlaneFit plane = fitPlane(cloud);
  ASSERT_TRUE(plane.valid);
  const Eigen::Vector3d truth_normal = rotation.col(2);  // brick z faces the camera
  EXPECT_LT(truth_normal.z(), 0.0);
  EXPECT_LT(degrees(std::acos(std::min(1.0, plane.normal.dot(truth_normal)))), 0.5);
  EXPECT_LT(std::abs(plane.signedDistance(centre)), 0.001);
  EXPECT_LT(plane.rms_m, 0.003);
  EXPECT_LE(plane.inlier_count, cloud.size() - 40);
}

TEST(PlaneFit, CollinearPointsGiveNoPlane)
{
  pcl::PointCloud<pcl::PointXYZ> line;
  for (int i = 0; i < 10; ++i) line.push_back(pcl::PointXYZ(0.01f * i, 0.0f, 1.0f));
  EXPECT_FALSE(fitPlane(line).valid);
}

TEST(OrientedBoundingBox, MeasuresRotatedRectangleWithinMillimetres)
{
  const Eigen::Matrix3d rotation = test::PlateScene::facingCamera(0.7, 0.5);
  const Eigen::Vector3d centre(-0.2, 0.1, 1.5);
  const auto cloud = rectanglePoints(rotation, centre, 0.6, 0.2, 0.002);
  const OrientedBoundingBox box = computeOrientedBoundingBox(cloud);
  ASSERT_TRUE(box.valid);
  EXPECT_NEAR(box.extents_m.x(), 0.6, 0.003);
  EXPECT_NEAR(box.extents_m.y(), 0.2, 0.003);
  EXPECT_LT(box.extents_m.z(), 0.001);
  EXPECT_LT((box.center_m - centre).norm(), 0.002);
  EXPECT_GT(std::abs(box.axes.col(0).dot(rotation.col(0))), std::cos(0.01));
  EXPECT_NEAR(box.axes.determinant(), 1.0, 1e-9);
}

TEST(OrientedBoundingBox, DimensionCheckAgainstCatalogue)
{
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  const BrickType& green = catalogue.at("green");
  const DimensionTolerance tolerance;
  EXPECT_FALSE(checkTopFaceDimensions(0.61, 0.19, 0.01, green, tolerance));
  EXPECT_FALSE(checkTopFaceDimensions(0.40, 0.20, 0.01, green, tolerance)) << "partly occluded plate";
  const auto too_long = checkTopFaceDimensions(0.70, 0.20, 0.01, green, tolerance);
  ASSERT_TRUE(too_long);
  EXPECT_NE(too_long->find("length"), std::string::npos);
  const auto too_wide = checkTopFaceDimensions(0.60, 0.30, 0.01, green, tolerance);
  ASSERT_TRUE(too_wide);
  EXPECT_NE(too_wide->find("width"), std::string::npos);
  const auto too_thick = checkTopFaceDimensions(0.60, 0.20, 0.15, green, tolerance);
  ASSERT_TRUE(too_thick);
  EXPECT_NE(too_thick->find("thickness"), std::string::npos);
  EXPECT_TRUE(checkTopFaceDimensions(0.10, 0.20, 0.0, green, tolerance));
}

TEST(LeastAreaQuad, ChamferedRectangleReducesToTheRectangle)
{
  // A rectangle with all four corners cut off is an octagon; the least-area
  // enclosing quadrilateral puts the corners back.
  const std::vector<Eigen::Vector2d> octagon = {{2, 0}, {8, 0}, {10, 2}, {10, 4}, {8, 6}, {2, 6}, {0, 4}, {0, 2}};
  const auto quad = reduceToLeastAreaQuad(octagon);
  ASSERT_TRUE(quad);
  const std::array<Eigen::Vector2d, 4> truth = {{{0, 0}, {10, 0}, {10, 6}, {0, 6}}};
  EXPECT_LT(worstCornerErrorPx(*quad, truth), 1e-9);
  EXPECT_FALSE(reduceToLeastAreaQuad({{0, 0}, {1, 0}, {0, 1}}));
}

/// The masks of these tests are sampled at pixel centres: the outer
/// envelope of their outline touches the edges (no anti-aliasing margin).
QuadFitParams centreSampled()
{
  QuadFitParams params;
  params.edge_offset_px = 0.0;
  return params;
}

TEST(LeastAreaQuad, SubPixelCornersOfRotatedRectangle)
{
  for (const double angle : {0.0, 0.2, 0.61, 1.1})
  {
    const auto truth = rotatedRectangle({200.3, 150.7}, 220.0, 80.0, angle);
    const cv::Mat mask = rasterise(truth, {400, 300});
    const auto quad = fitLeastAreaQuad(largestOutline(mask), centreSampled());
    ASSERT_TRUE(quad);
    EXPECT_LT(worstCornerErrorPx(*quad, truth), 0.6) << "angle " << angle;
    EXPECT_GT(signedAreaPx(*quad), 0.0) << "clockwise on screen";
  }
}

TEST(LeastAreaQuad, NotchedEdgeStillGivesTheFullRectangle)
{
  // A chunk missing from one long edge (e.g. a gripper over the plate): the
  // convex hull then loses nothing, but the outline along that edge is broken.
  const double angle = 0.35;
  const Eigen::Vector2d centre(210.0, 160.0);
  const auto truth = rotatedRectangle(centre, 240.0, 90.0, angle);
  const Eigen::Vector2d along(std::cos(angle), std::sin(angle)), across(-std::sin(angle), std::cos(angle));
  const std::vector<Eigen::Vector2d> notch = {centre - 30 * along + 20 * across, centre + 30 * along + 20 * across,
                                              centre + 30 * along + 60 * across, centre - 30 * along + 60 * across};
  const cv::Mat mask = rasterise(truth, {420, 320}, notch);
  const std::vector<cv::Point> outline = largestOutline(mask);
  const auto quad = fitLeastAreaQuad(outline, centreSampled());
  ASSERT_TRUE(quad);
  EXPECT_LT(worstCornerErrorPx(*quad, truth), 1.0);

  // A notch at a corner: the convex hull cuts the corner, the least-area quad
  // restores it from the two edges it still has.
  const std::vector<Eigen::Vector2d> corner_notch = {truth[0] - 40 * along - 10 * across, truth[0] + 10 * along - 10 * across,
                                                     truth[0] + 10 * along + 25 * across, truth[0] - 40 * along + 25 * across};
  const cv::Mat cut = rasterise(truth, {420, 320}, corner_notch);
  const auto cut_quad = fitLeastAreaQuad(largestOutline(cut), centreSampled());
  ASSERT_TRUE(cut_quad);
  EXPECT_LT(worstCornerErrorPx(*cut_quad, truth), 1.0);
  std::vector<cv::Point> hull;
  cv::convexHull(largestOutline(cut), hull);
  double hull_to_corner = 1e9;
  for (const cv::Point& p : hull) hull_to_corner = std::min(hull_to_corner, (Eigen::Vector2d(p.x, p.y) - truth[0]).norm());
  EXPECT_GT(hull_to_corner, 10.0) << "the hull alone misses the occluded corner";
}

TEST(LeastAreaQuad, SpurOnAnEdgeDoesNotTiltIt)
{
  // A blob of the plate's colour stuck to one long edge near its end (a
  // bleeding side face, a neighbour's sliver): the enclosing quad's side
  // runs over its tip, tilted and up to 5 px outside the edge.
  for (const double angle : {0.3, 0.785, 1.2})
  {
    const Eigen::Vector2d centre(210.0, 160.0);
    const auto truth = rotatedRectangle(centre, 240.0, 80.0, angle);
    const Eigen::Vector2d along(std::cos(angle), std::sin(angle)), outward(-std::sin(angle), std::cos(angle));
    const Eigen::Vector2d base = centre + 90.0 * along + 40.0 * outward;  // on the long edge, near corner 0
    const std::vector<Eigen::Vector2d> spur = {base - 12.0 * along - outward, base + 12.0 * along - outward,
                                               base + 8.0 * along + 5.0 * outward, base - 8.0 * along + 5.0 * outward};
    const cv::Mat mask = rasterise(truth, {420, 320}, {}, spur);
    const auto quad = fitLeastAreaQuad(largestOutline(mask), centreSampled());
    ASSERT_TRUE(quad);
    EXPECT_LT(worstCornerErrorPx(*quad, truth), 0.6) << "angle " << angle;
  }
}

TEST(LeastAreaQuad, RaggedEdgesGiveTheEdgesNotTheirMean)
{
  // Low light: edge pixels drop out of the colour threshold at random, so
  // the outline dips 1-3 px into the plate all along its edges. Neither the
  // dips (convexity defects as deep as the whole side) nor their mean
  // should move the sides.
  std::mt19937 generator(11);
  std::uniform_int_distribution<int> dip(0, 11);  // one outline pixel in 12 starts a dip
  std::uniform_int_distribution<int> depth_px(1, 3);
  // Not along the pixel grid: a binary mask only places such an edge within
  // a pixel (between its last row in and the first out), ragged or not.
  for (const double angle : {0.1, 0.42, 0.785, 1.37})
  {
    const auto truth = rotatedRectangle({205.4, 158.2}, 260.0, 90.0, angle);
    cv::Mat mask = rasterise(truth, {420, 320});
    cv::Mat eroded = mask.clone();
    for (const cv::Point& p : largestOutline(mask))
      if (dip(generator) == 0) cv::circle(eroded, p, depth_px(generator), cv::Scalar(0), cv::FILLED);
    const auto quad = fitLeastAreaQuad(largestOutline(eroded), centreSampled());
    ASSERT_TRUE(quad);
    EXPECT_LT(worstCornerErrorPx(*quad, truth), 0.8) << "angle " << angle;
  }
}

/// The mask less a ragged rim: from one outline pixel in `one_in`, a disc
/// of 1-2 px radius is cleared (a depth edge a matching window left jagged).
cv::Mat withRaggedRim(const cv::Mat& mask, int one_in, unsigned seed)
{
  std::mt19937 generator(seed);
  std::uniform_int_distribution<int> start(0, one_in - 1);
  std::uniform_int_distribution<int> radius_px(1, 2);
  cv::Mat ragged = mask.clone();
  for (const cv::Point& p : largestOutline(mask))
    if (start(generator) == 0) cv::circle(ragged, p, radius_px(generator), cv::Scalar(0), cv::FILLED);
  return ragged;
}

/// Outline area over the quad's area, as RoiFilter measures a segment's fill.
double outlineFill(const cv::Mat& mask, const QuadCorners& quad)
{
  double area_px = 0.0;
  for (const auto& outline : allOutlines(mask)) area_px += std::abs(cv::contourArea(outline));
  return area_px / std::abs(signedAreaPx(quad));
}

TEST(InsetFill, TheInsetQuadIsTheQuadWithEachSideMovedIn)
{
  for (const double angle : {0.0, 0.3, 1.1})
  {
    QuadCorners quad = rotatedRectangle({100.0, 80.0}, 60.0, 20.0, angle);
    const QuadCorners truth = rotatedRectangle({100.0, 80.0}, 56.0, 16.0, angle);
    for (const bool reversed : {false, true})
    {
      if (reversed) std::reverse(quad.begin(), quad.end());
      const std::optional<QuadCorners> inset = insetQuad(quad, 2.0);
      ASSERT_TRUE(inset);
      EXPECT_LT(worstCornerErrorPx(*inset, truth), 1e-9) << "angle " << angle << (reversed ? ", reversed" : "");
    }
  }
  // A strip 3 px wide has nothing 2 px inside both long sides.
  EXPECT_FALSE(insetQuad(rotatedRectangle({50.0, 50.0}, 40.0, 3.0, 0.2), 2.0));
}

TEST(InsetFill, ARaggedRimIsLeftOutAMissingPieceIsNot)
{
  // A thin face, 64 x 19 px (a real box top at a metre), whose depth edge
  // is jagged 1-2 px deep all round, as much as on the real box tops of
  // mOSD: its outline fills under 0.85 of its fitted quad, the quad 2 px
  // inside all but a few specks. A corner missing (the same fill) leaves a
  // tenth of the inside open, though the least-area quad cuts part of it off.
  const double angle = 0.25;
  const Eigen::Vector2d centre(80.0, 60.0);
  const QuadCorners quad = rotatedRectangle(centre, 64.0, 19.0, angle);
  const cv::Mat ragged = withRaggedRim(rasterise(quad, {160, 120}), 4, 6);
  // The quad RoiFilter fits to the outline.
  const std::optional<QuadCorners> fitted = fitLeastAreaQuad(allOutlines(ragged), centreSampled());
  ASSERT_TRUE(fitted);
  const double fill = outlineFill(ragged, *fitted);
  EXPECT_LT(fill, 0.85);
  EXPECT_TRUE(shortfallFitsARim(fill * std::abs(signedAreaPx(*fitted)), *fitted, 2.0));
  EXPECT_GT(insetFillRatio(allOutlines(ragged), *fitted, 2.0), 0.95);

  const Eigen::Vector2d along(std::cos(angle), std::sin(angle)), across(-std::sin(angle), std::cos(angle));
  const std::vector<Eigen::Vector2d> corner = {quad[0] - 22.0 * along - 12.0 * across, quad[0] + 5.0 * along - 12.0 * across,
                                               quad[0] + 5.0 * along + 5.0 * across, quad[0] - 22.0 * along + 5.0 * across};
  const cv::Mat notched = rasterise(quad, {160, 120}, corner);
  const std::optional<QuadCorners> notched_quad = fitLeastAreaQuad(allOutlines(notched), centreSampled());
  ASSERT_TRUE(notched_quad);
  EXPECT_LT(outlineFill(notched, *notched_quad), 0.85);
  EXPECT_LT(insetFillRatio(allOutlines(notched), *notched_quad, 2.0), 0.92);
  // Half of it missing: more than a 2 px rim along its sides holds.
  EXPECT_FALSE(shortfallFitsARim(0.5 * std::abs(signedAreaPx(quad)), quad, 2.0));
}

TEST(RoiFilter, FaceCentreOfALongFaceMovesLittleWithOneBadCorner)
{
  // An orange plate, 1.8 x 0.2 m, on a tilted plane. One corner measured
  // 3 mm too far across the face (a side line fitted at a slant).
  const Eigen::Matrix3d rotation = test::PlateScene::facingCamera(0.4, 0.3);
  const Eigen::Vector3d centre(0.1, -0.2, 1.4);
  const Eigen::Vector3d along = rotation.col(0), across = rotation.col(1);
  std::array<Eigen::Vector3d, 4> corners = {centre + 0.9 * along + 0.1 * across, centre + 0.9 * along - 0.1 * across,
                                            centre - 0.9 * along - 0.1 * across, centre - 0.9 * along + 0.1 * across};
  EXPECT_LT((faceCentre(corners) - centre).norm(), 1e-12);
  corners[0] += 0.003 * across;
  const Eigen::Vector3d offset = faceCentre(corners) - centre;
  EXPECT_NEAR(offset.dot(across), 0.00075, 1e-9) << "a quarter of the corner's error, across";
  EXPECT_LT(std::abs(offset.dot(along)), 1e-9) << "nothing along the face";
}

/// Candidate of the scene's plate through HSV segmentation and the ROI filter.
RoiFilterParams centreSampledRoi()
{
  RoiFilterParams params;
  params.quad = centreSampled();
  return params;
}

RoiResult filterScene(const test::PlateScene& scene, const RgbdFrame& frame, RoiFilterParams params = centreSampledRoi())
{
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  const std::vector<Segment> segments = HsvSegmenter().segment(frame, catalogue);
  if (segments.size() != 1) return "expected one segment, got " + std::to_string(segments.size());
  CloudProcessorParams cloud;
  cloud.outlier_removal_enabled = false;
  // Up is the plate's own normal (a top face) unless the caller says otherwise.
  if (params.up_direction.norm() == 0.0) params.up_direction = scene.rotation.col(2);
  return RoiFilter(catalogue, params, cloud).filter(frame, segments.front());
}

TEST(RoiFilter, CornersCentreAndAxisPointsOfATiltedPlate)
{
  test::PlateScene scene;
  scene.camera = test::PlateScene::vgaCamera();
  scene.centre_m = Eigen::Vector3d(0.05, -0.03, 1.1);
  scene.rotation = test::PlateScene::facingCamera(0.5, 0.35);
  scene.depth_noise_m = 0.002;
  const RgbdFrame frame = scene.frame();
  const RoiResult result = filterScene(scene, frame);
  ASSERT_TRUE(std::holds_alternative<BrickCandidate>(result)) << std::get<std::string>(result);
  const BrickCandidate& c = std::get<BrickCandidate>(result);

  EXPECT_EQ(c.type_name, "green");
  EXPECT_TRUE(c.complete);
  EXPECT_NEAR(c.length_m, 0.6, 0.004);
  EXPECT_NEAR(c.width_m, 0.2, 0.004);
  EXPECT_NEAR(c.obb.extents_m.x(), 0.6, 0.015);
  EXPECT_NEAR(c.obb.extents_m.y(), 0.2, 0.015);
  EXPECT_LT((c.centroid_m - scene.centre_m).norm(), 0.003);
  EXPECT_LT(degrees(std::acos(std::min(1.0, c.normal.dot(scene.rotation.col(2))))), 0.5);

  // Corners: each truth corner within 1 px and 4 mm of a candidate corner.
  const auto truth_m = scene.cornersM();
  for (const auto& t : truth_m)
  {
    double best_px = 1e9, best_m = 1e9;
    for (int k = 0; k < 4; ++k)
    {
      best_px = std::min(best_px, (c.corners_px[k] - frame.camera.project(t)).norm());
      best_m = std::min(best_m, (c.corners_m[k] - t).norm());
    }
    EXPECT_LT(best_px, 1.0);
    EXPECT_LT(best_m, 0.004);
  }
  // Long edge first.
  EXPECT_NEAR((c.corners_m[1] - c.corners_m[0]).norm(), 0.6, 0.005);
  EXPECT_NEAR((c.corners_m[2] - c.corners_m[1]).norm(), 0.2, 0.005);
  EXPECT_LE(c.corners_px[0].y(), c.corners_px[2].y());

  // T1/T2 at +-L/4 on the long axis, either way round.
  const Eigen::Vector3d quarter = 0.15 * scene.rotation.col(0);
  const Eigen::Vector3d a = scene.centre_m + quarter, b = scene.centre_m - quarter;
  const double direct = (c.t1_m - a).norm() + (c.t2_m - b).norm();
  const double swapped = (c.t1_m - b).norm() + (c.t2_m - a).norm();
  EXPECT_LT(std::min(direct, swapped), 0.008);
  EXPECT_LT((frame.camera.project(c.t1_m) - c.t1_px).norm(), 1e-6);
  EXPECT_LT((frame.camera.project(c.centroid_m) - c.centroid_px).norm(), 1e-6);
}

TEST(RoiFilter, EdgesCutByTheImageBorderAreTruncated)
{
  test::PlateScene scene;
  scene.camera = test::PlateScene::vgaCamera();
  scene.centre_m = Eigen::Vector3d(0.0, 0.0, 1.0);
  scene.rotation = test::PlateScene::facingCamera(0.0);
  {
    const RgbdFrame frame = scene.frame();
    const RoiResult whole = filterScene(scene, frame);
    ASSERT_TRUE(std::holds_alternative<BrickCandidate>(whole));
    const BrickCandidate& c = std::get<BrickCandidate>(whole);
    for (const bool cut : c.edge_truncated) EXPECT_FALSE(cut);
    EXPECT_TRUE(c.complete);
  }
  // Shifted right so that its +x end (0.3 m, 180 px) leaves the image.
  scene.centre_m.x() = 0.45;
  const RgbdFrame frame = scene.frame();
  const RoiResult clipped = filterScene(scene, frame);
  ASSERT_TRUE(std::holds_alternative<BrickCandidate>(clipped)) << std::get<std::string>(clipped);
  const BrickCandidate& c = std::get<BrickCandidate>(clipped);
  EXPECT_FALSE(c.complete);
  int truncated = 0;
  for (int k = 0; k < 4; ++k)
    if (c.edge_truncated[k])
    {
      ++truncated;
      // The truncated edge is the one along the right image border.
      EXPECT_GT(std::min(c.corners_px[k].x(), c.corners_px[(k + 1) % 4].x()), 630.0);
    }
  EXPECT_EQ(truncated, 1);
}

TEST(PlateSplitter, SplitsWhereDepthSteps)
{
  // One colour blob: left part at 1.0 m, right part 0.2 m farther, with a
  // flying pixel column in between, and a hole without depth.
  const PinholeCamera camera = test::PlateScene::vgaCamera();
  cv::Mat depth(camera.height_px, camera.width_px, CV_32FC1, cv::Scalar(1.0f));
  depth(cv::Rect(200, 0, 440, 480)).setTo(1.2f);
  depth(cv::Rect(200, 0, 1, 480)).setTo(1.1f);
  depth(cv::Rect(120, 200, 3, 3)).setTo(std::numeric_limits<float>::quiet_NaN());
  const RgbdFrame frame = makeRgbdFrame(cv::Mat(camera.height_px, camera.width_px, CV_8UC3, cv::Scalar::all(0)), depth,
                                        camera, {});
  Segment segment;
  segment.type_name = "blue";
  segment.bounding_box_px = cv::Rect(100, 150, 200, 100);
  segment.mask = cv::Mat(segment.bounding_box_px.size(), CV_8UC1, cv::Scalar(255));
  segment.area_px = 200 * 100;

  const std::vector<Segment> parts = splitAtDepthSteps(frame, segment, 0.03, 400);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].area_px, 100 * 100 - 9);  // left: x 100..199, minus the hole
  EXPECT_EQ(parts[1].area_px, 99 * 100);       // right: x 201..299
  EXPECT_EQ(parts[0].type_name, "blue");
  for (const int index : parts[1].pixel_indices) EXPECT_GT(index % camera.width_px, 200);
  EXPECT_TRUE(splitAtDepthSteps(frame, segment, 0.5, 400).empty()) << "one part when every step is allowed";
}

TEST(PlateSplitter, CountsPlatesSideBySide)
{
  EXPECT_EQ(sideBySideCount(0.20, 0.2), 1);
  EXPECT_EQ(sideBySideCount(0.29, 0.2), 1);
  EXPECT_EQ(sideBySideCount(0.41, 0.2), 2);
  EXPECT_EQ(sideBySideCount(0.64, 0.2), 3);
}

TEST(RoiFilter, RejectsAnOversizedPlateWithAReason)
{
  test::PlateScene scene;
  scene.camera = test::PlateScene::vgaCamera();
  scene.centre_m = Eigen::Vector3d(0.0, 0.0, 1.5);
  scene.rotation = test::PlateScene::facingCamera(0.2);
  scene.length_m = 0.9;  // green colour, but 0.9 m long
  const RgbdFrame frame = scene.frame();
  const RoiResult result = filterScene(scene, frame);
  ASSERT_TRUE(std::holds_alternative<std::string>(result));
  EXPECT_NE(std::get<std::string>(result).find("length"), std::string::npos) << std::get<std::string>(result);
}

TEST(RoiFilter, RejectsSegmentWithTooFewDepthPixels)
{
  test::PlateScene scene;
  scene.camera = test::PlateScene::vgaCamera();
  const RgbdFrame frame = scene.frame();
  Segment segment = HsvSegmenter().segment(frame, BrickCatalogue::mbzirc2020()).at(0);
  segment.pixel_indices.resize(10);
  const RoiResult result = RoiFilter(BrickCatalogue::mbzirc2020(), RoiFilterParams(), CloudProcessorParams()).filter(frame, segment);
  ASSERT_TRUE(std::holds_alternative<std::string>(result));
  EXPECT_NE(std::get<std::string>(result).find("depth pixels"), std::string::npos);
}

TEST(RoiFilter, UpDirectionRejectsSideFaces)
{
  test::PlateScene scene;
  scene.camera = test::PlateScene::vgaCamera();
  scene.rotation = test::PlateScene::facingCamera(0.1, 0.6);
  const RgbdFrame frame = scene.frame();
  RoiFilterParams params = centreSampledRoi();
  params.up_direction = Eigen::Vector3d(0.0, -1.0, 0.0);  // camera looking horizontally, y down
  const RoiResult result = filterScene(scene, frame, params);
  ASSERT_TRUE(std::holds_alternative<std::string>(result));
  EXPECT_NE(std::get<std::string>(result).find("not a top face"), std::string::npos) << std::get<std::string>(result);
  params.up_direction = scene.rotation.col(2);  // the plate's own normal: a top face
  EXPECT_TRUE(std::holds_alternative<BrickCandidate>(filterScene(scene, frame, params)));
}

/// The pixels whose depth is nearer than `z_m` (the plate, before its background).
cv::Mat nearerThan(const RgbdFrame& frame, double z_m)
{
  cv::Mat mask = cv::Mat::zeros(frame.height_px(), frame.width_px(), CV_8UC1);
  for (int v = 0; v < frame.height_px(); ++v)
    for (int u = 0; u < frame.width_px(); ++u)
      if (frame.depthAt(u, v) < z_m) mask.at<std::uint8_t>(v, u) = 255;
  return mask;
}

/// A plate of `scene` as a colour-free segment: its depth pixels in `mask`.
RoiResult filterColourFree(const test::PlateScene& scene, const RgbdFrame& frame, const cv::Mat& mask,
                           const RoiFilterParams& params)
{
  const Segment segment =
      segmentFromMask(mask, cv::Rect(0, 0, frame.width_px(), frame.height_px()), frame.depth_m, "");
  CloudProcessorParams cloud;
  cloud.outlier_removal_enabled = false;
  return RoiFilter(BrickCatalogue::mbzirc2020(), params, cloud).filter(frame, segment);
}

TEST(RoiFilter, AColourFreeFaceWithARaggedDepthEdgeIsStillWhole)
{
  // A red plate (0.3 x 0.2 m) 2.6 m away through a wide lens (300 px
  // focal length): 35 x 23 px, as small as a box top in mOSD.
  test::PlateScene scene;
  scene.camera = test::PlateScene::vgaCamera(300.0);
  scene.centre_m = Eigen::Vector3d(0.1, 0.05, 2.6);
  scene.rotation = test::PlateScene::facingCamera(0.2);
  scene.length_m = 0.3;
  scene.background_offset_m = 0.3;
  const RgbdFrame frame = scene.frame();
  const cv::Mat plate = nearerThan(frame, scene.centre_m.z() + 0.15);
  RoiFilterParams params = centreSampledRoi();
  params.up_direction = scene.rotation.col(2);
  // The jagged rim has no depth (what a matcher leaves there is dropped as
  // invalid, or lies off the plane).
  const cv::Mat rim_kept = withRaggedRim(plate, 2, 7);
  RgbdFrame jagged = frame;
  jagged.depth_m = frame.depth_m.clone();
  jagged.depth_m.setTo(std::numeric_limits<float>::quiet_NaN(), plate & ~rim_kept);

  const RoiResult ragged = filterColourFree(scene, jagged, rim_kept, params);
  ASSERT_TRUE(std::holds_alternative<BrickCandidate>(ragged)) << std::get<std::string>(ragged);
  const BrickCandidate& candidate = std::get<BrickCandidate>(ragged);
  EXPECT_LT(candidate.fill_ratio, params.min_fill_ratio) << "the rim must cost more than the plain fill allows";
  EXPECT_EQ(candidate.type_name, "red");
  EXPECT_TRUE(candidate.complete) << candidate.partial_reason;
  // Without the rim allowance the same segment is refused for its fill.
  RoiFilterParams strict = params;
  strict.ragged_outline_px = 0.0;
  const RoiResult refused = filterColourFree(scene, jagged, rim_kept, strict);
  ASSERT_TRUE(std::holds_alternative<std::string>(refused));
  EXPECT_NE(std::get<std::string>(refused).find("segment fills"), std::string::npos) << std::get<std::string>(refused);

  // A quarter of the plate missing at one end of a long side is no rim.
  scene.has_notch = true;
  scene.notch_min_m = Eigen::Vector2d(0.0, 0.0);
  scene.notch_max_m = Eigen::Vector2d(0.16, 0.11);
  const RgbdFrame notched_frame = scene.frame();
  const cv::Mat notched = nearerThan(notched_frame, scene.centre_m.z() + 0.15);
  const RoiResult notch = filterColourFree(scene, notched_frame, notched, params);
  ASSERT_TRUE(std::holds_alternative<std::string>(notch));
  EXPECT_NE(std::get<std::string>(notch).find("segment fills"), std::string::npos) << std::get<std::string>(notch);
}

TEST(RoiFilter, ARimMissingMoreThanARimHoldsNeverLowersMinFillRatio)
{
  // A green (0.6 x 0.2 m, 450 x 150 px) with a corner missing, 4 % of it:
  // more than a 2 px rim along its sides holds, so the rim rule says nothing
  // and a min_fill_ratio above the face's fill refuses it.
  test::PlateScene scene;
  scene.camera = test::PlateScene::vgaCamera();
  scene.centre_m = Eigen::Vector3d(0.0, 0.0, 0.8);
  scene.rotation = test::PlateScene::facingCamera(0.1);
  scene.has_notch = true;
  scene.notch_min_m = Eigen::Vector2d(0.26, 0.0);
  scene.notch_max_m = Eigen::Vector2d(0.31, 0.095);
  const RgbdFrame frame = scene.frame();
  const cv::Mat plate = nearerThan(frame, scene.centre_m.z() + 0.15);
  RoiFilterParams params = centreSampledRoi();
  params.up_direction = scene.rotation.col(2);
  params.min_fill_ratio = 0.99;
  const RoiResult result = filterColourFree(scene, frame, plate, params);
  ASSERT_TRUE(std::holds_alternative<std::string>(result)) << "fill " << std::get<BrickCandidate>(result).fill_ratio;
  EXPECT_NE(std::get<std::string>(result).find("more short than a ragged rim"), std::string::npos)
      << std::get<std::string>(result);
}
}  // namespace
}  // namespace brick_pose
