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

TEST(SeamProbe, AStripTooShortToReadLeavesTheSeamPossible)
{
  const test::TouchingPlatesScene scene = twoRedsEndToEnd();
  BrickCandidate face = measuredFace(scene);
  face.corners_m[1] = face.corners_m[0] + 0.01 * (face.corners_m[1] - face.corners_m[0]).normalized();
  const RgbdFrame frame = scene.frame();
  const std::vector<Segment> segments = HsvSegmenter().segment(frame, BrickCatalogue::mbzirc2020());
  ASSERT_EQ(segments.size(), 1u);
  const SeamProbe short_strip = probeSeamsAcross(frame, segments[0], face, 6.0, 0.0008);
  EXPECT_TRUE(short_strip.seam_possible);
}
}  // namespace
}  // namespace brick_pose
