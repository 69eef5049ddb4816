// Which two partial candidates the front end may join as pieces of one
// plate's face, and the segment it joins them into.
#include <gtest/gtest.h>

#include <algorithm>

#include "brick_pose/pipeline/face_pieces.h"

namespace brick_pose
{
namespace
{
constexpr double kMaxAngleDeg = 10.0;
constexpr double kMaxOffsetM = 0.02;

/// A partial piece of a green plate's face 1 m in front of the camera,
/// centred `along_m` along x, its footprint `columns` wide from column `u0`.
BrickCandidate piece(double along_m, int u0, int columns)
{
  BrickCandidate candidate;
  candidate.type_name = "green";
  candidate.typed_by_colour = true;
  candidate.complete = false;
  candidate.normal = -Eigen::Vector3d::UnitZ();
  candidate.centroid_m = Eigen::Vector3d(along_m, 0.0, 1.0);
  candidate.plane.centroid_m = candidate.centroid_m;
  candidate.plane.normal = candidate.normal;
  candidate.plane.valid = true;
  candidate.bounding_box_px = cv::Rect(u0, 10, columns, 2);
  candidate.mask = cv::Mat(2, columns, CV_8UC1, cv::Scalar(255));
  for (int v = 10; v < 12; ++v)
    for (int u = u0; u < u0 + columns; ++u) candidate.pixel_indices.push_back(v * 100 + u);
  return candidate;
}

bool mayJoin(const BrickCandidate& a, const BrickCandidate& b)
{
  return mayBePiecesOfOneFace(a, b, kMaxAngleDeg, kMaxOffsetM);
}
}  // namespace

TEST(FacePieces, TwoPartialPiecesOfOnePlateColourInOnePlaneMayBeJoined)
{
  EXPECT_TRUE(mayJoin(piece(-0.2, 0, 5), piece(0.2, 8, 5)));
}

TEST(FacePieces, PiecesTypedByTheirSizeAreNeverJoined)
{
  // Tiles of a printed box top, cut where the print draws lines: joined,
  // they would be judged as a plate colour's face, where every line is an
  // edge (learn24 of mOSD: complete on 0.65 of a real box's top).
  BrickCandidate coloured = piece(-0.2, 0, 5), colour_free = piece(0.2, 8, 5);
  colour_free.typed_by_colour = false;
  EXPECT_FALSE(mayJoin(coloured, colour_free));
  EXPECT_FALSE(mayJoin(colour_free, coloured));
  coloured.typed_by_colour = false;
  EXPECT_FALSE(mayJoin(coloured, colour_free));
}

TEST(FacePieces, CompletePiecesAndPiecesOfAnotherTypeAreNotJoined)
{
  BrickCandidate a = piece(-0.2, 0, 5), b = piece(0.2, 8, 5);
  b.complete = true;
  EXPECT_FALSE(mayJoin(a, b));
  b.complete = false;
  b.type_name = "red";
  EXPECT_FALSE(mayJoin(a, b));
}

TEST(FacePieces, PiecesOfAnotherPlaneAreNotJoined)
{
  const BrickCandidate a = piece(-0.2, 0, 5);
  BrickCandidate tilted = piece(0.2, 8, 5);
  tilted.normal = tilted.plane.normal = Eigen::Vector3d(0.0, std::sin(0.3), -std::cos(0.3));  // 17 deg
  EXPECT_FALSE(mayJoin(a, tilted));
  BrickCandidate raised = piece(0.2, 8, 5);
  raised.centroid_m.z() = raised.plane.centroid_m.z() = 1.0 - 2.0 * kMaxOffsetM;  // a layer higher
  EXPECT_FALSE(mayJoin(a, raised));
  EXPECT_FALSE(mayJoin(raised, a));
}

TEST(FacePieces, TheJoinedSegmentHoldsBothFootprintsInRasterOrder)
{
  const BrickCandidate a = piece(-0.2, 0, 5), b = piece(0.2, 8, 5);
  const Segment joined = joinSegments(a, b);
  EXPECT_EQ(joined.type_name, "green");
  EXPECT_EQ(joined.bounding_box_px, cv::Rect(0, 10, 13, 2));
  EXPECT_EQ(joined.area_px, 20);  // the 3 columns between the pieces stay out
  ASSERT_EQ(joined.pixel_indices.size(), 20u);
  EXPECT_TRUE(std::is_sorted(joined.pixel_indices.begin(), joined.pixel_indices.end()));
  EXPECT_EQ(joined.mask.at<unsigned char>(0, 6), 0);
  EXPECT_EQ(joined.mask.at<unsigned char>(1, 12), 255);
}
}  // namespace brick_pose
