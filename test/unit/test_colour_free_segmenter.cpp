// Colour-free planar segmentation (cell clustering + pixel refinement):
// synthetic planes, steps and creases, degenerate frames, border accuracy,
// the front-end mode, and real Kinect frames from mOSD.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/pipeline/pipeline_config.h"
#include "brick_pose/segmentation/cell_clustering.h"
#include "brick_pose/segmentation/cell_grid.h"
#include "brick_pose/segmentation/colour_free_segmenter.h"
#include "brick_pose/segmentation/depth_noise.h"
#include "brick_pose/segmentation/plane_moments.h"
#include "png_image.h"
#include "synthetic_plate_scene.h"

namespace brick_pose
{
namespace
{
/// A plane through `point` with normal `normal` (camera frame).
struct Plane
{
  Eigen::Vector3d point;
  Eigen::Vector3d normal;

  /// Depth of the plane along the ray through (u, v); NaN when the ray misses it.
  double depthAt(const PinholeCamera& camera, int u, int v) const
  {
    const Eigen::Vector3d ray = camera.ray(u, v);
    const double denominator = normal.dot(ray);
    if (std::abs(denominator) < 1e-9) return NAN;
    const double z = normal.dot(point) / denominator;
    return z > 0.0 ? z : NAN;
  }
};

/// A frame whose depth is `depth(u, v)` plus Gaussian noise of sigma
/// noise_at_1m_m * z^2 (a stereo sensor's law), grey colour.
RgbdFrame renderFrame(const PinholeCamera& camera, const std::function<double(int, int)>& depth,
                      double noise_at_1m_m = 0.0, unsigned seed = 1)
{
  std::mt19937 generator(seed);
  std::normal_distribution<double> gaussian(0.0, 1.0);
  cv::Mat depth_m(camera.height_px, camera.width_px, CV_32FC1);
  for (int v = 0; v < camera.height_px; ++v)
    for (int u = 0; u < camera.width_px; ++u)
    {
      double z = depth(u, v);
      if (!std::isnan(z)) z += noise_at_1m_m * z * z * gaussian(generator);
      depth_m.at<float>(v, u) = static_cast<float>(z);
    }
  const cv::Mat rgb(camera.height_px, camera.width_px, CV_8UC3, cv::Scalar(128, 128, 128));
  return makeRgbdFrame(rgb, depth_m, camera, {});
}

/// The face of the raised-face scenes, in pixels.
const cv::Rect kRaisedFace(200, 150, 220, 130);

/// A VGA frame of the ground 1 m away, facing the camera, with kRaisedFace
/// 0.25 m above it (a depth step all round), D415-like noise.
RgbdFrame raisedFaceOverGround()
{
  return renderFrame(
      test::PlateScene::vgaCamera(525.0), [](int u, int v) { return kRaisedFace.contains({u, v}) ? 0.75 : 1.0; },
      0.0015, 3);
}

/// Full-image mask of a segment.
cv::Mat placed(const Segment& segment, cv::Size size)
{
  cv::Mat full = cv::Mat::zeros(size, CV_8UC1);
  segment.mask.copyTo(full(segment.bounding_box_px));
  return full;
}

double iou(const cv::Mat& a, const cv::Mat& b)
{
  return static_cast<double>(cv::countNonZero(a & b)) / std::max(1, cv::countNonZero(a | b));
}

/// The segment with the largest intersection over union with `truth`.
double bestIou(const std::vector<Segment>& segments, const cv::Mat& truth, const Segment** best = nullptr)
{
  double best_iou = 0.0;
  for (const Segment& segment : segments)
  {
    const double value = iou(placed(segment, truth.size()), truth);
    if (value > best_iou)
    {
      best_iou = value;
      if (best) *best = &segment;
    }
  }
  return best_iou;
}

void expectConsistent(const Segment& segment, int width)
{
  EXPECT_TRUE(segment.type_name.empty());
  EXPECT_EQ(segment.area_px, cv::countNonZero(segment.mask));
  EXPECT_EQ(segment.mask.size(), segment.bounding_box_px.size());
  EXPECT_TRUE(std::is_sorted(segment.pixel_indices.begin(), segment.pixel_indices.end()));
  for (const int pixel : segment.pixel_indices)
  {
    const cv::Point p(pixel % width, pixel / width);
    ASSERT_TRUE(segment.bounding_box_px.contains(p));
    ASSERT_TRUE(segment.mask.at<std::uint8_t>(p - segment.bounding_box_px.tl()));
  }
}

TEST(PlaneMoments, FitsAnExactPlaneAndMergesByAddition)
{
  const Eigen::Vector3d normal = Eigen::Vector3d(0.2, -0.3, -1.0).normalized();
  const Eigen::Vector3d u_axis = normal.unitOrthogonal(), v_axis = normal.cross(u_axis);
  const Eigen::Vector3d centre(0.1, 0.0, 1.5);
  PlaneMoments left, right, all;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
    {
      const Eigen::Vector3d p = centre + 0.01 * i * u_axis + 0.01 * j * v_axis;
      (i < 5 ? left : right).add(p.x(), p.y(), p.z());
      all.add(p.x(), p.y(), p.z());
    }
  const MomentPlane plane = fitMomentPlane(left + right);
  ASSERT_TRUE(plane.valid);
  EXPECT_NEAR(std::abs(plane.normal.dot(normal)), 1.0, 1e-9);
  EXPECT_LT(plane.normal.dot(plane.centroid_m), 0.0) << "normal toward the camera";
  EXPECT_NEAR(plane.mse_m2, 0.0, 1e-12);
  EXPECT_NEAR((left + right).count, all.count, 0.0);
  EXPECT_NEAR((plane.centroid_m - all.mean()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(plane.meanSquaredDistance(right), 0.0, 1e-12);

  PlaneMoments line;
  for (int i = 0; i < 10; ++i) line.add(0.01 * i, 0.0, 1.0);
  EXPECT_FALSE(fitMomentPlane(line).valid) << "collinear points have no plane";
  EXPECT_FALSE(fitMomentPlane(PlaneMoments()).valid);
}

TEST(PlaneMoments, RefitFromANearbyNormalMatchesTheClosedFormFit)
{
  // A noisy patch 0.3 x 0.2 m at 1.2 m: the refit started 5 degrees off
  // converges to the closed-form fit's normal, MSE and narrow variance.
  const Eigen::Vector3d normal = Eigen::Vector3d(0.1, -0.4, -1.0).normalized();
  const Eigen::Vector3d u_axis = normal.unitOrthogonal(), v_axis = normal.cross(u_axis);
  std::mt19937 generator(7);
  std::normal_distribution<double> noise_m(0.0, 0.002);
  PlaneMoments patch;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 20; ++j)
    {
      const Eigen::Vector3d p = Eigen::Vector3d(0.0, 0.1, 1.2) + 0.01 * i * u_axis + 0.01 * j * v_axis +
                                noise_m(generator) * normal;
      patch.add(p.x(), p.y(), p.z());
    }
  const MomentPlane exact = fitMomentPlane(patch);
  const Eigen::Vector3d guess = Eigen::AngleAxisd(5.0 * M_PI / 180.0, u_axis) * normal;
  const MomentPlane refit = refitMomentPlane(patch, guess);
  ASSERT_TRUE(exact.valid);
  ASSERT_TRUE(refit.valid);
  EXPECT_GT(refit.normal.dot(exact.normal), std::cos(0.05 * M_PI / 180.0));
  EXPECT_NEAR(refit.mse_m2, exact.mse_m2, 1e-3 * exact.mse_m2);
  EXPECT_NEAR(refit.narrow_variance_m2, exact.narrow_variance_m2, 1e-3 * exact.narrow_variance_m2);
  EXPECT_LT(refit.normal.dot(refit.centroid_m), 0.0) << "normal toward the camera";

  // A guess that gives no direction: the closed form answers instead.
  const MomentPlane fallback = refitMomentPlane(patch, Eigen::Vector3d::Zero());
  ASSERT_TRUE(fallback.valid);
  EXPECT_GT(std::abs(fallback.normal.dot(exact.normal)), 1.0 - 1e-9);
}

TEST(DepthNoise, EstimateReadsTheFlatMajorityAndIsClamped)
{
  std::vector<double> normalised;
  for (int i = 0; i < 80; ++i) normalised.push_back(0.002 * 0.002);  // flat cells, 2 mm at 1 m
  for (int i = 0; i < 20; ++i) normalised.push_back(0.05 * 0.05);    // edges and clutter
  EXPECT_NEAR(estimateNoiseAt1m(normalised, 0.3, 0.0005, 0.02, 0.0016), 0.002, 1e-9);
  EXPECT_NEAR(estimateNoiseAt1m(normalised, 0.3, 0.003, 0.02, 0.0016), 0.003, 1e-12);
  EXPECT_NEAR(estimateNoiseAt1m({}, 0.3, 0.0005, 0.02, 0.0016), 0.0016, 1e-12);
}

TEST(ColourFreeSegmenter, OneTiltedPlaneIsOneSegment)
{
  const PinholeCamera camera = test::PlateScene::vgaCamera(525.0);
  const Plane plane{{0.0, 0.0, 1.2}, Eigen::Vector3d(0.0, -0.6, -1.0).normalized()};
  const RgbdFrame frame = renderFrame(camera, [&](int u, int v) { return plane.depthAt(camera, u, v); }, 0.0015);
  ColourFreeTimings timings;
  const std::vector<Segment> segments = ColourFreeSegmenter().segment(frame, cv::Mat(), &timings);
  ASSERT_EQ(segments.size(), 1u);
  EXPECT_GT(segments[0].area_px, 0.99 * 640 * 480);
  expectConsistent(segments[0], 640);
  EXPECT_NEAR(timings.noise_at_1m_m, 0.0015, 0.0005) << "the noise is measured from the cells";
}

TEST(ColourFreeSegmenter, RaisedFaceAndGroundAreTwoSegmentsWithExactBorders)
{
  // A face 0.25 m above the ground, seen from above: a depth step all round.
  const cv::Rect face = kRaisedFace;
  const RgbdFrame frame = raisedFaceOverGround();
  const std::vector<Segment> segments = ColourFreeSegmenter().segment(frame);
  ASSERT_EQ(segments.size(), 2u);
  cv::Mat truth = cv::Mat::zeros(480, 640, CV_8UC1);
  truth(face).setTo(255);
  const Segment* best = nullptr;
  EXPECT_GT(bestIou(segments, truth, &best), 0.99);
  ASSERT_NE(best, nullptr);
  EXPECT_EQ(best->bounding_box_px, face) << "borders to the pixel on a clean step";
  EXPECT_GT(bestIou(segments, ~truth), 0.99);
  for (const Segment& segment : segments) expectConsistent(segment, 640);
}

TEST(ColourFreeSegmenter, SupportingPlaneIsMarkedAndLeftOutOnRequest)
{
  const RgbdFrame frame = raisedFaceOverGround();
  const ColourFreeSegmenter segmenter;
  const PlanarSegments all = segmenter.segmentPlanes(frame);
  ASSERT_EQ(all.segments.size(), 2u);
  ASSERT_EQ(all.supporting.size(), 2u);
  EXPECT_TRUE(all.supporting[0]) << "the ground (largest) carries the face";
  EXPECT_FALSE(all.supporting[1]);

  const PlanarSegments without = segmenter.segmentPlanes(frame, cv::Mat(), nullptr, false);
  ASSERT_EQ(without.segments.size(), 1u);
  EXPECT_FALSE(without.supporting[0]);
  EXPECT_EQ(without.segments[0].bounding_box_px, all.segments[1].bounding_box_px);
  EXPECT_EQ(without.segments[0].pixel_indices, all.segments[1].pixel_indices);
}

TEST(ColourFreeSegmenter, TwoFacesAtNinetyDegreesAreKeptApartAtTheCrease)
{
  // A roof: two planes at 90 degrees meeting in a vertical ridge line at
  // u = 320, each seen at 45 degrees.
  const PinholeCamera camera = test::PlateScene::vgaCamera(525.0);
  const Plane left{{0.0, 0.0, 1.0}, Eigen::Vector3d(-1.0, 0.0, -1.0).normalized()};
  const Plane right{{0.0, 0.0, 1.0}, Eigen::Vector3d(1.0, 0.0, -1.0).normalized()};
  const RgbdFrame frame = renderFrame(
      camera, [&](int u, int v) { return std::min(left.depthAt(camera, u, v), right.depthAt(camera, u, v)); }, 0.0015, 5);
  const std::vector<Segment> segments = ColourFreeSegmenter().segment(frame);
  ASSERT_EQ(segments.size(), 2u);
  cv::Mat left_truth = cv::Mat::zeros(480, 640, CV_8UC1);
  left_truth.colRange(0, 320).setTo(255);
  EXPECT_GT(bestIou(segments, left_truth), 0.985);
  EXPECT_GT(bestIou(segments, ~left_truth), 0.985);
  // The border follows the ridge: on most rows within 2 px.
  const Segment* left_segment = nullptr;
  bestIou(segments, left_truth, &left_segment);
  ASSERT_NE(left_segment, nullptr);
  const cv::Mat mask = placed(*left_segment, {640, 480});
  int rows_on_ridge = 0;
  for (int v = 0; v < 480; ++v)
  {
    int last = -1;
    for (int u = 0; u < 640; ++u)
      if (mask.at<std::uint8_t>(v, u)) last = u;
    if (std::abs(last - 319) <= 2) ++rows_on_ridge;
  }
  EXPECT_GT(rows_on_ridge, 0.95 * 480);
}

TEST(ColourFreeSegmenter, ParallelFacesTwoCentimetresApartAreKeptApart)
{
  const PinholeCamera camera = test::PlateScene::vgaCamera(525.0);
  const cv::Rect face(180, 120, 280, 200);
  const RgbdFrame frame = renderFrame(
      camera, [&](int u, int v) { return face.contains({u, v}) ? 1.18 : 1.2; }, 0.0015, 7);
  const std::vector<Segment> segments = ColourFreeSegmenter().segment(frame);
  ASSERT_EQ(segments.size(), 2u);
  cv::Mat truth = cv::Mat::zeros(480, 640, CV_8UC1);
  truth(face).setTo(255);
  EXPECT_GT(bestIou(segments, truth), 0.98);
}

TEST(ColourFreeSegmenter, CoplanarFacesWithGroundBetweenThemAreTwoSegments)
{
  const PinholeCamera camera = test::PlateScene::vgaCamera(525.0);
  const cv::Rect a(100, 150, 200, 150), b(310, 150, 200, 150);  // 10 px of ground between them
  const RgbdFrame frame = renderFrame(
      camera, [&](int u, int v) { return a.contains({u, v}) || b.contains({u, v}) ? 0.8 : 1.0; }, 0.0015, 9);
  const std::vector<Segment> segments = ColourFreeSegmenter().segment(frame);
  ASSERT_EQ(segments.size(), 3u);
  cv::Mat truth_a = cv::Mat::zeros(480, 640, CV_8UC1), truth_b = truth_a.clone();
  truth_a(a).setTo(255);
  truth_b(b).setTo(255);
  EXPECT_GT(bestIou(segments, truth_a), 0.98);
  EXPECT_GT(bestIou(segments, truth_b), 0.98);
}

TEST(ColourFreeSegmenter, RotatedPlateBorderIsWithinAPixel)
{
  // A tilted, rotated 0.6 x 0.2 m plate 1.2 m away over a background 0.3 m
  // behind it, D415-like noise; truth from exact ray casting.
  test::PlateScene scene;
  scene.camera = test::PlateScene::vgaCamera();
  scene.centre_m = {0.02, -0.01, 1.2};
  scene.rotation = test::PlateScene::facingCamera(0.35, 0.25);
  scene.depth_noise_m = 0.002;
  const RgbdFrame frame = scene.frame();
  scene.depth_noise_m = 0.0;
  scene.background_offset_m = 1e6;  // truth mask: plate pixels only
  cv::Mat truth_rgb, truth_depth;
  scene.render(truth_rgb, truth_depth);
  cv::Mat truth;
  cv::compare(truth_depth, 1e5, truth, cv::CMP_LT);

  const std::vector<Segment> segments = ColourFreeSegmenter().segment(frame);
  const Segment* plate = nullptr;
  EXPECT_GT(bestIou(segments, truth, &plate), 0.97);
  ASSERT_NE(plate, nullptr);
  // Every border pixel of the segment within 1.5 px of the true border.
  cv::Mat truth_border, distance_to_border;
  cv::morphologyEx(truth, truth_border, cv::MORPH_GRADIENT, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}));
  cv::distanceTransform(~truth_border, distance_to_border, cv::DIST_L2, 3);
  const cv::Mat mask = placed(*plate, truth.size());
  cv::Mat border;
  cv::morphologyEx(mask, border, cv::MORPH_GRADIENT, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}));
  border &= mask;
  std::vector<double> distances;
  for (int v = 0; v < border.rows; ++v)
    for (int u = 0; u < border.cols; ++u)
      if (border.at<std::uint8_t>(v, u)) distances.push_back(distance_to_border.at<float>(v, u));
  ASSERT_FALSE(distances.empty());
  std::sort(distances.begin(), distances.end());
  EXPECT_LE(distances[distances.size() / 2], 1.0) << "median border error";
  EXPECT_LE(distances[distances.size() * 95 / 100], 1.5) << "95th percentile border error";
}

