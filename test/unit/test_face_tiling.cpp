// Touching bricks merged into one planar segment, cut apart by tiling the
// segment with catalogue sizes along the seams the image shows.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "brick_pose/common/errors.h"
#include "brick_pose/eval/candidate_matching.h"
#include "brick_pose/eval/rig_truth.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/roi/cell_counts.h"
#include "brick_pose/roi/face_tiling.h"
#include "brick_pose/roi/plane_pixel_samples.h"
#include "brick_pose/segmentation/hsv_segmenter.h"
#include "brick_pose/sim/d415_modes.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"
#include "bench_frame.h"
#include "synthetic_plate_scene.h"
#include "touching_plates_scene.h"

namespace brick_pose
{
namespace
{
test::TouchingPlatesScene rowScene(int count, double length_m, double width_m)
{
  test::TouchingPlatesScene scene;
  scene.camera = test::PlateScene::vgaCamera();
  scene.origin_m = Eigen::Vector3d(0.02, -0.01, 1.5);
  scene.rotation = test::TouchingPlatesScene::facingCamera(0.35, 0.4);
  scene.plates = test::TouchingPlatesScene::row(count, length_m, width_m);
  return scene;
}

/// The candidate nearest (centre) to each plate, and the largest corner error.
double worstCornerErrorM(const std::vector<BrickCandidate>& candidates, const test::TouchingPlatesScene& scene)
{
  double worst = 0.0;
  for (const auto& plate : scene.plates)
  {
    const auto truth = scene.cornersM(plate);
    const Eigen::Vector3d centre = 0.25 * (truth[0] + truth[1] + truth[2] + truth[3]);
    const BrickCandidate* nearest = nullptr;
    for (const BrickCandidate& c : candidates)
      if (!nearest || (c.centroid_m - centre).norm() < (nearest->centroid_m - centre).norm()) nearest = &c;
    if (!nearest) return 1e9;
    for (const auto& corner : truth)
    {
      double best = 1e9;
      for (const auto& c : nearest->corners_m) best = std::min(best, (c - corner).norm());
      worst = std::max(worst, best);
    }
  }
  return worst;
}

/// `count` candidates, each a complete `type_name`, their corners within
/// 1.5 cm of the scene's plates.
void expectWholeBricks(const FrontEndResult& result, const test::TouchingPlatesScene& scene, std::size_t count,
                       const std::string& type_name)
{
  ASSERT_EQ(result.candidates.size(), count);
  for (const BrickCandidate& c : result.candidates)
  {
    EXPECT_EQ(c.type_name, type_name);
    EXPECT_TRUE(c.complete) << c.partial_reason;
  }
  EXPECT_LT(worstCornerErrorM(result.candidates, scene), 0.015);
}

/// Plain plates whose seams and outer rims are dark lines 2 mm wide, 40
/// grey levels darker (the rounded edges of plain bricks: shading, which
/// darkens each channel in proportion to the plate's colour).
void darkenSeamsAndRims(test::TouchingPlatesScene& scene)
{
  scene.line_darkening = 40.0;
  scene.rim_darkening = 40.0;
  scene.line_half_width_m = 0.002;
  scene.lines_are_shading = true;
}

/// Two plain greens side by side, dark seams and rims, the layer's depth
/// fattened `fattening_m` over its steps.
test::TouchingPlatesScene fattenedGreens(double fattening_m)
{
  test::TouchingPlatesScene scene = rowScene(2, 0.6, 0.2);
  for (auto& plate : scene.plates) plate.rgb = cv::Vec3b(200, 60, 50);
  darkenSeamsAndRims(scene);
  scene.fattening_m = fattening_m;
  return scene;
}

/// A front end without colour: region growing, types told by size.
FrontEndParams colourFreeParams()
{
  FrontEndParams params;
  params.mode = SegmentationMode::kRegionGrowing;
  return params;
}

/// The union of the plates measured as one face: plane and outer corners.
BrickCandidate measuredUnion(const test::TouchingPlatesScene& scene)
{
  BrickCandidate measured;
  measured.plane.centroid_m = scene.origin_m;
  measured.plane.normal = scene.rotation.col(2);
  measured.plane.rms_m = scene.depth_noise_m;
  measured.plane.valid = true;
  Eigen::Vector2d low(1e9, 1e9), high(-1e9, -1e9);
  for (const auto& plate : scene.plates)
  {
    low = low.cwiseMin(plate.min_m);
    high = high.cwiseMax(plate.max_m);
  }
  measured.corners_m = {scene.toCamera(low.x(), high.y()), scene.toCamera(high.x(), high.y()),
                        scene.toCamera(high.x(), low.y()), scene.toCamera(low.x(), low.y())};
  return measured;
}

/// Three greens side by side with faint 2 mm grooves between them, which
/// the HSV segmenter sees as one colour blob: the row the tiling tests cut.
struct GroovedGreenRow
{
  static test::TouchingPlatesScene groovedScene()
  {
    test::TouchingPlatesScene scene = rowScene(3, 0.6, 0.2);
    scene.groove_depth_m = 0.002;
    return scene;
  }

