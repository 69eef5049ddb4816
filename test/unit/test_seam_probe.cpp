// The quick look for a seam across a face one brick wide, which spares the
// tiler the faces it could not split.
#include <gtest/gtest.h>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/roi/seam_probe.h"
#include "brick_pose/segmentation/hsv_segmenter.h"
#include "synthetic_plate_scene.h"
#include "touching_plates_scene.h"

namespace brick_pose
{
namespace
{
/// Two 0.3 x 0.2 plates end to end at 1.5 m, seen askew at VGA: a green's
/// top, or two reds'.
test::TouchingPlatesScene twoRedsEndToEnd()
{
  test::TouchingPlatesScene scene;
  scene.camera = test::PlateScene::vgaCamera();
  scene.origin_m = Eigen::Vector3d(0.02, -0.01, 1.5);
  scene.rotation = test::TouchingPlatesScene::facingCamera(0.35, 0.4);
  scene.plates = {{{-0.3, -0.1}, {0.0, 0.1}}, {{0.0, -0.1}, {0.3, 0.1}}};
  scene.colour_noise = 3.0;
  return scene;
}

/// The face as measured: its plane and its corners, 0 -> 1 along its length.
BrickCandidate measuredFace(const test::TouchingPlatesScene& scene)
{
  BrickCandidate face;
  face.plane.centroid_m = scene.origin_m;
  face.plane.normal = scene.rotation.col(2);
  face.plane.valid = true;
  face.corners_m = {scene.toCamera(-0.3, 0.1), scene.toCamera(0.3, 0.1), scene.toCamera(0.3, -0.1),
                    scene.toCamera(-0.3, -0.1)};
  return face;
}

SeamProbe probe(const test::TouchingPlatesScene& scene)
{
  const RgbdFrame frame = scene.frame();
  const std::vector<Segment> segments = HsvSegmenter().segment(frame, BrickCatalogue::mbzirc2020());
  EXPECT_EQ(segments.size(), 1u);
  if (segments.empty()) return SeamProbe();
  // The smallest seams a cut is kept with (EdgeEvidenceParams' defaults).
  return probeSeamsAcross(frame, segments[0], measuredFace(scene), 6.0, 0.0008);
}

TEST(SeamProbe, APlainFaceShowsNoSeam)
{
  const SeamProbe plain = probe(twoRedsEndToEnd());
  EXPECT_GT(plain.bins, 150);  // about a pixel each along 0.6 m at 1.5 m
  EXPECT_FALSE(plain.seam_possible) << plain.strongest;
}

TEST(SeamProbe, AFaintGrooveOrLineAcrossTheFaceIsAPossibleSeam)
{
  // Both as faint as seams the tiler confirms (test_face_tiling: a 1.5 mm
  // groove, a line of a few grey levels in a dim light).
  test::TouchingPlatesScene grooved = twoRedsEndToEnd();
  grooved.groove_depth_m = 0.0015;
  const SeamProbe groove = probe(grooved);
  EXPECT_TRUE(groove.seam_possible) << groove.strongest;

  test::TouchingPlatesScene lined = twoRedsEndToEnd();
  lined.line_darkening = 8.0;
  lined.line_half_width_m = 0.002;
  const SeamProbe line = probe(lined);
  EXPECT_TRUE(line.seam_possible) << line.strongest;
}

TEST(SeamProbe, ItLocatesTheSeamWhereTheBricksMeet)
{
  test::TouchingPlatesScene grooved = twoRedsEndToEnd();
  grooved.groove_depth_m = 0.0015;
  const SeamProbe groove = probe(grooved);
  ASSERT_TRUE(groove.located);
  EXPECT_NEAR(groove.length_m, 0.6, 1e-6);
  // The reds meet 0.3 m from corner 0; a dip spreads over a bin or two.
  ASSERT_FALSE(groove.possible_seams_m.empty()) << groove.strongest;
  for (const double at_m : groove.possible_seams_m) EXPECT_NEAR(at_m, 0.3, 0.01);

  const SeamProbe plain = probe(twoRedsEndToEnd());
  EXPECT_TRUE(plain.located);
  EXPECT_TRUE(plain.possible_seams_m.empty());
}

TEST(SeamProbe, ItReadsAlongTheLongEdgeWhicheverCornerStartsIt)
{
  test::TouchingPlatesScene grooved = twoRedsEndToEnd();
  grooved.groove_depth_m = 0.0015;
  const RgbdFrame frame = grooved.frame();
  const std::vector<Segment> segments = HsvSegmenter().segment(frame, BrickCatalogue::mbzirc2020());
  ASSERT_EQ(segments.size(), 1u);
  // Corner 0 to 1 now runs across the face (0.2 m); 1 to 2 along it.
  BrickCandidate face = measuredFace(grooved);
  const std::array<Eigen::Vector3d, 4> corners_m = face.corners_m;
  face.corners_m = {corners_m[3], corners_m[0], corners_m[1], corners_m[2]};
  const SeamProbe groove = probeSeamsAcross(frame, segments[0], face, 6.0, 0.0008);
  ASSERT_TRUE(groove.located);
  EXPECT_NEAR(groove.length_m, 0.6, 1e-6);
  EXPECT_EQ(groove.end_edges[0], 0);
  EXPECT_EQ(groove.end_edges[1], 2);
  ASSERT_FALSE(groove.possible_seams_m.empty()) << groove.strongest;
  for (const double at_m : groove.possible_seams_m) EXPECT_NEAR(at_m, 0.3, 0.01);
}

TEST(SeamProbe, ABrickMayLieOnlyBetweenSeenEndsAndSeamsItsLengthApart)
{
  SeamProbe strip;
  strip.located = true;
  strip.length_m = 0.5;
  strip.possible_seams_m = {0.2};
  const std::vector<double> red_m{0.3, 0.2};
  // Corner 1's end seen: 0.3 m to the seam, a red's length.
  EXPECT_TRUE(seamsMayBoundABrick(strip, {{false, true}}, red_m, 0.05));
  // Only corner 0's end seen: 0.2 m to the seam, a red's width.
  EXPECT_TRUE(seamsMayBoundABrick(strip, {{true, false}}, red_m, 0.05));
  EXPECT_FALSE(seamsMayBoundABrick(strip, {{true, false}}, {0.3}, 0.05));
  // Neither end seen, one seam: nothing bounds a brick.
  EXPECT_FALSE(seamsMayBoundABrick(strip, {{false, false}}, red_m, 0.05));
  // Two seams a length apart bound one between them.
  strip.possible_seams_m = {0.1, 0.4};
  EXPECT_TRUE(seamsMayBoundABrick(strip, {{false, false}}, {0.3}, 0.05));
  // Where the probe could not locate its seams, the tiler decides.
  strip.located = false;
  strip.possible_seams_m.clear();
  EXPECT_TRUE(seamsMayBoundABrick(strip, {{false, false}}, red_m, 0.05));
}

TEST(SeamProbe, AStripTooShortToReadLeavesTheSeamPossible)
{
  const test::TouchingPlatesScene scene = twoRedsEndToEnd();
  BrickCandidate face = measuredFace(scene);
  // A square of 1 cm: either edge too short to read.
  const Eigen::Vector3d along = (face.corners_m[1] - face.corners_m[0]).normalized();
  const Eigen::Vector3d across = (face.corners_m[3] - face.corners_m[0]).normalized();
  face.corners_m = {face.corners_m[0], face.corners_m[0] + 0.01 * along,
                    face.corners_m[0] + 0.01 * (along + across), face.corners_m[0] + 0.01 * across};
  const RgbdFrame frame = scene.frame();
  const std::vector<Segment> segments = HsvSegmenter().segment(frame, BrickCatalogue::mbzirc2020());
  ASSERT_EQ(segments.size(), 1u);
  const SeamProbe short_strip = probeSeamsAcross(frame, segments[0], face, 6.0, 0.0008);
  EXPECT_TRUE(short_strip.seam_possible);
  EXPECT_FALSE(short_strip.located);
}
}  // namespace
}  // namespace brick_pose