TEST(ColourFreeSegmenter, DegenerateFramesGiveNoSegmentAndNoCrash)
{
  const ColourFreeSegmenter segmenter;
  auto flatFrame = [](cv::Size size) {
    PinholeCamera camera = test::PlateScene::vgaCamera(525.0);
    camera.width_px = size.width;
    camera.height_px = size.height;
    camera.cx_px = 0.5 * (size.width - 1);
    camera.cy_px = 0.5 * (size.height - 1);
    return renderFrame(camera, [](int, int) { return 1.0; });
  };
  // Single pixels, smaller than a cell, thin strips: below the minimum area.
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(2, 3), cv::Size(5, 5), cv::Size(7, 40), cv::Size(300, 1)})
    EXPECT_TRUE(segmenter.segment(flatFrame(size)).empty()) << size;
  // Smaller than a cell with an area threshold it passes: no whole cell, no plane.
  ColourFreeParams small_area;
  small_area.min_area_px = 4;
  EXPECT_TRUE(ColourFreeSegmenter(small_area).segment(flatFrame({5, 5})).empty());
  EXPECT_TRUE(ColourFreeSegmenter(small_area).segment(flatFrame({3, 200})).empty()) << "strip thinner than a cell";
  // All NaN depth (makeRgbdFrame refuses it, a hand-made frame may not).
  RgbdFrame empty;
  empty.camera = test::PlateScene::vgaCamera(525.0);
  empty.rgb = cv::Mat(480, 640, CV_8UC3, cv::Scalar::all(0));
  empty.depth_m = cv::Mat(480, 640, CV_32FC1, cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_TRUE(segmenter.segment(empty).empty());
  // Sparse depth: every third pixel only, no cell is full enough.
  const PinholeCamera camera = test::PlateScene::vgaCamera(525.0);
  const RgbdFrame sparse = renderFrame(camera, [](int u, int v) { return (u + v) % 3 == 0 ? 1.0 : NAN; });
  EXPECT_TRUE(segmenter.segment(sparse).empty());
  // Pure noise: no planes.
  std::mt19937 generator(3);
  std::uniform_real_distribution<double> uniform(0.5, 3.0);
  const RgbdFrame noise = renderFrame(camera, [&](int, int) { return uniform(generator); });
  EXPECT_TRUE(segmenter.segment(noise).empty());
}