  test::TouchingPlatesScene scene = groovedScene();
  RgbdFrame frame = scene.frame();
  BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  std::vector<Segment> segments = HsvSegmenter().segment(frame, catalogue);
};

TEST(FaceTiling, ThreeGreensSideBySideWithFaintGroovesAreThreeTiles)
{
  const GroovedGreenRow row;
  ASSERT_EQ(row.segments.size(), 1u) << "one colour blob for the whole row";
  const FaceTiling tiling = tileFace(row.frame, row.segments[0], measuredUnion(row.scene),
                                     {&row.catalogue.at("green")}, 0.03, FaceTilingParams(), EdgeEvidenceParams());
  ASSERT_EQ(tiling.tiles.size(), 3u);
  EXPECT_EQ(tiling.seen_cuts, tiling.cuts);
  EXPECT_GE(tiling.cuts, 2);
  EXPECT_LT(tiling.untiled_fraction, 0.05);
  for (const FaceTile& tile : tiling.tiles)
  {
    EXPECT_EQ(tile.type_name, "green");
    EXPECT_NEAR((tile.corners_m[1] - tile.corners_m[0]).norm() + (tile.corners_m[2] - tile.corners_m[1]).norm(), 0.8,
                0.02);
    EXPECT_GT(tile.segment.area_px, 0);
  }
}

// The two directions of the seam evidence are read on two threads from
// pixels made before them: the tiling must not depend on the thread count
// (a check of determinism; the sanitizer build is not ThreadSanitizer).
TEST(FaceTiling, SeamEvidenceReadOnTwoThreadsTilesAsOnOne)
{
  const GroovedGreenRow row;
  ASSERT_EQ(row.segments.size(), 1u);
  FaceTilingParams two_threads;
  two_threads.worker_threads = 2;
  const std::vector<const BrickType*> types{&row.catalogue.at("green"), &row.catalogue.at("red")};
  const FaceTiling one = tileFace(row.frame, row.segments[0], measuredUnion(row.scene), types, 0.03,
                                  FaceTilingParams(), EdgeEvidenceParams());
  const FaceTiling two = tileFace(row.frame, row.segments[0], measuredUnion(row.scene), types, 0.03, two_threads,
                                  EdgeEvidenceParams());
  ASSERT_EQ(one.tiles.size(), 3u);
  ASSERT_EQ(two.tiles.size(), one.tiles.size());
  EXPECT_EQ(two.cuts, one.cuts);
  EXPECT_EQ(two.seen_cuts, one.seen_cuts);
  EXPECT_EQ(two.grooved_cuts, one.grooved_cuts);
  EXPECT_EQ(two.untiled_fraction, one.untiled_fraction);
  for (std::size_t k = 0; k < one.tiles.size(); ++k)
  {
    EXPECT_EQ(two.tiles[k].type_name, one.tiles[k].type_name);
    EXPECT_EQ(two.tiles[k].seam_seen, one.tiles[k].seam_seen);
    for (int c = 0; c < 4; ++c) EXPECT_EQ((two.tiles[k].corners_m[c] - one.tiles[k].corners_m[c]).norm(), 0.0);
    EXPECT_EQ(two.tiles[k].segment.area_px, one.tiles[k].segment.area_px);
  }
}

TEST(FaceTiling, TileSegmentsAreCutOnlyForTheTilingKept)
{
  const GroovedGreenRow row;
  ASSERT_EQ(row.segments.size(), 1u);
  const std::vector<const BrickType*> greens{&row.catalogue.at("green")};
  std::vector<FaceTiling> compared =
      tileFaceEach(row.frame, row.segments[0], measuredUnion(row.scene), {greens, greens}, 0.03,
                   FaceTilingParams(), EdgeEvidenceParams(),
                   [](std::size_t, const std::vector<FaceTiling>&) { return true; });
  ASSERT_EQ(compared.size(), 2u);
  ASSERT_EQ(compared[0].tiles.size(), 3u);
  for (const FaceTile& tile : compared[0].tiles) EXPECT_EQ(tile.segment.area_px, 0) << "cut before one is kept";
  cutTileSegments(row.frame, row.segments[0], compared[0]);
  const FaceTiling kept = tileFace(row.frame, row.segments[0], measuredUnion(row.scene), greens, 0.03,
                                   FaceTilingParams(), EdgeEvidenceParams());
  ASSERT_EQ(kept.tiles.size(), 3u);
  int tiled_px = 0;
  for (std::size_t k = 0; k < kept.tiles.size(); ++k)
  {
    EXPECT_GT(compared[0].tiles[k].segment.area_px, 0);
    EXPECT_EQ(compared[0].tiles[k].segment.area_px, kept.tiles[k].segment.area_px);
    EXPECT_EQ(compared[0].tiles[k].segment.bounding_box_px, kept.tiles[k].segment.bounding_box_px);
    tiled_px += kept.tiles[k].segment.area_px;
  }
  // Neighbouring tiles may share the pixels their common edge runs through.
  EXPECT_GT(tiled_px, 0.9 * row.segments[0].area_px);
  EXPECT_LT(tiled_px, 1.05 * row.segments[0].area_px);
}

TEST(FaceTiling, TouchingRowWithSeamsGivesCompleteBricksInHsvMode)
{
  test::TouchingPlatesScene scene = rowScene(3, 0.6, 0.2);
  scene.groove_depth_m = 0.002;
  scene.line_darkening = 40.0;
  const FrontEndResult result = FrontEnd(BrickCatalogue::mbzirc2020()).process(scene.frame());
  ASSERT_EQ(result.candidates.size(), 3u);
  for (const BrickCandidate& c : result.candidates)
  {
    EXPECT_EQ(c.type_name, "green");
    EXPECT_NEAR(c.length_m, 0.6, 0.015);
    EXPECT_NEAR(c.width_m, 0.2, 0.015);
    EXPECT_TRUE(c.complete) << c.partial_reason;
    EXPECT_TRUE(c.partial_reason.empty());
  }
  EXPECT_LT(worstCornerErrorM(result.candidates, scene), 0.015);
}

TEST(FaceTiling, CutsWithoutASeenSeamArePartialWithTheReason)
{
  // No groove and no line: the sizes still tile the row, but the cuts are
  // guesses, so no brick may claim to be whole.
  test::TouchingPlatesScene scene = rowScene(3, 0.6, 0.2);
  const FrontEndResult result = FrontEnd(BrickCatalogue::mbzirc2020()).process(scene.frame());
  ASSERT_EQ(result.candidates.size(), 3u);
  int middle = 0;
  for (const BrickCandidate& c : result.candidates)
  {
    EXPECT_FALSE(c.complete);
    EXPECT_FALSE(c.partial_reason.empty());
    EXPECT_NE(c.partial_reason.find("continues on the same plane"), std::string::npos) << c.partial_reason;
    int mask_edges = 0;
    for (const EdgeKind kind : c.edge_kinds) mask_edges += kind == EdgeKind::kMaskEdge ? 1 : 0;
    middle += mask_edges == 2 ? 1 : 0;
  }
  EXPECT_EQ(middle, 1) << "the middle brick has two guessed edges";
}

TEST(FaceTiling, ColourFreeTwoRedsEndToEndWithASeamAreNotOneGreen)
{
  // 0.6 x 0.2 is a green's top; a dark seam across its middle says two reds.
  test::TouchingPlatesScene scene = rowScene(1, 0.6, 0.2);
  scene.plates = {{{-0.3, -0.1}, {0.0, 0.1}, {140, 120, 90}}, {{0.0, -0.1}, {0.3, 0.1}, {140, 120, 90}}};
  scene.line_darkening = 50.0;
  scene.groove_depth_m = 0.002;
  const FrontEndParams params = colourFreeParams();
  const FrontEndResult result = FrontEnd(BrickCatalogue::mbzirc2020(), params).process(scene.frame());
  ASSERT_EQ(result.candidates.size(), 2u);
  for (const BrickCandidate& c : result.candidates)
  {
    EXPECT_EQ(c.type_name, "red");
    EXPECT_NEAR(c.length_m, 0.3, 0.02);
  }
  // Without the seam it is one green.
  scene.line_darkening = 0.0;
  scene.groove_depth_m = 0.0;
  const FrontEndResult plain = FrontEnd(BrickCatalogue::mbzirc2020(), params).process(scene.frame());
  ASSERT_EQ(plain.candidates.size(), 1u);
  EXPECT_EQ(plain.candidates[0].type_name, "green");
}

/// A white label with a barcode painted over the layer-frame rectangle
/// [min_m, max_m] of `scene` in `frame`'s colour image (print: the depth
/// does not see it).
void paintLabel(RgbdFrame& frame, const test::TouchingPlatesScene& scene, const Eigen::Vector2d& min_m,
                const Eigen::Vector2d& max_m)
{
  auto pixel = [&](double x_m, double y_m) {
    const Eigen::Vector2d uv = scene.camera.project(scene.toCamera(x_m, y_m));
    return cv::Point(static_cast<int>(std::lround(uv.x())), static_cast<int>(std::lround(uv.y())));
  };
  auto fill = [&](double x0, double y0, double x1, double y1, const cv::Scalar& colour) {
    const std::vector<cv::Point> corners{pixel(x0, y0), pixel(x1, y0), pixel(x1, y1), pixel(x0, y1)};
    cv::fillConvexPoly(frame.rgb, corners, colour);
  };
  fill(min_m.x(), min_m.y(), max_m.x(), max_m.y(), cv::Scalar(235, 235, 235));
  // Bars 4 mm wide every 8 mm across the label's middle third.
  const double y0 = min_m.y() + (max_m.y() - min_m.y()) / 3.0, y1 = max_m.y() - (max_m.y() - min_m.y()) / 3.0;
  for (double x = min_m.x() + 0.01; x + 0.004 < max_m.x() - 0.01; x += 0.008) fill(x, y0, x + 0.004, y1, cv::Scalar(30, 30, 30));
}

TEST(FaceTiling, ColourFreeLabelledRedsEndToEndAreCutWhereTheCardboardAroundTheirSeamIsPlain)
{
  // Two reds end to end make a green's top, their seam a clear line with no
  // groove (a closed seam the D4xx smooths). Each carries a label, so
  // neither is plain: a line on a printed face may be print. But the face
  // around the line, 5 cm either side, is plain: the line is no print, and
  // the face is two reds.
  test::TouchingPlatesScene scene = rowScene(1, 0.6, 0.2);
  scene.plates = {{{-0.3, -0.1}, {0.0, 0.1}, {140, 120, 90}}, {{0.0, -0.1}, {0.3, 0.1}, {140, 120, 90}}};
  scene.line_darkening = 50.0;
  const FrontEndParams params = colourFreeParams();
  RgbdFrame frame = scene.frame();
  paintLabel(frame, scene, {-0.24, -0.06}, {-0.12, 0.06});
  paintLabel(frame, scene, {0.12, -0.06}, {0.24, 0.06});
  const FrontEndResult labelled = FrontEnd(BrickCatalogue::mbzirc2020(), params).process(frame);
  ASSERT_EQ(labelled.candidates.size(), 2u);
  for (const BrickCandidate& c : labelled.candidates)
  {
    EXPECT_EQ(c.type_name, "red");
    EXPECT_NEAR(c.length_m, 0.3, 0.02);
  }
  // A label 2 cm from the line: the line may be print, and the face stays one
  // green in doubt.
  RgbdFrame near_line = scene.frame();
  paintLabel(near_line, scene, {-0.24, -0.06}, {-0.12, 0.06});
  paintLabel(near_line, scene, {0.02, -0.06}, {0.14, 0.06});
  const FrontEndResult doubted = FrontEnd(BrickCatalogue::mbzirc2020(), params).process(near_line);
  ASSERT_EQ(doubted.candidates.size(), 1u);
  EXPECT_EQ(doubted.candidates[0].type_name, "green");
  EXPECT_FALSE(doubted.candidates[0].complete);
}

TEST(FaceTiling, TwoLabelledBoxesSideBySideOnAStackAreNotOneLargeBox)
{
  // Pallet stack 169 at 640x480: two box_small side by side on a stack,
  // 0.40 x 0.30 m together (a box_large's top), both labelled, their seam a
  // clear line through plain cardboard. They were one box_large in doubt,
  // "mixed" over the two; now each is found whole as a box_small.
  const BrickCatalogue boxes = BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/boxes.yaml");
  const test::BenchFrameRun run = test::runBenchFrame(boxes, test::kPalletStackClass, 169, "640x480");
  const eval::SceneTruth truth = eval::rigSceneTruth(run.rendered, run.up_in_camera);
  const eval::FrameMatch match = eval::matchCandidates(run.result.candidates, truth, run.rendered.camera);
  int mixed_large = 0, small_tops = 0;
  for (std::size_t c = 0; c < match.candidates.size(); ++c)
  {
    const eval::CandidateMatch& candidate_match = match.candidates[c];
    EXPECT_FALSE(candidate_match.false_complete);
    const std::string& type = run.result.candidates[c].type_name;
    mixed_large += type == "box_large" && candidate_match.outcome == eval::CandidateOutcome::kMixed ? 1 : 0;
    small_tops += type == "box_small" && candidate_match.outcome == eval::CandidateOutcome::kWholeTop ? 1 : 0;
  }
  EXPECT_EQ(mixed_large, 0);
  EXPECT_GE(small_tops, 2);
}

TEST(FaceTiling, TheBarsOfALabelAreNoSeam)
{
  // Pallet layer 148 at 1280x720, in a low light: a box_small was laid
  // half a box off, across the seam of two boxes, its cut along the dark
  // bars of a barcode (parallel to the box's edges); the two halves left
  // could take no box. Bars on white paper are print: all 12 whole tops.
  // (Release build only, in scripts/sanitize.sh: the sanitizer build's
  // clang renders another scene from the frame's seed, with 6 whole tops.)
  const test::WholeTops tops = test::palletLayerBenchFrame(148, "1280x720");
  EXPECT_EQ(tops.whole, 12);
  EXPECT_EQ(tops.found, tops.whole);
}

TEST(FaceTiling, ColourFreeGreenSizedFaceWithAFaintLineWhereTwoRedsWouldMeetIsPartial)
{
  // A closed seam between two reds: no groove, and a line of 10 grey levels
  // that the tiler does not cut on. It is no proof of two reds, but a whole
  // green shows nothing there: green, partial, not complete.
  test::TouchingPlatesScene scene = rowScene(1, 0.6, 0.2);
  scene.plates = {{{-0.3, -0.1}, {0.0, 0.1}, {140, 120, 90}}, {{0.0, -0.1}, {0.3, 0.1}, {140, 120, 90}}};
  scene.line_darkening = 10.0;
  const FrontEndParams params = colourFreeParams();
  const FrontEndResult faint = FrontEnd(BrickCatalogue::mbzirc2020(), params).process(scene.frame());
  ASSERT_EQ(faint.candidates.size(), 1u);
  EXPECT_EQ(faint.candidates[0].type_name, "green");
  EXPECT_FALSE(faint.candidates[0].complete);
  EXPECT_NE(faint.candidates[0].partial_reason.find("smaller catalogue tops"), std::string::npos)
      << faint.candidates[0].partial_reason;
  // Nothing there: a whole green.
  scene.line_darkening = 0.0;
  const FrontEndResult plain = FrontEnd(BrickCatalogue::mbzirc2020(), params).process(scene.frame());
  ASSERT_EQ(plain.candidates.size(), 1u);
  EXPECT_TRUE(plain.candidates[0].complete) << plain.candidates[0].partial_reason;
}

/// The colour_free front end on bench_frontend's touching-rows frame `frame`
/// (seed, lighting, the ground given as support, as the benchmark sets them).
FrontEndResult touchingRowsBenchFrame(int frame, const std::string& resolution, std::size_t expected_bricks)
{
  const test::BenchFrameRun run =
      test::runBenchFrame(BrickCatalogue::mbzirc2020(), test::kTouchingRowsClass, frame, resolution);
  EXPECT_EQ(run.scene.bricks.size(), expected_bricks);
  return run.result;
}

TEST(FaceTiling, ALineTooCloseToAnEdgeForABrickBeyondItIsNoEdge)
{
  // Touching rows frame 120 (1280x720, low light): four reds end to end
  // make a blue's top. Along the first red, 2 cm inside its long edge, the
  // simulated D4xx depth draws a line the tiler took for that red's edge:
  // the strip beyond it, 3 cm to the segment's end, was left a cut with no
  // seam seen, and the four were one blue in doubt. No brick fits a strip
  // wider than a fattening fringe and narrower than any brick, so such a
  // line is no cut, and the red ends at the segment's end.
  const FrontEndResult result = touchingRowsBenchFrame(120, "1280x720", 4u);
  ASSERT_EQ(result.candidates.size(), 4u);
  for (const BrickCandidate& c : result.candidates)
  {
    EXPECT_EQ(c.type_name, "red");
    EXPECT_TRUE(c.complete) << c.partial_reason;
  }
}

TEST(FaceTiling, AZOfTwoRedsSideBySideIsCutAlongTheLineTheyShare)
{
  // Touching rows frame 122 (848x480): two reds side by side, offset 14 cm
  // along their length, a Z. Each tile is anchored at the line they share
  // (its anchor slid along the outline to the first untiled cells), so
  // neither made that line a cut, the tiling had no cut, and the Z was
  // refused as filling too little of its quad. Read as a cut of both, the
  // seam gives the reds; the one whose edge there also runs along the
  // ground is partial (its edge test sees no seam along the whole edge).
  const FrontEndResult result = touchingRowsBenchFrame(122, "848x480", 2u);
  ASSERT_EQ(result.candidates.size(), 2u);
  int complete = 0;
  for (const BrickCandidate& c : result.candidates)
  {
    EXPECT_EQ(c.type_name, "red");
    complete += c.complete ? 1 : 0;
  }
  EXPECT_GE(complete, 1);
}

TEST(FaceTiling, AZOfTwoRedsWithARaggedOutlineIsTiledAlongTheBricks)
{
  // The same Z at 640x480 in sunlight: its outline so ragged that its sides
  // did not stand out (see OutlineAxis.ARaggedOutlineStillGivesItsAxis), and
  // the tiling on the quad's axes, 5 degrees off the bricks, fitted one red.
  const FrontEndResult result = touchingRowsBenchFrame(122, "640x480", 2u);
  ASSERT_EQ(result.candidates.size(), 2u);
  for (const BrickCandidate& c : result.candidates) EXPECT_EQ(c.type_name, "red");
}

TEST(FaceTiling, ALayerIsAnchoredWhereItEndsThoughItsGridSidesTouchItNowhere)
{
  // bench_frontend's pallet-layer frame 146 (sunlight, colour-free, VGA).
  // The grid spans the quad's corners on the outline's axes; where the quad
  // lies askew of them, the grid's sides touch the layer nowhere and no
  // tile could start at its outer corners: the tiling stopped early, and
  // 6 of the frame's 11 whole tops were found (9 with the lines where the
  // layer starts and ends).
  const test::WholeTops tops = test::palletLayerBenchFrame(146, "640x480");
  ASSERT_GE(tops.whole, 10) << "the frame's layout";
  EXPECT_GE(tops.found, 8) << tops.found << " of " << tops.whole << " whole tops found";
}

TEST(FaceTiling, MixedLayerOfAGreenAndTwoRedsIsTiledWithBothSizes)
{
  test::TouchingPlatesScene scene = rowScene(1, 0.6, 0.2);
  const cv::Vec3b cardboard(140, 120, 90);
  scene.plates = {{{-0.3, -0.2}, {0.3, 0.0}, cardboard},
                  {{-0.3, 0.0}, {0.0, 0.2}, cardboard},
                  {{0.0, 0.0}, {0.3, 0.2}, cardboard}};
  scene.line_darkening = 50.0;
  scene.groove_depth_m = 0.002;
  const FrontEndParams params = colourFreeParams();
  const FrontEndResult result = FrontEnd(BrickCatalogue::mbzirc2020(), params).process(scene.frame());
  ASSERT_EQ(result.candidates.size(), 3u);
  int reds = 0, greens = 0;
  for (const BrickCandidate& c : result.candidates)
  {
    reds += c.type_name == "red" ? 1 : 0;
    greens += c.type_name == "green" ? 1 : 0;
  }
  EXPECT_EQ(reds, 2);
  EXPECT_EQ(greens, 1);
  EXPECT_LT(worstCornerErrorM(result.candidates, scene), 0.02);
}

TEST(FaceTiling, OffsetBricksEndToEndAreTiledAlongTheirOwnAxes)
{
  // Two reds end to end, the second moved half its width sideways: a
  // Z-shaped outline whose least-area quad is a parallelogram tilted 18
  // degrees from the bricks, on whose axes no red fits (checked: no tile
  // at all on the quad's axes).
  test::TouchingPlatesScene scene = rowScene(1, 0.3, 0.2);
  const cv::Vec3b red(200, 30, 30);
  scene.plates = {{{-0.3, -0.1}, {0.0, 0.1}, red}, {{0.0, 0.0}, {0.3, 0.2}, red}};
  scene.line_darkening = 40.0;
  scene.groove_depth_m = 0.002;
  const FrontEndResult result = FrontEnd(BrickCatalogue::mbzirc2020()).process(scene.frame());
  ASSERT_EQ(result.candidates.size(), 2u);
  for (const BrickCandidate& c : result.candidates) EXPECT_EQ(c.type_name, "red");
  EXPECT_LT(worstCornerErrorM(result.candidates, scene), 0.02);
}

/// Dark print on each plate (a label and two stripes), as on a printed box.
void printOnPlates(const test::TouchingPlatesScene& scene, RgbdFrame& frame)
{
  for (const auto& plate : scene.plates)
  {
    const Eigen::Vector2d size = plate.max_m - plate.min_m;
    auto pixel = [&](double fx, double fy) {
      const Eigen::Vector2d p = scene.camera.project(
          scene.toCamera(plate.min_m.x() + fx * size.x(), plate.min_m.y() + fy * size.y()));
      return cv::Point(static_cast<int>(p.x()), static_cast<int>(p.y()));
    };
    cv::rectangle(frame.rgb, pixel(0.25, 0.3), pixel(0.5, 0.7), cv::Scalar(250, 250, 250), cv::FILLED);
    cv::line(frame.rgb, pixel(0.6, 0.3), pixel(0.6, 0.7), cv::Scalar(20, 20, 20), 3);
    cv::line(frame.rgb, pixel(0.7, 0.3), pixel(0.7, 0.7), cv::Scalar(20, 20, 20), 3);
  }
}

/// The first candidate of type `type_name`, or none.
const BrickCandidate* candidateOfType(const FrontEndResult& result, const std::string& type_name)
{
  for (const BrickCandidate& c : result.candidates)
    if (c.type_name == type_name) return &c;
  return nullptr;
}

/// The box catalogue of config/boxes.yaml.
BrickCatalogue boxCatalogue() { return BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/boxes.yaml"); }

/// A box_large top (0.4 x 0.3 m) in a layer, touching a box_small (0.3 x
/// 0.2 m) of the same `rgb` along a seam with a gap of a few mm: a real
/// edge, print or not.
test::TouchingPlatesScene largeBesideSmallScene(const cv::Vec3b& rgb)
{
  test::TouchingPlatesScene scene = rowScene(1, 0.6, 0.2);
  scene.plates = {{{-0.2, -0.3}, {0.2, 0.0}, rgb}, {{-0.15, 0.0}, {0.15, 0.2}, rgb}};
  scene.line_half_width_m = 0.002;
  scene.groove_depth_m = 0.005;
  return scene;
}

int completeCount(const FrontEndResult& result)
{
  int complete = 0;
  for (const BrickCandidate& c : result.candidates) complete += c.complete ? 1 : 0;
  return complete;
}

TEST(FaceTiling, ColourFreeTouchingBricksAreCutAtDarkSeamsAndCompleteWhenPlain)
{
  // Three greens side by side: a 0.6 m square that no catalogue top has.
  // Their seams are closed: no groove (a D4xx smooths it away), only the
  // dark line of the rounded edges.
  test::TouchingPlatesScene scene = rowScene(3, 0.6, 0.2);
  for (auto& plate : scene.plates) plate.rgb = cv::Vec3b(200, 60, 50);
  scene.line_darkening = 40.0;
  scene.line_half_width_m = 0.002;  // two rounded edges of 2 mm
  const FrontEndParams params = colourFreeParams();
  const FrontEnd front_end(BrickCatalogue::mbzirc2020(), params);
  const FrontEndResult seamed = front_end.process(scene.frame());
  ASSERT_NO_FATAL_FAILURE(expectWholeBricks(seamed, scene, 3u, "green"));

  // The same face printed: a line is no seam there. Cut or not, no brick
  // may claim to be whole.
  RgbdFrame printed = scene.frame();
  printOnPlates(scene, printed);
  const FrontEndResult on_print = front_end.process(printed);
  EXPECT_EQ(completeCount(on_print), 0);
  for (const BrickCandidate& c : on_print.candidates) EXPECT_FALSE(c.partial_reason.empty());

  // Nothing seen where they meet: no cut, nothing complete.
  scene.line_darkening = 0.0;
  EXPECT_EQ(completeCount(front_end.process(scene.frame())), 0);
}

TEST(FaceTiling, ColourFreeTouchingBricksAreCutAtFaintSeamsInADimLight)
{
  // The same three greens in a dim light (mean grey 62): their seams are 8
  // grey levels under 3 levels of pixel noise. Along a 0.6 m cut that is
  // many standard errors (the error of the mean is a fraction of a level),
  // and 8 levels is as deep as a seam is in that light.
  test::TouchingPlatesScene scene = rowScene(3, 0.6, 0.2);
  for (auto& plate : scene.plates) plate.rgb = cv::Vec3b(120, 36, 30);
  scene.background_rgb = cv::Vec3b(60, 58, 55);
  scene.line_darkening = 8.0;
  scene.line_half_width_m = 0.003;
  scene.colour_noise = 3.0;
  const FrontEnd front_end(BrickCatalogue::mbzirc2020(), colourFreeParams());
  const FrontEndResult faint = front_end.process(scene.frame());
  ASSERT_NO_FATAL_FAILURE(expectWholeBricks(faint, scene, 3u, "green"));
}

/// `count` plain plates of `length_m` x 0.2 m in a low light (mean grey 27),
/// their seams lines `line_darkening` grey levels dark under 2 levels of
/// pixel noise.
test::TouchingPlatesScene lowLightRow(int count, double length_m, double line_darkening)
{
  test::TouchingPlatesScene scene = rowScene(count, length_m, 0.2);
  for (auto& plate : scene.plates) plate.rgb = cv::Vec3b(40, 24, 18);
  scene.background_rgb = cv::Vec3b(20, 19, 18);
  scene.line_darkening = line_darkening;
  scene.line_half_width_m = 0.003;
  scene.colour_noise = 2.0;
  return scene;
}

TEST(FaceTiling, ColourFreeBlueSizedFaceOfFourRedsInALowLightIsCutAtClearLines)
{
  // Four reds end to end make a blue's top. In a low light their seams draw
  // lines of 6 grey levels on a face of grey 27: as clear a share of its
  // light as 15 levels are of a face in normal light.
  const test::TouchingPlatesScene scene = lowLightRow(1, 1.2, 6.0);
  test::TouchingPlatesScene reds = scene;
  reds.plates.clear();
  for (int k = 0; k < 4; ++k)
    reds.plates.push_back({{-0.6 + 0.3 * k, -0.1}, {-0.3 + 0.3 * k, 0.1}, scene.plates.front().rgb});
  const FrontEnd front_end(BrickCatalogue::mbzirc2020(), colourFreeParams());
  ASSERT_NO_FATAL_FAILURE(expectWholeBricks(front_end.process(reds.frame()), reds, 4u, "red"));

  // Lines of 3 levels (11 % of the light) are seen but no proof of four
  // reds: one blue, and not complete.
  reds.line_darkening = 3.0;
  const FrontEndResult faint = front_end.process(reds.frame());
  EXPECT_EQ(completeCount(faint), 0);
  for (const BrickCandidate& c : faint.candidates) EXPECT_FALSE(c.partial_reason.empty());
}

/// Seams as shading (mean grey levels) and every channel's own noise (grey
/// levels), for dim red plates (mean grey 37). Read in the mean of the
/// channels these seams were no clear cut; read in the plates' own colour
/// they are.
constexpr double kSeamShading = 11.0;
constexpr double kChannelNoise = 12.0;

TEST(FaceTiling, ColourFreeRedsInALowLightAreCutAtSeamsTheirOwnColourShows)
{
  // Four dim red plates end to end (a blue's top). Their seams are shading:
  // a share of what each channel reflects, so the red channel alone holds
  // them, under noise of its own in every channel. Read in the mean of the
  // three channels, the line is a third of its depth in the red under the
  // green's and blue's noise as well, and no cut is clear enough to make a
  // red of; read in the plates' own colour (FaceGrey), every seam is.
  test::TouchingPlatesScene reds = lowLightRow(1, 1.2, 0.0);
  reds.plates.clear();
  for (int k = 0; k < 4; ++k) reds.plates.push_back({{-0.6 + 0.3 * k, -0.1}, {-0.3 + 0.3 * k, 0.1}, {14, 12, 84}});
  reds.line_darkening = kSeamShading;
  reds.lines_are_shading = true;
  reds.colour_noise = kChannelNoise;
  reds.noise_per_channel = true;
  const FrontEnd front_end(BrickCatalogue::mbzirc2020(), colourFreeParams());
  ASSERT_NO_FATAL_FAILURE(expectWholeBricks(front_end.process(reds.frame()), reds, 4u, "red"));

  // The cuts are the seams': with none drawn the same face is one blue.
  reds.line_darkening = 0.0;
  const FrontEndResult seamless = front_end.process(reds.frame());
  ASSERT_EQ(seamless.candidates.size(), 1u);
  EXPECT_EQ(seamless.candidates.front().type_name, "blue");
}

TEST(FaceTiling, ColourFreeTouchingBricksWithAFattenedOutlineAreCutAtTheirSeam)
{
  // Two greens side by side, their rims and their seam dark. A D4xx
  // fattens the layer's depth about a centimetre over its steps, so the
  // merged face reaches that far beyond the bricks' ends, and the line where
  // each brick really ends reads as a seam with the fringe beyond it. A cut
  // there, with nothing but the fringe beyond, is no cut between two bricks.
  const test::TouchingPlatesScene scene = fattenedGreens(0.010);
  const FrontEnd front_end(BrickCatalogue::mbzirc2020(), colourFreeParams());
  const FrontEndResult result = front_end.process(scene.frame());
  ASSERT_NO_FATAL_FAILURE(expectWholeBricks(result, scene, 2u, "green"));
}

TEST(FaceTiling, ADropoutBeyondAFattenedOutlineHidesNoNeighbour)
{
  // Two greens as above with the stereo shadow beyond their fringe: a few
  // pixels over the next 1.5 cm have no depth. A dropout there hides no
  // neighbour beyond the fringe (whose top would run at least a brick's
  // width along the cut), so the fringe is still no cut. Before, one
  // dropout kept it a cut and the bricks were refused as "cut from its
  // neighbour shows no seam" (touching rows, frame 100 in VGA). The fringe
  // is 1.04 cm so that it fills the face's last column of tiling cells, and
  // its end lies beyond the cells, as in that frame (at 1 cm the strip ends
  // within the cells and what lies beyond is not read).
  for (const unsigned seed : {3u, 4u, 5u, 6u})
  {
    test::TouchingPlatesScene scene = fattenedGreens(0.0104);
    scene.dropout_band_m = 0.015;
    scene.dropout_share = 0.05;
    scene.seed = seed;
    const FrontEnd front_end(BrickCatalogue::mbzirc2020(), colourFreeParams());
    SCOPED_TRACE("seed " + std::to_string(seed));
    ASSERT_NO_FATAL_FAILURE(expectWholeBricks(front_end.process(scene.frame()), scene, 2u, "green"));
  }
}

TEST(FaceTiling, ManyDropoutsBeyondAFattenedOutlineKeepItACut)
{
  // The same fringe with half the pixels beyond it without depth: a
  // neighbour could lie there out of sight, so the fringe stays a cut, the
  // cut shows no seam, and neither green may be published whole.
  for (const unsigned seed : {3u, 4u})
  {
    test::TouchingPlatesScene scene = fattenedGreens(0.0104);
    scene.dropout_band_m = 0.015;
    scene.dropout_share = 0.5;
    scene.seed = seed;
    SCOPED_TRACE("seed " + std::to_string(seed));
    const FrontEndResult result = FrontEnd(BrickCatalogue::mbzirc2020(), colourFreeParams()).process(scene.frame());
    for (const BrickCandidate& c : result.candidates) EXPECT_FALSE(c.complete) << c.type_name;
  }
}

TEST(FaceTiling, ARejectedTileIsReportedOverItsOwnFootprint)
{
  // The two greens above, refused one by one: each tile's reason is about
  // that tile, so it is reported over the tile's box. Before, every tile's
  // reason carried the whole merged segment's box, and the ROI nodelet's
  // log and bench_frontend's miss lines read each as the whole layer's.
  test::TouchingPlatesScene scene = fattenedGreens(0.0104);
  scene.dropout_band_m = 0.015;
  scene.dropout_share = 0.5;
  scene.seed = 3;
  const FrontEndResult result = FrontEnd(BrickCatalogue::mbzirc2020(), colourFreeParams()).process(scene.frame());
  // The two greens' parts: refused tiles and tiles kept (partial).
  std::vector<cv::Rect> refused, parts;
  for (const Rejection& rejection : result.rejections)
    if (rejection.reason.rfind("part of a split segment: cut", 0) == 0) refused.push_back(rejection.bounding_box_px);
  parts = refused;
  for (const BrickCandidate& candidate : result.candidates) parts.push_back(candidate.bounding_box_px);
  ASSERT_GE(refused.size(), 1u) << "a green refused for its unseen cut";
  ASSERT_EQ(parts.size(), 2u) << "the pair tiled into its two greens";
  // The greens lie askew: their boxes overlap, but neither is the pair's.
  const cv::Rect pair = parts[0] | parts[1];
  for (const cv::Rect& box : parts)
    EXPECT_LT(box.area(), 0.8 * pair.area()) << "each part is reported over its own green, not over the pair";
}

TEST(FaceTiling, TwoBricksOffsetEndToEndAreTiledThoughTheirQuadLeavesTheImage)
{
  // Two blues side by side, one pushed half its length along the other:
  // the merged face is a Z whose least-area quad reaches beyond the image
  // while the face itself keeps clear of the border. Those sides of the
  // quad are "at the image border"; they were taken for a face cut by it,
  // and the face was not tiled at all (touching rows, frame 113 in VGA).
  // At 1.9 and 2.6 m the quad leaves the image (at 2.1 m it does not).
  for (const double distance_m : {1.9, 2.6})
  {
    test::TouchingPlatesScene scene = rowScene(1, 1.2, 0.2);
    scene.origin_m = Eigen::Vector3d(0.0, 0.0, distance_m);
    const cv::Vec3b plain(60, 60, 200);
    scene.plates = {{{-0.9, -0.2}, {0.3, 0.0}, plain}, {{-0.3, 0.0}, {0.9, 0.2}, plain}};
    darkenSeamsAndRims(scene);
    const FrontEnd front_end(BrickCatalogue::mbzirc2020(), colourFreeParams());
    SCOPED_TRACE("distance " + std::to_string(distance_m) + " m");
    ASSERT_NO_FATAL_FAILURE(expectWholeBricks(front_end.process(scene.frame()), scene, 2u, "blue"));
  }
}

TEST(FaceTiling, StaggeredRowsAreCutWhereTheirBricksMeetAlone)
{
  // Two rows of reds end to end, the second pushed half a brick along the
  // first, as bricks are laid: the long seam between the rows runs past
  // either end of the other row, where a row's side bounds the layer. A cut
  // along a brick's side is read only where the other row lies beyond it;
  // read along the whole side, its stretch at the layer's edge hid the seam
  // (touching rows, frame 106 in VGA: two reds refused, "cut shows no seam").
  test::TouchingPlatesScene scene = rowScene(1, 0.3, 0.2);
  const cv::Vec3b plain(200, 30, 30);
  scene.plates = {{{-0.3, 0.0}, {0.0, 0.2}, plain},
                  {{0.0, 0.0}, {0.3, 0.2}, plain},
                  {{-0.15, -0.2}, {0.15, 0.0}, plain},
                  {{0.15, -0.2}, {0.45, 0.0}, plain}};
  scene.line_darkening = 40.0;
  scene.line_half_width_m = 0.002;
  RgbdFrame frame = scene.frame();
  // A floor of light and dark tiles around the layer, as the rig's.
  for (int v = 0; v < frame.height_px(); ++v)
    for (int u = 0; u < frame.width_px(); ++u)
      if (frame.depthAt(u, v) > scene.origin_m.z() + 0.1)
        frame.rgb.at<cv::Vec3b>(v, u) = ((u / 12 + v / 12) % 2 == 0) ? cv::Vec3b(90, 88, 85) : cv::Vec3b(180, 176, 170);
  const FrontEnd front_end(BrickCatalogue::mbzirc2020(), colourFreeParams());
  ASSERT_NO_FATAL_FAILURE(expectWholeBricks(front_end.process(frame), scene, 4u, "red"));
}

TEST(FaceTiling, ASeamLaidAskewOfTheTilingIsStillSeen)
{
  // Three plain greens side by side whose closed seams (no groove, only the
  // dark line of the rounded edges, 2 px wide) run askew of the row's
  // outline, as bricks laid by hand do: 6 px across over the 0.6 m seam,
  // about 1.4 degrees. Read straight along the tiling's cut, the line
  // crosses the profile's columns and no column is dark in most rows, so
  // the cut was unconfirmed and no green whole; it is now also read turned
  // by a pixel or two at each end (touching rows, frame 119 in VGA).
  test::TouchingPlatesScene scene = rowScene(3, 0.6, 0.2);
  const cv::Vec3b plain(200, 60, 50);
  for (auto& plate : scene.plates) plate.rgb = plain;
  RgbdFrame frame = scene.frame();
  for (const double seam_y_m : {-0.1, 0.1})
  {
    const Eigen::Vector2d a = scene.camera.project(scene.toCamera(-0.3, seam_y_m));
    const Eigen::Vector2d b = scene.camera.project(scene.toCamera(0.3, seam_y_m));
    cv::line(frame.rgb, cv::Point2d(a.x(), a.y() - 3.0), cv::Point2d(b.x(), b.y() + 3.0), cv::Scalar(160, 20, 10), 2);
  }
  const FrontEnd front_end(BrickCatalogue::mbzirc2020(), colourFreeParams());
  ASSERT_NO_FATAL_FAILURE(expectWholeBricks(front_end.process(frame), scene, 3u, "green"));
}

TEST(FaceTiling, ARowRunningOffTheImageIsTiledFromTheSeamsItShows)
{
  // Reds end to end in a row that runs off the image at both ends, the
  // border cutting one end brick after 15 cm and the other after 25 cm (and
  // the same row mirrored). A tile started at the border may be mostly out
  // of view, so its far edge is any clear seam up to a brick's length in;
  // before, it was looked for only within the tolerance of a whole brick's
  // length, missed the seam, and every tile after it was off (touching
  // rows, frame 110 in VGA).
  for (const double first_x_m : {-0.95, -0.85})
  {
    test::TouchingPlatesScene scene = rowScene(1, 0.3, 0.2);
    scene.origin_m = Eigen::Vector3d(0.0, 0.0, 1.5);  // the image spans x in [-0.8, 0.8] m
    scene.rotation = test::TouchingPlatesScene::facingCamera(0.0, 0.0);
    const cv::Vec3b plain(200, 60, 50);
    scene.plates.clear();
    test::TouchingPlatesScene whole = scene;  // the bricks wholly in view
    for (double x0 = first_x_m; x0 < 1.0; x0 += 0.3)
    {
      scene.plates.push_back({{x0, -0.1}, {x0 + 0.3, 0.1}, plain});
      if (x0 > -0.8 && x0 + 0.3 < 0.8) whole.plates.push_back(scene.plates.back());
    }
    darkenSeamsAndRims(scene);
    SCOPED_TRACE("first brick at x = " + std::to_string(first_x_m) + " m");
    const FrontEndResult result = FrontEnd(BrickCatalogue::mbzirc2020(), colourFreeParams()).process(scene.frame());
    // Each brick wholly in view whole; the cut-off ones are no whole brick.
    std::vector<BrickCandidate> complete;
    for (const BrickCandidate& c : result.candidates)
    {
      EXPECT_EQ(c.type_name, "red");
      if (c.complete) complete.push_back(c);
    }
    ASSERT_EQ(whole.plates.size(), 4u);
    ASSERT_EQ(complete.size(), whole.plates.size());
    EXPECT_LT(worstCornerErrorM(complete, whole), 0.015);
  }
}

TEST(FaceTiling, ColourFreeTilingPrefersTheSizesItsSeamsDraw)
{
  // Two rows of two reds end to end (0.6 x 0.4): reds, greens and the
  // mixed set all tile it; only the reds' cuts all lie on seams.
  test::TouchingPlatesScene scene = rowScene(1, 0.6, 0.2);
  const cv::Vec3b plain(200, 60, 50);
  scene.plates = {{{-0.3, -0.2}, {0.0, 0.0}, plain},
                  {{0.0, -0.2}, {0.3, 0.0}, plain},
                  {{-0.3, 0.0}, {0.0, 0.2}, plain},
                  {{0.0, 0.0}, {0.3, 0.2}, plain}};
  scene.line_darkening = 40.0;
  scene.line_half_width_m = 0.002;
  const FrontEndParams params = colourFreeParams();
  const FrontEndResult result = FrontEnd(BrickCatalogue::mbzirc2020(), params).process(scene.frame());
  ASSERT_EQ(result.candidates.size(), 4u);
  for (const BrickCandidate& c : result.candidates)
  {
    EXPECT_EQ(c.type_name, "red");
    EXPECT_TRUE(c.complete) << c.partial_reason;
  }
  // Without the seam across the middle the same face is two greens.
  scene.plates = {{{-0.3, -0.2}, {0.3, 0.0}, plain}, {{-0.3, 0.0}, {0.3, 0.2}, plain}};
  const FrontEndResult greens = FrontEnd(BrickCatalogue::mbzirc2020(), params).process(scene.frame());
  ASSERT_EQ(greens.candidates.size(), 2u);
  for (const BrickCandidate& c : greens.candidates) EXPECT_EQ(c.type_name, "green");
}

TEST(FaceTiling, ColourFreeTopThatSmallerBoxesMakeUpIsCompleteOnlyWhenPlain)
{
  // A box_large top (0.4 x 0.3 m) in a layer, touching a box_small (0.3 x
  // 0.2 m) along a seen seam. Two box_smalls side by side make the same top
  // with a seam across its middle: on a plain face that seam would show,
  // on a printed one it need not.
  test::TouchingPlatesScene scene = largeBesideSmallScene(cv::Vec3b(180, 140, 100));
  scene.line_darkening = 40.0;
  const FrontEnd front_end(boxCatalogue(), colourFreeParams());

  const FrontEndResult plain = front_end.process(scene.frame());
  const BrickCandidate* plain_large = candidateOfType(plain, "box_large");
  ASSERT_NE(plain_large, nullptr);
  EXPECT_TRUE(plain_large->complete) << plain_large->partial_reason;

  RgbdFrame printed_frame = scene.frame();
  printOnPlates(scene, printed_frame);
  const FrontEndResult printed = front_end.process(printed_frame);
  const BrickCandidate* printed_large = candidateOfType(printed, "box_large");
  ASSERT_NE(printed_large, nullptr);
  EXPECT_FALSE(printed_large->complete);
  EXPECT_NE(printed_large->partial_reason.find("box_small tops touching"), std::string::npos)
      << printed_large->partial_reason;
}

TEST(FaceTiling, ColourFreeTopThatSmallerBoxesMakeUpIsPartialWhenTooDarkForTheirSeam)
{
  // The plain box_large top of ColourFreeTopThatSmallerBoxesMakeUpIsComplete-
  // OnlyWhenPlain, in a dim light (mean grey about 30): the seam of two
  // box_smalls in its place could be two grey levels deep, under any trace.
  test::TouchingPlatesScene scene = largeBesideSmallScene(cv::Vec3b(40, 30, 22));
  scene.background_rgb = cv::Vec3b(25, 24, 22);
  scene.line_darkening = 15.0;
  const FrontEndResult result = FrontEnd(boxCatalogue(), colourFreeParams()).process(scene.frame());
  const BrickCandidate* large = candidateOfType(result, "box_large");
  ASSERT_NE(large, nullptr);
  EXPECT_FALSE(large->complete);
  EXPECT_NE(large->partial_reason.find("too dark"), std::string::npos) << large->partial_reason;
}

TEST(FaceTiling, ColourFreeLoneTopThatSmallerBoxesMakeUpIsPartialWhereTheirSeamShows)
{
  // Two box_smalls side by side on their own (every outer edge a step down)
  // make a box_large top; a dark line runs where they meet. Printed, and
  // with nothing touching them, no box_large may be complete. A box_large
  // alone, with no line across it, is.
  test::TouchingPlatesScene scene = rowScene(1, 0.6, 0.2);
  const cv::Vec3b kraft(180, 140, 100);
  scene.plates = {{{-0.15, -0.2}, {0.15, 0.0}, kraft}, {{-0.15, 0.0}, {0.15, 0.2}, kraft}};
  scene.line_darkening = 30.0;
  const FrontEnd front_end(boxCatalogue(), colourFreeParams());
  RgbdFrame pair_frame = scene.frame();
  printOnPlates(scene, pair_frame);
  const FrontEndResult pair = front_end.process(pair_frame);
  ASSERT_FALSE(pair.candidates.empty());
  for (const BrickCandidate& c : pair.candidates)
  {
    EXPECT_FALSE(c.complete && c.type_name == "box_large") << "two box_smalls published as one complete box_large";
    if (c.type_name == "box_large")
    {
      EXPECT_FALSE(c.type_doubt.empty()) << c.partial_reason;
    }
  }

  scene.plates = {{{-0.15, -0.2}, {0.15, 0.2}, kraft}};
  const FrontEndResult lone = front_end.process(scene.frame());
  ASSERT_EQ(lone.candidates.size(), 1u);
  EXPECT_EQ(lone.candidates[0].type_name, "box_large");
  EXPECT_TRUE(lone.candidates[0].complete) << lone.candidates[0].partial_reason;
}

/// Twelve greens laid 3 x 4, all one way (a layer of a touching pile).
test::TouchingPlatesScene gridScene()
{
  test::TouchingPlatesScene scene;
  scene.camera = test::PlateScene::vgaCamera();
  scene.origin_m = Eigen::Vector3d(0.02, -0.01, 2.4);
  scene.rotation = test::TouchingPlatesScene::facingCamera(0.2, 0.35);
  for (int column = 0; column < 3; ++column)
    for (int row = 0; row < 4; ++row)
    {
      const Eigen::Vector2d min_m(0.6 * column - 0.9, 0.2 * row - 0.4);
      scene.plates.push_back({min_m, min_m + Eigen::Vector2d(0.6, 0.2), cv::Vec3b(30, 170, 50)});
    }
  return scene;
}

TEST(FaceTiling, EachOrientationLaysEveryTileThatWay)
{
  test::TouchingPlatesScene scene = gridScene();
  scene.line_darkening = 40.0;
  const RgbdFrame frame = scene.frame();
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  const std::vector<Segment> segments = HsvSegmenter().segment(frame, catalogue);
  ASSERT_EQ(segments.size(), 1u);
  const std::vector<const BrickType*> greens{catalogue.find("green")};
  const std::vector<FaceTiling> tilings = tileFaceEach(
      frame, segments[0], measuredUnion(scene), {greens}, 0.03, FaceTilingParams(), EdgeEvidenceParams(),
      [](std::size_t, const std::vector<FaceTiling>&) { return true; },
      {TileOrientation::kEither, TileOrientation::kLongAlongAxis, TileOrientation::kLongAcrossAxis});
  ASSERT_EQ(tilings.size(), 3u);
  // Corners 1 -> 2 run along the grid's axis, 0 -> 1 across it.
  for (const bool along : {true, false})
  {
    const FaceTiling& tiling = tilings[along ? 1 : 2];
    ASSERT_GE(tiling.tiles.size(), 2u);
    for (const FaceTile& tile : tiling.tiles)
    {
      const double along_m = (tile.corners_m[2] - tile.corners_m[1]).norm();
      const double across_m = (tile.corners_m[1] - tile.corners_m[0]).norm();
      EXPECT_EQ(along_m > across_m, along) << along_m << " x " << across_m;
    }
  }
  // Laid the way the bricks lie, the tiles are the twelve bricks.
  const std::size_t most = std::max(tilings[1].tiles.size(), tilings[2].tiles.size());
  EXPECT_EQ(most, 12u);
}

TEST(FaceTiling, ALayerInADimLightIsTiledTheWayItsSeamsRun)
{
  // frame 102 of bench_frontend's touching rows at VGA: greens in a dim
  // light, their seams a few grey levels deep. The greedy tiler laid its
  // first tiles across the rows and the rest followed; laid all one way,
  // the tiles follow the seams that show.
  test::TouchingPlatesScene scene = gridScene();
  for (auto& plate : scene.plates) plate.rgb = cv::Vec3b(20, 95, 30);
  scene.background_rgb = cv::Vec3b(50, 48, 46);
  scene.line_darkening = 6.0;
  scene.line_half_width_m = 0.003;
  scene.colour_noise = 3.0;
  const FrontEndResult result = FrontEnd(BrickCatalogue::mbzirc2020()).process(scene.frame());
  int on_a_plate = 0;
  for (const BrickCandidate& c : result.candidates)
  {
    EXPECT_EQ(c.type_name, "green");
    on_a_plate += std::abs(c.length_m - 0.6) < 0.03 && std::abs(c.width_m - 0.2) < 0.03 ? 1 : 0;
  }
  EXPECT_EQ(on_a_plate, 12) << result.candidates.size() << " candidates";
  EXPECT_LT(worstCornerErrorM(result.candidates, scene), 0.02);
}

TEST(FaceTiling, ParameterChecks)
{
  FaceTilingParams params;
  EXPECT_NO_THROW(params.validate());
  params.min_coverage = 0.0;
  EXPECT_THROW(params.validate(), ConfigError);
  params = FaceTilingParams();
  params.cell_m = -1.0;
  EXPECT_THROW(params.validate(), ConfigError);
}

/// A VGA frame of noisy depth around 1.2 m, with holes, and random colour.
RgbdFrame noisyFrame()
{
  RgbdFrame frame;
  frame.camera = test::PlateScene::vgaCamera();
  frame.rgb.create(480, 640, CV_8UC3);
  frame.depth_m.create(480, 640, CV_32FC1);
  cv::RNG rng(7);
  rng.fill(frame.rgb, cv::RNG::UNIFORM, 0, 256);
  rng.fill(frame.depth_m, cv::RNG::UNIFORM, 1.1, 1.3);
  for (int k = 0; k < 3000; ++k)
    frame.depth_m.at<float>(rng.uniform(0, 480), rng.uniform(0, 640)) = std::numeric_limits<float>::quiet_NaN();
  return frame;
}

TEST(PlanePixelSamples, ReadsEveryPixelAsComputedAndStoresOnlyThoseNearTheOutline)
{
  const RgbdFrame frame = noisyFrame();
  PlaneFit plane;
  plane.centroid_m = Eigen::Vector3d(0.05, -0.02, 1.2);
  plane.normal = Eigen::Vector3d(0.2, -0.3, -1.0).normalized();
  plane.valid = true;
  // A long face seen askew (its image box is three times its area), and
  // one running off the image.
  const std::vector<std::vector<Eigen::Vector2d>> outlines = {
      {{100.0, 100.0}, {420.0, 340.0}, {390.5, 380.2}, {70.3, 140.0}},
      {{-50.0, 200.0}, {300.0, 190.0}, {310.0, 520.0}, {-40.0, 530.0}},
  };
  const int margin_px = 4;
  for (const auto& outline : outlines)
  {
    const PlanePixelSamples samples(frame, plane, outline, margin_px);
    for (const double weight : samples.faceGrey().weights()) EXPECT_NEAR(weight, 1.0 / 3.0, 0.02);
    cv::Mat inside(480, 640, CV_8UC1, cv::Scalar(0));
    std::vector<cv::Point> polygon;
    for (const Eigen::Vector2d& p : outline) polygon.emplace_back(cvRound(p.x()), cvRound(p.y()));
    cv::fillConvexPoly(inside, polygon, cv::Scalar(255));
    const cv::Rect box = cv::boundingRect(polygon) & cv::Rect(0, 0, 640, 480);
    const auto box_area = static_cast<std::size_t>(box.area());
    FaceColourSum on_face;  // the stored pixels within a centimetre of the plane
    for (int v = 0; v < 480; ++v)
      for (int u = 0; u < 640; ++u)
      {
        double offset_m = 0.0, grey = 0.0;
        samples.read(u, v, offset_m, grey);
        const cv::Vec3b rgb = frame.rgb.at<cv::Vec3b>(v, u);
        // In the face's own grey (its colour here is noise: near the mean of
        // the channels), stored in single precision.
        ASSERT_NEAR(grey, samples.faceGrey()(rgb), 1e-4) << u << " " << v;
        const float z = frame.depthAt(u, v);
        if (std::isnan(z))
        {
          ASSERT_TRUE(std::isnan(offset_m)) << u << " " << v;
        }
        else
        {
          ASSERT_DOUBLE_EQ(offset_m, plane.signedDistance(frame.camera.backProject(u, v, z))) << u << " " << v;
        }
        if (inside.at<std::uint8_t>(v, u))
        {
          ASSERT_TRUE(samples.stored(u, v)) << u << " " << v;
        }
        if (samples.stored(u, v) && std::abs(offset_m) < kFaceColourOnPlaneM) on_face.add(rgb);
      }
    // The face's mean grey (the print test's reference): its on-plane
    // pixels' mean colour, in its own grey.
    EXPECT_NEAR(samples.meanFaceGrey(), samples.faceGrey()(on_face.mean()), 1e-9);
    EXPECT_GT(samples.meanFaceGrey(), 0.0);
    if (&outline != &outlines.front()) continue;
    // Nothing stored far from the askew face: not a corner of its image
    // box, and well under the box's area.
    EXPECT_FALSE(samples.stored(box.x, box.y + box.height - 1));
    EXPECT_LT(samples.storedCount(), box_area / 2);
  }
  // No outline: the whole image.
  const PlanePixelSamples whole(frame, plane, {}, margin_px);
  EXPECT_EQ(whole.storedCount(), 640u * 480u);
  EXPECT_TRUE(whole.stored(0, 0) && whole.stored(639, 479));
  // A corner projected from just in front of the camera lies far off the
  // image: the band of rows it crosses is stored across the image.
  const PlanePixelSamples band(frame, plane, {{-1e12, 100.0}, {1e12, 100.0}, {1e12, 110.0}, {-1e12, 110.0}}, margin_px);
  EXPECT_TRUE(band.stored(0, 105) && band.stored(639, 105));
  EXPECT_FALSE(band.stored(320, 200));
  EXPECT_EQ(band.storedCount(), 640u * (11u + 2u * margin_px));
}

TEST(CellCounts, CountsTheStateOverAnyRectangleAndNothingBeyondTheGrid)
{
  const int nx = 13, ny = 7;
  std::vector<std::uint8_t> states(static_cast<std::size_t>(nx) * ny);
  for (std::size_t k = 0; k < states.size(); ++k) states[k] = static_cast<std::uint8_t>((k * 7 + k / 5) % 3);
  const CellCounts counts(states, nx, ny, 1);
  for (int i0 = -2; i0 <= nx + 1; ++i0)
    for (int i1 = i0 - 1; i1 <= nx + 2; ++i1)
      for (int j0 = -2; j0 <= ny + 1; ++j0)
        for (int j1 = j0 - 1; j1 <= ny + 2; ++j1)
        {
          int expected = 0;
          for (int j = std::max(0, j0); j < std::min(ny, j1); ++j)
            for (int i = std::max(0, i0); i < std::min(nx, i1); ++i) expected += states[j * nx + i] == 1 ? 1 : 0;
          ASSERT_EQ(counts.count(i0, i1, j0, j1), expected) << i0 << " " << i1 << " " << j0 << " " << j1;
        }
  EXPECT_GT(counts.count(0, nx, 0, ny), 0);
  EXPECT_LT(counts.count(0, nx, 0, ny), nx * ny);
  EXPECT_EQ(CellCounts(states, nx, ny, 9).count(0, nx, 0, ny), 0) << "a state no cell holds";
}

TEST(CellCounts, AnUpdateFromARowCountsAsAFreshTable)
{
  const int nx = 11, ny = 9;
  std::vector<std::uint8_t> states(static_cast<std::size_t>(nx) * ny);
  for (std::size_t k = 0; k < states.size(); ++k) states[k] = static_cast<std::uint8_t>((k * 5 + k / 3) % 2);
  CellCounts counts(states, nx, ny, 1);
  // A tile taken over rows 4-6: its cells change state (as the tiler's do).
  for (int j = 4; j < 7; ++j)
    for (int i = 2; i < 8; ++i) states[static_cast<std::size_t>(j) * nx + i] = 2;
  const int before = counts.count(0, nx, 0, ny);
  counts.update(states, 4);
  const CellCounts fresh(states, nx, ny, 1);
  for (int i0 = 0; i0 <= nx; ++i0)
    for (int i1 = i0; i1 <= nx; ++i1)
      for (int j0 = 0; j0 <= ny; ++j0)
        for (int j1 = j0; j1 <= ny; ++j1)
          ASSERT_EQ(counts.count(i0, i1, j0, j1), fresh.count(i0, i1, j0, j1)) << i0 << " " << i1 << " " << j0 << " " << j1;
  EXPECT_LT(counts.count(0, nx, 0, ny), before) << "the taken cells no longer count";
}
}  // namespace
}  // namespace brick_pose
