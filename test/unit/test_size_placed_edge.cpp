// A colour line placed as a box's end by the catalogue's sizes: on
// synthetic depth/colour with a real sensor's noise, a face 0.30 m across
// from a step down to a dark line, its plane going on beyond the line (the
// neighbour in a layer of touching boxes).
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/roi/size_placed_edge.h"
#include "bench_frame.h"

namespace brick_pose
{
namespace
{
constexpr int kWidth = 320, kHeight = 240;
constexpr double kFocalPx = 300.0, kCentreU = 159.5, kCentreV = 119.5;
constexpr double kFaceDepthM = 1.2;
constexpr double kMetresPerPx = kFaceDepthM / kFocalPx;  // 4 mm
constexpr int kStepU = 40;               // the face's real edge: the ground lies at u < kStepU
constexpr int kLineU = kStepU + 75;      // 0.30 m on: the line between two boxes
constexpr int kTopV = 70, kBottomV = 170;  // the face's other edges (0.40 m apart)
constexpr double kToleranceM = 0.03;

PinholeCamera camera()
{
  PinholeCamera c;
  c.width_px = kWidth;
  c.height_px = kHeight;
  c.fx_px = c.fy_px = kFocalPx;
  c.cx_px = kCentreU;
  c.cy_px = kCentreV;
  return c;
}

/// Depth: the face's plane from kStepU on, the ground 0.25 m farther before
/// it; grey 150 with `dark(u, v)` pixels 40 levels darker; sensor noise.
template <typename Dark>
RgbdFrame makeFrame(const Dark& dark)
{
  std::mt19937 generator(11);
  std::normal_distribution<double> depth_noise(0.0, 0.0015), grey_noise(0.0, 3.0);
  cv::Mat rgb(kHeight, kWidth, CV_8UC3), depth(kHeight, kWidth, CV_32FC1);
  for (int v = 0; v < kHeight; ++v)
    for (int u = 0; u < kWidth; ++u)
    {
      const double z = u < kStepU ? kFaceDepthM + 0.25 : kFaceDepthM;
      depth.at<float>(v, u) = static_cast<float>(z + depth_noise(generator));
      const auto level = cv::saturate_cast<std::uint8_t>((dark(u, v) ? 110.0 : 150.0) + grey_noise(generator));
      rgb.at<cv::Vec3b>(v, u) = cv::Vec3b(level, level, level);
    }
  FrameHeader header;
  header.stamp_ns = 1;
  header.frame_id = "test";
  return makeRgbdFrame(rgb, depth, camera(), header);
}

bool onTheSeam(int u) { return u == kLineU || u == kLineU + 1; }

Eigen::Vector3d onFace(double u, double v)
{
  return {(u - kCentreU) * kMetresPerPx, (v - kCentreV) * kMetresPerPx, kFaceDepthM};
}

/// The face from the step to the line: edge 0 is the line, edge 2 the step.
BrickCandidate faceUpToTheLine(EdgeKind opposite = EdgeKind::kStepDown)
{
  BrickCandidate face;
  face.plane.centroid_m = onFace(kCentreU, kCentreV);
  face.plane.normal = -Eigen::Vector3d::UnitZ();
  face.plane.rms_m = 0.0015;
  face.plane.valid = true;
  const double line_u = kLineU + 0.5;
  face.corners_m = {onFace(line_u, kTopV), onFace(line_u, kBottomV), onFace(kStepU, kBottomV), onFace(kStepU, kTopV)};
  face.centroid_m = 0.25 * (face.corners_m[0] + face.corners_m[1] + face.corners_m[2] + face.corners_m[3]);
  face.edge_kinds = {EdgeKind::kColourLine, EdgeKind::kStepDown, opposite, EdgeKind::kStepDown};
  return face;
}

/// A box_large-like catalogue: 0.40 x 0.30 x 0.25 m.
const std::vector<double> kExtentsM{0.25, 0.30, 0.40};

TEST(SizePlacedEdge, ALineAtTheCataloguesSizeFromARealEdgeIsTheEndWhereNoOtherSizeShowsAMark)
{
  const RgbdFrame frame = makeFrame([](int u, int) { return onTheSeam(u); });
  const SizePlacedEdge placed = judgeSizePlacedEdge(frame, faceUpToTheLine(), 0, kExtentsM, kToleranceM, {});
  EXPECT_TRUE(placed.confirmed) << placed.doubt;
  EXPECT_TRUE(placed.doubt.empty());
}

TEST(SizePlacedEdge, ALineWhereABoxOfAnotherSizeWouldEndLeavesTheEndInDoubt)
{
  // A second line 0.40 m from the step: the box may be 0.40 m across, the
  // line at 0.30 m print on it.
  const int far_u = kStepU + 100;
  const RgbdFrame frame = makeFrame([&](int u, int) { return onTheSeam(u) || u == far_u || u == far_u + 1; });
  const SizePlacedEdge placed = judgeSizePlacedEdge(frame, faceUpToTheLine(), 0, kExtentsM, kToleranceM, {});
  EXPECT_FALSE(placed.confirmed);
  EXPECT_NE(placed.doubt.find("0.4 m across"), std::string::npos) << placed.doubt;
  // The same inside the face, where a box 0.25 m across would end.
  const int near_u = kStepU + 62;
  const RgbdFrame inside = makeFrame([&](int u, int) { return onTheSeam(u) || u == near_u || u == near_u + 1; });
  const SizePlacedEdge inside_placed = judgeSizePlacedEdge(inside, faceUpToTheLine(), 0, kExtentsM, kToleranceM, {});
  EXPECT_FALSE(inside_placed.confirmed);
  EXPECT_NE(inside_placed.doubt.find("0.25 m across"), std::string::npos) << inside_placed.doubt;
}

TEST(SizePlacedEdge, PrintAlongHalfOfWhereAnotherSizeWouldEndIsNoEnd)
{
  // A label's edge along the first half of the line 0.40 m on (two of the
  // line's four stretches): print, which a box's end running all along
  // the line is not.
  const int far_u = kStepU + 100;
  const RgbdFrame frame = makeFrame([&](int u, int v) { return onTheSeam(u) || (u == far_u && v < kTopV + 50); });
  const SizePlacedEdge placed = judgeSizePlacedEdge(frame, faceUpToTheLine(), 0, kExtentsM, kToleranceM, {});
  EXPECT_TRUE(placed.confirmed) << placed.doubt;
}

TEST(SizePlacedEdge, AMarkAlongThreeQuartersOfWhereAnotherSizeWouldEndLeavesTheDoubt)
{
  // A seam faint along a quarter of its length (low light) still shows
  // where a box 0.40 m across would end.
  const int far_u = kStepU + 100;
  const RgbdFrame frame = makeFrame([&](int u, int v) { return onTheSeam(u) || (u == far_u && v < kTopV + 72); });
  const SizePlacedEdge placed = judgeSizePlacedEdge(frame, faceUpToTheLine(), 0, kExtentsM, kToleranceM, {});
  EXPECT_FALSE(placed.confirmed);
}

TEST(SizePlacedEdge, ALineAcrossFromAnotherLineIsNoEnd)
{
  const RgbdFrame frame = makeFrame([](int u, int) { return onTheSeam(u); });
  const SizePlacedEdge placed =
      judgeSizePlacedEdge(frame, faceUpToTheLine(EdgeKind::kColourLine), 0, kExtentsM, kToleranceM, {});
  EXPECT_FALSE(placed.confirmed);
  EXPECT_NE(placed.doubt.find("no real edge"), std::string::npos) << placed.doubt;
}

TEST(SizePlacedEdge, TheCataloguesExtentsAreEveryTypesLengthWidthAndHeightOnce)
{
  // config/boxes.yaml: box_large 0.40 x 0.30 x 0.25, box_small and box_flat
  // 0.30 x 0.20, 0.15 and 0.07 tall (0.30 and 0.20 once each).
  const std::vector<double> extents =
      catalogueExtentsM(BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/boxes.yaml"));
  const std::vector<double> expected{0.07, 0.15, 0.20, 0.25, 0.30, 0.40};
  ASSERT_EQ(extents.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_NEAR(extents[k], expected[k], 1e-9);
}

/// A face on the plane z = 1.5 m, x from x0 to x1 and y from y0 to y1;
/// edge 1 runs along x = x1, edge 3 along x = x0.
BrickCandidate rectangle(double x0, double x1, double y0, double y1)
{
  BrickCandidate face;
  face.corners_m = {Eigen::Vector3d(x0, y0, 1.5), Eigen::Vector3d(x1, y0, 1.5), Eigen::Vector3d(x1, y1, 1.5),
                    Eigen::Vector3d(x0, y1, 1.5)};
  face.centroid_m = Eigen::Vector3d(0.5 * (x0 + x1), 0.5 * (y0 + y1), 1.5);
  return face;
}

TEST(SizePlacedEdge, TwoFacesMeetAlongAnEdgeOnlyWhereTheyLieAcrossOneLineCoveringIt)
{
  const BrickCandidate left = rectangle(0.0, 0.30, 0.0, 0.40);
  // Across the line x = 0.30, 5 mm off it (each refitted to its pixels).
  EXPECT_TRUE(meetAlongEdge(left, 1, rectangle(0.305, 0.605, 0.0, 0.40), 3, 0.02));
  // Too far off the line, too short a stretch of it, or on the same side.
  EXPECT_FALSE(meetAlongEdge(left, 1, rectangle(0.33, 0.63, 0.0, 0.40), 3, 0.02));
  EXPECT_FALSE(meetAlongEdge(left, 1, rectangle(0.30, 0.60, 0.25, 0.65), 3, 0.02));
  EXPECT_FALSE(meetAlongEdge(left, 1, rectangle(0.0, 0.30, 0.0, 0.40), 1, 0.02));
  // Not along the edge at all: the neighbour's edge across it.
  EXPECT_FALSE(meetAlongEdge(left, 1, rectangle(0.30, 0.60, 0.0, 0.40), 0, 0.02));
}

TEST(SizePlacedEdge, PalletBoxesBetweenPrintedNeighboursArePickableWhereOnlyTheirSizeCouldEndThem)
{
  // bench_frontend's pallet-layer frames at 640x480, the ground given: the
  // boxes of a layer touch, their tops carry print, and the edges between
  // them are only lines in the colour image. A box with a step down across
  // from such a line is complete where no other size of a box standing
  // there could end it; the line placed, the box across it begins there
  // too, and its own far line may be placed from it. Whole tops found
  // complete in the release build: frame 129, 3 of 9 (none before; 1
  // without the lines placed from a neighbour's); 137, 5 of 5 (none; 3).
  // (The sanitizer build's clang renders other scenes from the same seeds:
  // there 5 of 10 and 4 of 7.) No face is complete that is not a whole top
  // (asserted inside).
  const std::vector<std::pair<int, int>> frames_and_least_complete{{129, 3}, {137, 4}};
  for (const auto& [frame, least_complete] : frames_and_least_complete)
  {
    const test::WholeTops tops = test::palletLayerBenchFrame(frame, "640x480");
    EXPECT_EQ(tops.found, tops.whole) << "frame " << frame;
    EXPECT_GE(tops.found_complete, least_complete) << "frame " << frame << ", of " << tops.whole << " whole tops";
  }
}
}  // namespace
}  // namespace brick_pose