TEST(ColourFreeSegmenter, ExcludedPixelsAreLeftOut)
{
  const cv::Rect face = kRaisedFace;
  const RgbdFrame frame = raisedFaceOverGround();
  cv::Mat excluded = cv::Mat::zeros(480, 640, CV_8UC1);
  excluded(face).setTo(255);
  const std::vector<Segment> segments = ColourFreeSegmenter().segment(frame, excluded);
  ASSERT_EQ(segments.size(), 1u) << "only the ground is left";
  for (const int pixel : segments[0].pixel_indices) ASSERT_FALSE(face.contains({pixel % 640, pixel / 640}));
  EXPECT_THROW(ColourFreeSegmenter().segment(frame, cv::Mat::zeros(10, 10, CV_8UC1)), InputError);
}

/// The ground of renderFrame's flat scenes at depth 1 m facing the camera,
/// as tf would give it: up (0, 0, -1), the height of x being 1 - x.z.
Eigen::Vector4d groundAtOneMetre() { return Eigen::Vector4d(0.0, 0.0, -1.0, 1.0); }

TEST(ColourFreeSegmenter, WithTheSupportGivenOutOfViewTheLowerOfTwoTopsIsNotTakenForIt)
{
  // A close view of two layers' tops (0.9 and 0.8 m away), no ground in
  // view: found rather than given, the lower top is the supporting plane
  // (nothing below it, something on it) and is left out; with the ground
  // given 1 m away, both are tops.
  const PinholeCamera camera = test::PlateScene::vgaCamera(525.0);
  const RgbdFrame frame = renderFrame(camera, [&](int u, int) { return u < 400 ? 0.9 : 0.8; }, 0.0015, 7);
  const ColourFreeSegmenter segmenter;
  const PlanarSegments found = segmenter.segmentPlanes(frame, cv::Mat(), nullptr, false);
  ASSERT_EQ(found.segments.size(), 1u) << "the lower top was taken for the support";
  const PlanarSegments given = segmenter.segmentPlanes(frame, cv::Mat(), nullptr, false, groundAtOneMetre());
  ASSERT_EQ(given.segments.size(), 2u);
  EXPECT_FALSE(given.supporting[0]);
  EXPECT_FALSE(given.supporting[1]);
}

TEST(ColourFreeSegmenter, WithTheSupportGivenTheGroundInViewIsTheSupportingPlane)
{
  // The ground and a face 25 cm up: the ground, on the given plane, is the
  // supporting plane and the face is not; a normal of any length is the
  // same plane, and a plane without a normal is an error.
  const cv::Rect face = kRaisedFace;
  const RgbdFrame frame = raisedFaceOverGround();
  const ColourFreeSegmenter segmenter;
  const PlanarSegments all = segmenter.segmentPlanes(frame, cv::Mat(), nullptr, true, Eigen::Vector4d(0, 0, -2, 2));
  ASSERT_EQ(all.segments.size(), 2u);
  EXPECT_TRUE(all.supporting[0]);
  EXPECT_FALSE(all.supporting[1]);
  EXPECT_EQ(all.segments[1].bounding_box_px, face);
  EXPECT_THROW(segmenter.segmentPlanes(frame, cv::Mat(), nullptr, true, Eigen::Vector4d(0, 0, 0, 1)), InputError);
  EXPECT_THROW(segmenter.segmentPlanes(frame, cv::Mat(), nullptr, true, Eigen::Vector4d(0, 0, NAN, 1)), InputError);
}

/// The segments' pixels and supporting flags of `frame`, the support found
/// and then given (groundAtOneMetre()), are the same; the given support's
/// inside started the clustering as one node of at least `min_seeded` cells.
void expectSameSegmentsWithTheSupportGiven(const RgbdFrame& frame, int min_seeded)
{
  const ColourFreeSegmenter segmenter;
  ColourFreeTimings found_timings, given_timings;
  const PlanarSegments found = segmenter.segmentPlanes(frame, cv::Mat(), &found_timings, true);
  const PlanarSegments given = segmenter.segmentPlanes(frame, cv::Mat(), &given_timings, true, groundAtOneMetre());
  EXPECT_EQ(found_timings.seeded_cells, 0);
  EXPECT_GE(given_timings.seeded_cells, min_seeded);
  ASSERT_EQ(given.segments.size(), found.segments.size());
  for (std::size_t k = 0; k < found.segments.size(); ++k)
  {
    EXPECT_EQ(given.segments[k].pixel_indices, found.segments[k].pixel_indices) << "segment " << k;
    EXPECT_EQ(given.supporting[k], found.supporting[k]) << "segment " << k;
  }
}

TEST(ColourFreeSegmenter, WithTheSupportGivenItsInsideStartsAsOneNodeAndTheSegmentsStayTheSame)
{
  // 80 x 60 cells of 8 px; the face covers about 28 x 17 of them, and the
  // cells at its border (a depth step) and beside it are clustered as before.
  const RgbdFrame frame = raisedFaceOverGround();
  expectSameSegmentsWithTheSupportGiven(frame, static_cast<int>(0.9 * (80 * 60 - 31 * 20)));
}

TEST(ColourFreeSegmenter, WithTheSupportGivenAFaceTwoCentimetresUpIsNotSeededIntoIt)
{
  // Beside the raised face, a face 2 cm above the ground: within
  // support_margin_m (3 cm) of it, its rows of cells meeting the ground's
  // with no cell across the step. It is not seeded into the ground's node
  // (nor would the ground be seeded with it): it stays a plane of its own.
  const cv::Rect low(450, 150, 160, 130);
  const RgbdFrame frame = renderFrame(
      test::PlateScene::vgaCamera(525.0),
      [&](int u, int v) { return kRaisedFace.contains({u, v}) ? 0.75 : low.contains({u, v}) ? 0.98 : 1.0; }, 0.0015,
      5);
  expectSameSegmentsWithTheSupportGiven(frame, static_cast<int>(0.9 * (80 * 60 - 31 * 20 - 23 * 20)));
}

TEST(ColourFreeSegmenter, ALikelyPlaneSeedsTheClusteringAndDecidesNothing)
{
  // The raised face over the ground with the ground passed as the likely
  // plane (what FrontEnd's RANSAC finds when no support is given): its
  // inside is seeded, and the segments and the supporting plane are those
  // found without it.
  const RgbdFrame frame = raisedFaceOverGround();
  const ColourFreeSegmenter segmenter;
  ColourFreeTimings plain_timings, likely_timings;
  const PlanarSegments plain = segmenter.segmentPlanes(frame, cv::Mat(), &plain_timings, true);
  const PlanarSegments likely =
      segmenter.segmentPlanes(frame, cv::Mat(), &likely_timings, true, std::nullopt, groundAtOneMetre());
  EXPECT_EQ(plain_timings.seeded_cells, 0);
  EXPECT_GE(likely_timings.seeded_cells, static_cast<int>(0.9 * (80 * 60 - 31 * 20)));
  ASSERT_EQ(likely.segments.size(), plain.segments.size());
  for (std::size_t k = 0; k < plain.segments.size(); ++k)
  {
    EXPECT_EQ(likely.segments[k].pixel_indices, plain.segments[k].pixel_indices) << "segment " << k;
    EXPECT_EQ(likely.supporting[k], plain.supporting[k]) << "segment " << k;
  }
  // Not a given support: in a close view of two tops with the ground out
  // of view, the lower top is still taken for the support and left out.
  const RgbdFrame close = renderFrame(
      test::PlateScene::vgaCamera(525.0), [&](int u, int) { return u < 400 ? 0.9 : 0.8; }, 0.0015, 7);
  EXPECT_EQ(segmenter.segmentPlanes(close, cv::Mat(), nullptr, false, std::nullopt, groundAtOneMetre()).segments.size(),
            1u);
  EXPECT_THROW(segmenter.segmentPlanes(frame, cv::Mat(), nullptr, true, std::nullopt, Eigen::Vector4d(0, 0, 0, 1)),
               InputError);
}

TEST(CellClustering, ASeedGroupNotOnOnePlaneStartsAsSingleCells)
{
  // Every cell seeded: the group spans the ground and a face 2 cm above it
  // (no cell across the step), so it does not start as one node, and the
  // planes are the clustering's without seeds.
  const cv::Rect low(200, 160, 240, 160);
  const RgbdFrame frame = renderFrame(
      test::PlateScene::vgaCamera(525.0), [&](int u, int v) { return low.contains({u, v}) ? 0.98 : 1.0; }, 0.0015, 9);
  const PixelRays rays(frame.camera);
  const CellGrid grid(frame, rays, 8, cv::Mat(), false);
  const std::vector<MomentPlane> cell_planes = fitCellPlanes(grid, CellClusteringParams().min_cell_fill);
  DepthNoise noise;
  noise.sigma_at_1m_m = 0.0015;
  const CellClustering clustering{CellClusteringParams()};
  int seeded = -1;
  const CellPlanes plain = clustering.cluster(grid, cell_planes, noise);
  const CellPlanes all_seeded =
      clustering.cluster(grid, cell_planes, noise, std::vector<std::uint8_t>(grid.size(), 1), &seeded);
  EXPECT_EQ(seeded, 0);
  EXPECT_EQ(all_seeded.cell_labels, plain.cell_labels);
  ASSERT_EQ(plain.planes.size(), 2u) << "the ground and the face";
  // The ground's cells alone, seeded: one node from the start, the same planes.
  std::vector<std::uint8_t> ground(grid.size(), 0);
  for (int cell = 0; cell < grid.size(); ++cell)
    ground[cell] = std::abs(grid.moments(cell).mean().z() - 1.0) < 0.01 ? 1 : 0;
  const CellPlanes ground_seeded = clustering.cluster(grid, cell_planes, noise, ground, &seeded);
  EXPECT_GT(seeded, 0.8 * (80 * 60 - 30 * 20));
  EXPECT_EQ(ground_seeded.cell_labels, plain.cell_labels);
  EXPECT_THROW(clustering.cluster(grid, cell_planes, noise, std::vector<std::uint8_t>(3, 1)), InputError);
}

TEST(ColourFreeSegmenter, ParametersAreValidatedByName)
{
  auto expectField = [](const ColourFreeParams& params, const std::string& field) {
    try
    {
      ColourFreeSegmenter segmenter(params);
      ADD_FAILURE() << "expected ConfigError for " << field;
    }
    catch (const ConfigError& error)
    {
      EXPECT_NE(std::string(error.what()).find(field), std::string::npos) << error.what();
    }
  };
  ColourFreeParams params;
  params.cell_px = 1;
  expectField(params, "cell_px");
  params = ColourFreeParams();
  params.max_noise_at_1m_m = 0.0001;
  expectField(params, "max_noise_at_1m_m");
  params = ColourFreeParams();
  params.clustering.max_angle_deg = 95.0;
  expectField(params, "max_angle_deg");
  params = ColourFreeParams();
  params.refinement.pixel_sigma_factor = 0.0;
  expectField(params, "pixel_sigma_factor");
}

TEST(ColourFreeFrontEnd, ModeIsParsedConfiguredAndClassifiesByDimensions)
{
  EXPECT_EQ(parseSegmentationMode("colour_free"), SegmentationMode::kColourFree);
  EXPECT_EQ(toString(SegmentationMode::kColourFree), "colour_free");
  const std::map<std::string, std::string> values = {{"mode", "colour_free"}, {"colour_free_cell_px", "6"}};
  const ParamLookup lookup = [&](const std::string& name) -> std::optional<std::string> {
    const auto it = values.find(name);
    return it == values.end() ? std::nullopt : std::optional<std::string>(it->second);
  };
  const FrontEndParams params = frontEndParamsFrom(lookup);
  EXPECT_EQ(params.mode, SegmentationMode::kColourFree);
  EXPECT_EQ(params.colour_free.cell_px, 6);

  test::PlateScene scene;
  scene.camera = PinholeCamera::d415Color1280x720();
  scene.centre_m = {0.0, 0.0, 1.1};
  scene.rotation = test::PlateScene::facingCamera(0.3);
  scene.depth_noise_m = 0.0015;
  scene.plate_rgb = scene.background_rgb;  // colour-free
  const FrontEndResult result = FrontEnd(BrickCatalogue::mbzirc2020(), params).process(scene.frame());
  ASSERT_EQ(result.candidates.size(), 1u);
  EXPECT_EQ(result.candidates[0].type_name, "green");
  EXPECT_NEAR(result.candidates[0].length_m, 0.6, 0.01);
  EXPECT_NEAR(result.candidates[0].width_m, 0.2, 0.01);
}

#ifdef BRICK_POSE_SOURCE_DIR
/// A real Kinect scene of mOSD: frame and per-pixel labels.
bool loadMosd(int scene, RgbdFrame& frame, cv::Mat& labels)
{
  const std::string stem = std::string(BRICK_POSE_SOURCE_DIR) + "/test/data/mosd_learn/learn" + std::to_string(scene) + "_";
  const cv::Mat rgb = test::readPng(stem + "color.png");
  const cv::Mat depth = test::readPng(stem + "depth.png");
  labels = test::readPng(stem + "labels.png");
  if (rgb.type() != CV_8UC3 || depth.type() != CV_16UC1 || labels.type() != CV_16UC1) return false;
  PinholeCamera camera = test::PlateScene::vgaCamera(525.0);  // camera.json: fx = fy = 525, cx = 319.5, cy = 239.5
  frame = makeRgbdFrame(rgb, depth, camera, {});
  return true;
}

TEST(ColourFreeSegmenterMosd, TableIsOneSegmentAndNoSegmentMixesObjects)
{
  // learn3: two boxes standing on the table; learn20: a box on a box.
  for (const int scene : {3, 20})
  {
    RgbdFrame frame;
    cv::Mat labels;
    ASSERT_TRUE(loadMosd(scene, frame, labels)) << "test/data/mosd_learn is missing";
    const std::vector<Segment> segments = ColourFreeSegmenter().segment(frame);
    ASSERT_FALSE(segments.empty());
    auto objectOf = [](int label) { return label == 0 ? 0 : (label < 10 ? 1 : label / 10); };
    int table_pixels = 0;
    std::map<int, int> object_pixels;
    for (int i = 0; i < labels.rows * labels.cols; ++i) ++object_pixels[objectOf(labels.at<std::uint16_t>(i))];
    table_pixels = object_pixels[1];
    std::map<int, int> faces_on_object;
    double table_cover = 0.0;
    for (const Segment& segment : segments)
    {
      std::map<int, int> votes;
      for (const int pixel : segment.pixel_indices) ++votes[objectOf(labels.at<std::uint16_t>(pixel))];
      const auto top = std::max_element(votes.begin(), votes.end(),
                                        [](const auto& a, const auto& b) { return a.second < b.second; });
      const double purity = static_cast<double>(top->second) / segment.pixel_indices.size();
      EXPECT_GT(purity, 0.9) << "scene " << scene << ": a segment of " << segment.area_px << " px mixes objects";
      if (top->first == 1) table_cover = std::max(table_cover, static_cast<double>(top->second) / table_pixels);
      if (top->first >= 2) ++faces_on_object[top->first];
    }
    EXPECT_GT(table_cover, 0.8) << "scene " << scene << ": the table is one segment";
    for (const auto& [object, pixels] : object_pixels)
    {
      if (object < 2 || pixels <= 5000) continue;
      EXPECT_GE(faces_on_object[object], 2) << "scene " << scene << ": box " << object << " shows two faces";
    }
  }
}
#endif
}  // namespace
}  // namespace brick_pose
