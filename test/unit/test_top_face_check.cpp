// The top-face check on the synthetic D415: which way is up, side faces of
// the catalogue height below a top's edges, and side faces never taken for
// tops.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include <gtest/gtest.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/eval/candidate_matching.h"
#include "brick_pose/eval/rig_truth.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/roi/side_faces.h"
#include "brick_pose/roi/up_direction.h"
#include "brick_pose/sim/d415_modes.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace
{
/// Bricks given by (type, x, y, z of the top face centre, yaw) seen from
/// `elevation_deg` above the horizon at 1.2 m from the first brick's top.
sim::Scene scene(const std::vector<std::tuple<std::string, Eigen::Vector3d, double>>& bricks, double elevation_deg,
                 const BrickCatalogue& catalogue = BrickCatalogue::mbzirc2020())
{
  sim::Scene result;
  for (const auto& [type, top_centre, yaw_deg] : bricks)
  {
    sim::PlacedBrick brick{catalogue.at(type), Eigen::Isometry3d::Identity()};
    brick.world_T_brick.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    brick.world_T_brick.translation() = top_centre;
    result.bricks.push_back(brick);
  }
  result.world_T_camera = sim::lookAt(std::get<1>(bricks.front()), 1.2, elevation_deg, 25.0);
  return result;
}

struct Rendered
{
  sim::SyntheticFrame synthetic;
  RgbdFrame frame;
};

Rendered render(const sim::Scene& scene, const sim::SensorModel& sensor = sim::SensorModel(), std::uint64_t seed = 5)
{
  Rendered rendered;
  rendered.synthetic = sim::SyntheticRig(PinholeCamera::d415Color1280x720(), sensor).render(scene, seed);
  FrameHeader header;
  header.stamp_ns = 1;
  rendered.frame = makeRgbdFrame(rendered.synthetic.rgb, rendered.synthetic.depth_mm, rendered.synthetic.camera, header);
  return rendered;
}

Eigen::Vector3d worldUpInCamera(const sim::Scene& scene)
{
  return scene.world_T_camera.linear().transpose() * Eigen::Vector3d::UnitZ();
}

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b)
{
  return std::acos(std::max(-1.0, std::min(1.0, a.normalized().dot(b.normalized())))) * 180.0 / M_PI;
}

TEST(UpDirection, TheGroundIsTheSupportingPlane)
{
  const sim::Scene bricks = scene({{"green", {0.0, 0.0, 0.2}, 30.0}, {"red", {0.1, 0.35, 0.2}, -10.0}}, 55.0);
  const Rendered rendered = render(bricks);
  const UpDirection up = estimateSupportPlaneUp(rendered.frame);
  ASSERT_TRUE(up.known());
  EXPECT_EQ(up.source, UpSource::kSupportPlane);
  EXPECT_LT(angleDeg(up.up, worldUpInCamera(bricks)), 1.0);
  ASSERT_TRUE(up.has_support_plane);
  // The camera is 1.2 m from a point 0.2 m above the ground, 55 deg up.
  EXPECT_NEAR(up.support_offset_m, 1.2 * std::sin(55.0 * M_PI / 180.0) + 0.2, 0.02);
  EXPECT_NEAR(up.heightAboveSupport(bricks.world_T_camera.inverse() * Eigen::Vector3d(0.0, 0.0, 0.2)), 0.2, 0.02);
}

TEST(UpDirection, AGivenSupportIsUpAndThePlaneThePileStandsOn)
{
  // A deck 0.14 m above the ground, seen by the scene's camera.
  const sim::Scene bricks = scene({{"red", Eigen::Vector3d(0.0, 0.0, 0.2), 0.0}}, 55.0);
  Eigen::Isometry3d world_T_deck = Eigen::Isometry3d::Identity();
  world_T_deck.translation() = Eigen::Vector3d(0.3, -0.2, 0.14);
  world_T_deck.rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));  // its yaw is no matter
  const Eigen::Vector4d deck = xyPlaneInCamera(bricks.world_T_camera.inverse() * world_T_deck);
  const UpDirection given = givenSupport(deck);
  ASSERT_TRUE(given.known());
  EXPECT_EQ(given.source, UpSource::kGiven);
  EXPECT_TRUE(given.support_given);
  EXPECT_LT(angleDeg(given.up, worldUpInCamera(bricks)), 1e-6);
  // The brick's top, 0.2 m above the ground, is 0.06 m above the deck.
  const Eigen::Vector3d top_in_camera = bricks.world_T_camera.inverse() * Eigen::Vector3d(0.0, 0.0, 0.2);
  EXPECT_NEAR(given.heightAboveSupport(top_in_camera), 0.06, 1e-9);
  // Scaling the plane changes nothing; a plane without a normal is none.
  EXPECT_NEAR(givenSupport(3.0 * deck).heightAboveSupport(top_in_camera), 0.06, 1e-9);
  EXPECT_FALSE(givenSupport(Eigen::Vector4d(0.0, 0.0, 0.0, 1.0)).known());
  EXPECT_FALSE(givenSupport(Eigen::Vector4d(std::nan(""), 0.0, 1.0, 1.0)).known());
  // Up from tf stays; the plane is the given one.
  UpDirection from_tf;
  from_tf.up = Eigen::Vector3d::UnitY();
  from_tf.source = UpSource::kGiven;
  const UpDirection both = withGivenSupport(from_tf, deck);
  EXPECT_EQ(both.up, Eigen::Vector3d::UnitY());
  EXPECT_TRUE(both.support_given);
  EXPECT_NEAR(both.heightAboveSupport(top_in_camera), 0.06, 1e-9);
}

TEST(UpDirection, NoPlaneNoUpAndTheFacesDominantNormal)
{
  cv::Mat depth(48, 64, CV_32FC1, cv::Scalar(std::nanf("")));
  depth(cv::Rect(0, 0, 4, 4)).setTo(1.0f);  // too few samples for a plane
  PinholeCamera camera;
  camera.width_px = 64;
  camera.height_px = 48;
  camera.fx_px = camera.fy_px = 60.0;
  camera.cx_px = 31.5;
  camera.cy_px = 23.5;
  const RgbdFrame empty = makeRgbdFrame(cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(0)), depth, camera, {});
  EXPECT_FALSE(estimateSupportPlaneUp(empty).known());

  // Three tops facing one way outweigh a larger side face facing another.
  const Eigen::Vector3d top(0.0, -0.8, -0.6), side(0.0, 0.0, -1.0);
  const UpDirection up = dominantFaceNormal({top, side, top, top}, {1.0, 2.0, 1.0, 1.0});
  EXPECT_EQ(up.source, UpSource::kFaceNormals);
  EXPECT_LT(angleDeg(up.up, top), 1e-6);
  EXPECT_FALSE(dominantFaceNormal({}, {}).known());
  UpDirectionParams params;
  params.min_support_fraction = 0.0;
  EXPECT_THROW(params.validate(), ConfigError);
}

/// The truth top corners of brick i in the camera frame.
std::array<Eigen::Vector3d, 4> topCorners(const Rendered& rendered, int brick)
{
  return sim::topFaceCornersInCamera(rendered.synthetic.truth[static_cast<std::size_t>(brick)]);
}

TEST(SideFaces, TheSidesSeenBelowABricksTopAreItsHeight)
{
  const sim::Scene bricks = scene({{"green", {0.0, 0.0, 0.2}, 30.0}}, 50.0);
  const Rendered rendered = render(bricks);
  const UpDirection support = estimateSupportPlaneUp(rendered.frame);
  const Eigen::Vector3d up = worldUpInCamera(bricks);
  int matching = 0, hidden = 0;
  for (int edge = 0; edge < 4; ++edge)
  {
    const SideFaceEvidence side = measureSideFace(rendered.frame, topCorners(rendered, 0), up, edge, 0.2, support);
    if (!side.visible)
    {
      ++hidden;
      EXPECT_EQ(judgeSideFace(side, 0.2), SideFaceVerdict::kNotVisible);
      continue;
    }
    EXPECT_TRUE(side.foot_seen) << "edge " << edge;
    EXPECT_TRUE(side.foot_on_support) << "edge " << edge;
    EXPECT_NEAR(side.visible_height_m, 0.2, 0.025) << "edge " << edge;
    matching += judgeSideFace(side, 0.2) == SideFaceVerdict::kMatches ? 1 : 0;
    // A brick 13 cm tall would not have these sides (nor would two of them).
    EXPECT_EQ(judgeSideFace(side, 0.13), SideFaceVerdict::kMismatch) << "edge " << edge;
  }
  EXPECT_GE(matching, 1) << "seen obliquely, at least one side faces the camera";
  EXPECT_GE(hidden, 1) << "and at least one faces away";
}

TEST(SideFaces, BricksStackedFlushShowTwoHeightsOfSide)
{
  // A green on a green: one wall of side, two bricks tall, still matches.
  const sim::Scene bricks = scene({{"green", {0.0, 0.0, 0.4}, 0.0}, {"green", {0.0, 0.0, 0.2}, 0.0}}, 40.0);
  const Rendered rendered = render(bricks);
  const UpDirection support = estimateSupportPlaneUp(rendered.frame);
  bool seen = false;
  for (int edge = 0; edge < 4; ++edge)
  {
    const SideFaceEvidence side =
        measureSideFace(rendered.frame, topCorners(rendered, 0), worldUpInCamera(bricks), edge, 0.2, support);
    if (!side.foot_seen) continue;
    seen = true;
    EXPECT_NEAR(side.visible_height_m, 0.4, 0.04);
    EXPECT_EQ(judgeSideFace(side, 0.2), SideFaceVerdict::kMatches);
  }
  EXPECT_TRUE(seen);
}

TEST(SideFaces, ASideCutShortByALowerNeighbourIsNoContradiction)
{
  SideFaceEvidence side;
  side.visible = true;
  side.foot_seen = true;
  side.foot_on_support = false;  // ends on a surface that is not the ground
  side.visible_height_m = 0.08;
  EXPECT_EQ(judgeSideFace(side, 0.2), SideFaceVerdict::kCutShort);
  side.foot_on_support = true;  // reaches the ground 8 cm down: not a 20 cm brick
  EXPECT_EQ(judgeSideFace(side, 0.2), SideFaceVerdict::kMismatch);
  side.foot_seen = false;
  EXPECT_EQ(judgeSideFace(side, 0.2), SideFaceVerdict::kCutShort);
  SideFaceParams params;
  params.columns = 1;
  EXPECT_THROW(params.validate(), ConfigError);
}

TEST(TopFaceCheck, ColourFreeSideFacesOfABrickAreRejectedAndItsTopIsComplete)
{
  // Seen obliquely, a green brick's long side (0.6 x 0.2) has a green's top
  // size. Without colour only "up" tells them apart.
  const sim::Scene bricks = scene({{"green", {0.0, 0.0, 0.2}, 20.0}}, 45.0);
  const Rendered rendered = render(bricks);
  FrontEndParams params;
  params.mode = SegmentationMode::kRegionGrowing;
  const FrontEndResult result = FrontEnd(BrickCatalogue::mbzirc2020(), params).process(rendered.frame);
  EXPECT_EQ(result.up.source, UpSource::kSupportPlane);
  int tops = 0;
  for (const BrickCandidate& candidate : result.candidates)
  {
    EXPECT_LT(angleDeg(candidate.normal, worldUpInCamera(bricks)), 5.0) << "only the top is a candidate";
    tops += candidate.complete ? 1 : 0;
  }
  EXPECT_EQ(tops, 1) << (result.candidates.empty() ? "no candidate" : result.candidates[0].partial_reason);
  int side_faces = 0;
  for (const Rejection& rejection : result.rejections)
    side_faces += rejection.reason.find("not a top face") != std::string::npos ? 1 : 0;
  EXPECT_GE(side_faces, 1) << "the visible long side is rejected as a side face";
}

/// Two plain boxes with one top size: only their height tells them apart.
BrickCatalogue twoBoxesWithOneTop()
{
  return BrickCatalogue::fromYamlString(R"(bricks:
  - {name: tall, length_m: 0.30, width_m: 0.20, height_m: 0.20}
  - {name: flat, length_m: 0.30, width_m: 0.20, height_m: 0.05}
)");
}

/// The colour-free candidate nearest the image centre, if any.
const BrickCandidate* centralCandidate(const FrontEndResult& result, const PinholeCamera& camera)
{
  const BrickCandidate* best = nullptr;
  double best_px = 1e9;
  for (const BrickCandidate& candidate : result.candidates)
  {
    const double off_px = (candidate.centroid_px - Eigen::Vector2d(camera.cx_px, camera.cy_px)).norm();
    if (off_px < best_px)
    {
      best = &candidate;
      best_px = off_px;
    }
  }
  return best;
}

TEST(TopFaceCheck, ATopTwoTypesShareIsCompleteOnlyWhenTheSidesTellTheHeight)
{
  const BrickCatalogue catalogue = twoBoxesWithOneTop();
  FrontEndParams params;
  params.mode = SegmentationMode::kColourFree;
  const FrontEnd front_end(catalogue, params);

  // Obliquely the sides run 0.20 m down to the ground: three flat boxes
  // stacked flush would be 0.15 m, so only "tall" fits.
  const sim::Scene oblique = scene({{"tall", {0.0, 0.0, 0.2}, 20.0}}, 45.0, catalogue);
  const Rendered seen_obliquely = render(oblique);
  const FrontEndResult oblique_result = front_end.process(seen_obliquely.frame);
  const BrickCandidate* side_on = centralCandidate(oblique_result, seen_obliquely.frame.camera);
  ASSERT_NE(side_on, nullptr);
  EXPECT_EQ(side_on->type_name, "tall");
  EXPECT_TRUE(side_on->type_doubt.empty()) << side_on->type_doubt;
  EXPECT_TRUE(side_on->complete) << side_on->partial_reason;

  // From straight above no side shows: the type is a guess, so never complete.
  const sim::Scene above = scene({{"tall", {0.0, 0.0, 0.2}, 20.0}}, 89.0, catalogue);
  const Rendered seen_from_above = render(above);
  const FrontEndResult above_result = front_end.process(seen_from_above.frame);
  const BrickCandidate* top_on = centralCandidate(above_result, seen_from_above.frame.camera);
  ASSERT_NE(top_on, nullptr);
  EXPECT_FALSE(top_on->complete);
  EXPECT_NE(top_on->partial_reason.find("type uncertain"), std::string::npos) << top_on->partial_reason;
}

/// A low box with a taller one standing against its +x end, seen from
/// nearly straight above the low box: the taller box's wall rises 0.18 m
/// at the low top's edge. `extra` adds a catalogue entry.
FrontEndResult lowBoxBesideATallOne(const std::string& extra)
{
  const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(R"(bricks:
  - {name: low, length_m: 0.32, width_m: 0.22, height_m: 0.12}
  - {name: high, length_m: 0.42, width_m: 0.36, height_m: 0.30}
)" + extra);
  const sim::Scene boxes = scene({{"low", {0.0, 0.0, 0.12}, 0.0}, {"high", {0.37, 0.0, 0.30}, 0.0}}, 85.0, catalogue);
  FrontEndParams params;
  params.mode = SegmentationMode::kColourFree;
  params.roi.up_direction = worldUpInCamera(boxes);
  const Rendered rendered = render(boxes);
  return FrontEnd(catalogue, params).process(rendered.frame);
}

/// The candidate of type `name`, if any.
const BrickCandidate* candidateOfType(const FrontEndResult& result, const std::string& name)
{
  for (const BrickCandidate& candidate : result.candidates)
    if (candidate.type_name == name) return &candidate;
  return nullptr;
}

TEST(TopFaceCheck, ATallerBoxStandingBesideATopEndsIt)
{
  // Nothing in the catalogue lying on the low top rises 0.18 m (its
  // extents and their pairs: 0.12, 0.22, 0.24, 0.30, ...): the wall is the
  // tall box's, standing beside the low one, and the low top is whole.
  const FrontEndResult result = lowBoxBesideATallOne("");
  const BrickCandidate* low = candidateOfType(result, "low");
  ASSERT_NE(low, nullptr);
  EXPECT_EQ(std::count(low->edge_kinds.begin(), low->edge_kinds.end(), EdgeKind::kStepUp), 1);
  EXPECT_TRUE(low->complete) << low->partial_reason;
}

TEST(TopFaceCheck, AWallAsHighAsSomethingThatCouldRestOnTheTopIsAnOcclusion)
{
  // The same view with a 0.18 m plank in the catalogue: the wall could be
  // a plank lying on the low top, which may go on beneath it.
  const FrontEndResult result = lowBoxBesideATallOne("  - {name: plank, length_m: 0.60, width_m: 0.40, height_m: 0.18}\n");
  for (const BrickCandidate& candidate : result.candidates)
    EXPECT_FALSE(candidate.type_name == "low" && candidate.complete) << "the low top may go on under a plank";
  // Without colour, a face that may go on beneath something is typed only
  // as a doubt, by its visible part: the low top is published partial,
  // naming the occlusion, its type in doubt.
  int occluded_low_tops = 0;
  for (const BrickCandidate& candidate : result.candidates)
    if (candidate.type_name == "low" && !candidate.complete &&
        candidate.partial_reason.find("occlusion boundary") != std::string::npos)
    {
      ++occluded_low_tops;
      EXPECT_NE(candidate.type_doubt.find("its visible part"), std::string::npos) << candidate.type_doubt;
      EXPECT_NE(candidate.partial_reason.find("type in doubt"), std::string::npos) << candidate.partial_reason;
    }
  EXPECT_EQ(occluded_low_tops, 1);
}

/// Whole tops found, and complete candidates that are no whole top, in
/// bench_frontend's touching-rows frame 100 + `j` (seed 1: D4xx depth,
/// 640x480, normal, sunlit and low light in turn), without colour.
std::pair<int, int> touchingRowsFrame(std::uint64_t j, bool read_seams_on_plain_faces)
{
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  const sim::Scene scene = sim::SceneGenerator(catalogue, sim::SceneParams::defaultsFor(sim::SceneKind::kTouchingRows))
                               .generate(1000003ULL + 4000000ULL + j);
  sim::SensorModel sensor = sim::SensorModel::d4xx();
  static const sim::Lighting kLightings[3] = {sim::Lighting::kNormal, sim::Lighting::kSunlight, sim::Lighting::kLowLight};
  sensor.lighting = kLightings[j % 3];
  const PinholeCamera camera = sim::d415ColourMode("640x480");
  const sim::SyntheticFrame synthetic = sim::SyntheticRig(camera, sensor).render(scene, 1000003ULL + 4000000ULL + j);
  FrameHeader header;
  header.stamp_ns = 1;
  const Eigen::Vector3d up = worldUpInCamera(scene);
  FrontEndParams params;
  params.mode = SegmentationMode::kColourFree;
  params.roi.up_direction = up;
  if (!read_seams_on_plain_faces)
  {
    params.roi.plain_seam_line_share = 0.0;
    params.roi.confirm_seams_along_lines = false;
  }
  const FrontEndResult result = FrontEnd(catalogue, params)
                                    .process(makeRgbdFrame(synthetic.rgb, synthetic.depth_mm, camera, header));
  const eval::FrameMatch match = eval::matchCandidates(result.candidates, eval::rigSceneTruth(synthetic, up), camera);
  int found = 0, false_complete = 0;
  for (const eval::TopMatch& top : match.tops) found += top.whole_in_view && top.found ? 1 : 0;
  for (const eval::CandidateMatch& candidate : match.candidates) false_complete += candidate.false_complete ? 1 : 0;
  return {found, false_complete};
}

TEST(TopFaceCheck, TouchingBricksInALowLightAreFoundWithoutAFalseCompleteFace)
{
  // Frames 102 (a grid of greens) and 123 (rows of reds) in a low light,
  // faces of grey 26: their seams draw lines of 3-8 grey levels, many below
  // the 6 of a seam's least line on a face of grey 100, and a brick's width
  // holds too few pixels for its own stretch of seam to be confirmed. Read
  // as a share of the face's light and along the lines the grid's cuts
  // share, whole tops are found and nothing false is complete; nor is
  // anything without that reading. How many more it finds is the
  // benchmark's to say: these frames are borderline, and the Release and
  // sanitizer builds render and read them differently (10 vs 2 whole tops
  // found in one, 10 vs 14 in the other).
  int found = 0;
  for (const std::uint64_t j : {2, 23})
  {
    const auto [by_reading, false_by_reading] = touchingRowsFrame(j, true);
    const auto [without, false_without] = touchingRowsFrame(j, false);
    EXPECT_EQ(false_by_reading, 0) << "frame " << 100 + j;
    EXPECT_EQ(false_without, 0) << "frame " << 100 + j;
    found += by_reading;
  }
  EXPECT_GE(found, 4);
}

/// Two boxes sharing a 0.30 x 0.20 m top, 0.15 and 0.07 m tall.
const char* const kFlatAndTallBoxes = R"(bricks:
  - {name: box_small, length_m: 0.30, width_m: 0.20, height_m: 0.15}
  - {name: box_flat, length_m: 0.30, width_m: 0.20, height_m: 0.07}
)";

/// The ground (world z = 0) in the scene's camera frame, as the nodelet's
/// support_frame gives it.
Eigen::Vector4d groundInCamera(const sim::Scene& scene)
{
  Eigen::Vector4d plane;
  plane << worldUpInCamera(scene), scene.world_T_camera.translation().z();
  return plane;
}

/// The colour-free candidates of `scene` seen with up given and, when
/// `ground_given`, the ground.
std::vector<BrickCandidate> colourFreeCandidates(const sim::Scene& scene, const BrickCatalogue& catalogue,
                                                 bool ground_given)
{
  FrontEndParams params;
  params.mode = SegmentationMode::kColourFree;
  params.roi.up_direction = worldUpInCamera(scene);
  if (ground_given) params.roi.support_plane = groundInCamera(scene);
  return FrontEnd(catalogue, params).process(render(scene).frame).candidates;
}

TEST(TopFaceCheck, AFlatBoxIsToldFromATallOneSharingItsTopByItsHeightAboveTheGivenGround)
{
  // Seen from straight above, a flat box shows no side: its top is also a
  // tall box's. Its height above the ground (given) is only the flat one's.
  const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(kFlatAndTallBoxes);
  const sim::Scene flat = scene({{"box_flat", Eigen::Vector3d(0.0, 0.0, 0.07), 20.0}}, 89.0, catalogue);

  const std::vector<BrickCandidate> unsure = colourFreeCandidates(flat, catalogue, false);
  ASSERT_EQ(unsure.size(), 1u);
  EXPECT_FALSE(unsure[0].complete);
  EXPECT_NE(unsure[0].partial_reason.find("type uncertain"), std::string::npos) << unsure[0].partial_reason;

  const std::vector<BrickCandidate> sure = colourFreeCandidates(flat, catalogue, true);
  ASSERT_EQ(sure.size(), 1u);
  EXPECT_TRUE(sure[0].complete) << sure[0].partial_reason;
  EXPECT_EQ(sure[0].type_name, "box_flat");
}

TEST(TopFaceCheck, AFlatBoxOnAPlinthTheCatalogueLacksIsNotTypedByItsHeightAboveTheGround)
{
  // On a 0.10 m plinth, the flat box's top is 0.17 m up: a tall box's on
  // the ground, within the tolerance, and no stack of catalogue boxes puts
  // a flat one there. The plinth's top, seen around the box's foot, is
  // where it may stand: its type stays in doubt.
  const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(kFlatAndTallBoxes);
  const BrickCatalogue with_plinth = BrickCatalogue::fromYamlString(std::string(kFlatAndTallBoxes) +
                                                                    "  - {name: plinth, length_m: 0.60, width_m: "
                                                                    "0.45, height_m: 0.10}\n");
  const sim::Scene on_plinth = scene({{"box_flat", Eigen::Vector3d(0.0, 0.0, 0.17), 20.0},
                                      {"plinth", Eigen::Vector3d(0.0, 0.0, 0.10), 20.0}},
                                     89.0, with_plinth);
  const std::vector<BrickCandidate> candidates = colourFreeCandidates(on_plinth, catalogue, true);
  ASSERT_FALSE(candidates.empty());
  for (const BrickCandidate& candidate : candidates)
  {
    EXPECT_FALSE(candidate.complete) << candidate.type_name << " " << candidate.length_m << " x " << candidate.width_m;
    if (std::abs(candidate.length_m - 0.30) < 0.03)
    {
      EXPECT_NE(candidate.partial_reason.find("type uncertain"), std::string::npos) << candidate.partial_reason;
    }
  }
}

TEST(TopFaceCheck, AFlatBoxBetweenTallOnesEndsAtTheirWallsWhenNoLargerBoxCouldStandThere)
{
  // A flat box touching a tall one along each long side: beyond both, a
  // wall 0.08 m high, as high as a flat box resting on it. Were one resting
  // there, the face would go on beneath it: a large box's 0.40 x 0.30 m top
  // could be the face's, partly covered. Its top 0.07 m above the ground
  // (given) is no large box's (0.25 m tall): the walls are its ends.
  const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(std::string(kFlatAndTallBoxes) +
                                                                  "  - {name: box_large, length_m: 0.40, width_m: "
                                                                  "0.30, height_m: 0.25}\n");
  const sim::Scene row = scene({{"box_flat", Eigen::Vector3d(0.0, 0.0, 0.07), 0.0},
                                {"box_small", Eigen::Vector3d(0.0, 0.20, 0.15), 0.0},
                                {"box_small", Eigen::Vector3d(0.0, -0.20, 0.15), 0.0}},
                               89.0, catalogue);
  auto flatOne = [](const std::vector<BrickCandidate>& candidates) -> const BrickCandidate* {
    // The flat box's top is the lowest face, nearest the image centre.
    for (const BrickCandidate& candidate : candidates)
      if ((candidate.centroid_px - Eigen::Vector2d(640.0, 360.0)).norm() < 40.0) return &candidate;
    return nullptr;
  };
  const std::vector<BrickCandidate> unsure = colourFreeCandidates(row, catalogue, false);
  const BrickCandidate* unsure_flat = flatOne(unsure);
  EXPECT_TRUE(unsure_flat == nullptr || !unsure_flat->complete) << "without the ground a large box may lie under";

  const std::vector<BrickCandidate> sure = colourFreeCandidates(row, catalogue, true);
  const BrickCandidate* sure_flat = flatOne(sure);
  ASSERT_NE(sure_flat, nullptr);
  EXPECT_TRUE(sure_flat->complete) << sure_flat->partial_reason;
  EXPECT_EQ(sure_flat->type_name, "box_flat");
  for (int k : {0, 2}) EXPECT_EQ(sure_flat->edge_kinds[k], EdgeKind::kStepUp) << "edge " << k;
  // The tall boxes' tops are also a flat box's on another (0.14 m): in doubt,
  // although each shows 0.09 m of side down to the flat box's top, more
  // than a flat box is tall (a flat box on another shows both sides, flush).
  // That side is only a lower bound, and a tall box stands exactly at 0.15
  // m: the guess is the tall box (it was the flat one, nearer 0.09 m).
  for (const BrickCandidate& candidate : sure)
    if (&candidate != sure_flat)
    {
      EXPECT_FALSE(candidate.complete) << candidate.type_name;
      EXPECT_EQ(candidate.type_name, "box_small");
    }
}

/// Two boxes sharing a 0.30 x 0.20 m top, 0.15 m tall, and a large box
/// whose 0.40 x 0.30 m top two of them make side by side.
const char* const kSmallAndLargeBoxes = R"(bricks:
  - {name: box_small, length_m: 0.30, width_m: 0.20, height_m: 0.15}
  - {name: box_large, length_m: 0.40, width_m: 0.30, height_m: 0.25}
)";

/// box_small boxes on the ground with their top centres at `centres_xy`,
/// seen from 1.4 m, 80 deg above the horizon.
sim::Scene smallBoxesOnTheGround(const std::vector<Eigen::Vector2d>& centres_xy)
{
  std::vector<std::tuple<std::string, Eigen::Vector3d, double>> boxes;
  for (const Eigen::Vector2d& xy : centres_xy)
    boxes.emplace_back("box_small", Eigen::Vector3d(xy.x(), xy.y(), 0.15), 0.0);
  sim::Scene row = scene(boxes, 80.0, BrickCatalogue::fromYamlString(kSmallAndLargeBoxes));
  row.world_T_camera = sim::lookAt(Eigen::Vector3d(0.0, 0.0, 0.15), 1.4, 80.0, 25.0);
  return row;
}

/// Colour-free candidates of `boxes` (D4xx depth, the ground given).
std::vector<BrickCandidate> colourFreeCandidatesOnTheGround(const sim::Scene& boxes, const BrickCatalogue& catalogue)
{
  FrontEndParams params;
  params.mode = SegmentationMode::kColourFree;
  params.roi.up_direction = worldUpInCamera(boxes);
  params.roi.support_plane = groundInCamera(boxes);
  return FrontEnd(catalogue, params).process(render(boxes, sim::SensorModel::d4xx()).frame).candidates;
}

/// Whether a candidate's centre lies within `within_m` of a top centre at
/// one of `centres_xy`, `top_z_m` up (`boxes`' camera frame).
bool onATop(const BrickCandidate& candidate, const sim::Scene& boxes, const std::vector<Eigen::Vector2d>& centres_xy,
            double top_z_m, double within_m)
{
  const Eigen::Isometry3d camera_T_world = boxes.world_T_camera.inverse();
  for (const Eigen::Vector2d& xy : centres_xy)
    if ((candidate.centroid_m - camera_T_world * Eigen::Vector3d(xy.x(), xy.y(), top_z_m)).norm() <= within_m)
      return true;
  return false;
}

TEST(TopFaceCheck, TwoSmallBoxesTouchingAreNoLargeBoxWhereNoneCouldStandAndAreCutWhereTheirTopFits)
{
  // Side by side, two box_small make a box_large's top; end to end, a top
  // no type has. D4xx depth smooths their seam away. With the ground given,
  // their top 0.15 m up is no box_large's (0.25 m tall), and only
  // box_small's top stands there: its size places the cut, which shows no
  // seam, so both are published, partial, with that doubt.
  const std::vector<std::vector<Eigen::Vector2d>> layouts{{{0.0, -0.10}, {0.0, 0.10}}, {{-0.15, 0.0}, {0.15, 0.0}}};
  for (const std::vector<Eigen::Vector2d>& centres_xy : layouts)
  {
    const sim::Scene row = smallBoxesOnTheGround(centres_xy);
    const std::vector<BrickCandidate> candidates =
        colourFreeCandidatesOnTheGround(row, BrickCatalogue::fromYamlString(kSmallAndLargeBoxes));
    int on_tops = 0;
    for (const BrickCandidate& candidate : candidates)
    {
      EXPECT_FALSE(candidate.complete) << candidate.type_name << ": " << candidate.partial_reason;
      EXPECT_EQ(candidate.type_name, "box_small") << candidate.partial_reason;
      EXPECT_NE(candidate.partial_reason.find("the one top standing at its height"), std::string::npos)
          << candidate.partial_reason;
      on_tops += onATop(candidate, row, centres_xy, 0.15, 0.03);
    }
    EXPECT_EQ(on_tops, 2) << candidates.size() << " candidates, layout at " << centres_xy[1].transpose();
  }
}

TEST(TopFaceCheck, LargeBoxesTouchingAreCutIntoTheTypeStandingMostExactlyAtTheirHeight)
{
  // End to end, or four in a square, box_large tops 0.25 m up also tile as
  // 0.30 x 0.20 m tops turned across. A box_flat with that top could be
  // there only on a box lying on a side (0.20 m, 2 cm off, within the
  // height tolerance), where a box_large stands exactly on the ground: the
  // faces are cut into box_large tops (partial: no seam shows).
  const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(R"(bricks:
  - {name: box_large, length_m: 0.40, width_m: 0.30, height_m: 0.25}
  - {name: box_flat, length_m: 0.30, width_m: 0.20, height_m: 0.07}
)");
  const std::vector<std::vector<Eigen::Vector2d>> layouts{
      {{-0.20, 0.0}, {0.20, 0.0}}, {{-0.20, -0.15}, {0.20, -0.15}, {-0.20, 0.15}, {0.20, 0.15}}};
  for (const std::vector<Eigen::Vector2d>& centres_xy : layouts)
  {
    std::vector<std::tuple<std::string, Eigen::Vector3d, double>> boxes;
    for (const Eigen::Vector2d& xy : centres_xy) boxes.emplace_back("box_large", Eigen::Vector3d(xy.x(), xy.y(), 0.25), 0.0);
    sim::Scene layer = scene(boxes, 80.0, catalogue);
    layer.world_T_camera = sim::lookAt(Eigen::Vector3d(0.0, 0.0, 0.25), 1.5, 80.0, 25.0);
    int on_tops = 0;
    for (const BrickCandidate& candidate : colourFreeCandidatesOnTheGround(layer, catalogue))
    {
      EXPECT_FALSE(candidate.complete) << candidate.partial_reason;
      EXPECT_EQ(candidate.type_name, "box_large") << candidate.length_m << " x " << candidate.width_m;
      on_tops += onATop(candidate, layer, centres_xy, 0.25, 0.03);
    }
    EXPECT_EQ(on_tops, static_cast<int>(centres_xy.size()));
  }
}

/// A box of `type` lying on a long side (its width up, resting on the
/// ground), seen from nearly straight above.
sim::Scene oneLyingOnALongSide(const BrickType& type)
{
  sim::Scene lying;
  sim::PlacedBrick box{type, Eigen::Isometry3d::Identity()};
  // Brick y (the width) turns up: the box rests on the ground, as tall as
  // it is wide; its height lies along world y.
  box.world_T_brick.linear() = Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  box.world_T_brick.translation() = Eigen::Vector3d(0.0, 0.0, 0.5 * type.width_m);
  lying.bricks.push_back(box);
  lying.world_T_camera = sim::lookAt(Eigen::Vector3d(0.0, 0.5 * type.height_m, 0.3), 1.2, 89.0, 25.0);
  return lying;
}

FrontEndResult colourFreeOf(const BrickCatalogue& catalogue, const RgbdFrame& frame)
{
  FrontEndParams params;
  params.mode = SegmentationMode::kColourFree;
  return FrontEnd(catalogue, params).process(frame);
}

/// The colour-free front end's result on the only type of `catalogue`
/// lying on a long side.
FrontEndResult colourFreeOfOneLyingOnALongSide(const BrickCatalogue& catalogue)
{
  return colourFreeOf(catalogue, render(oneLyingOnALongSide(catalogue.types().front())).frame);
}

TEST(TopFaceCheck, ABoxLyingOnItsSideIsNotACompleteTopWhenItsSideFaceHasNearlyTheTopsSize)
{
  // A crate 0.40 x 0.30 x 0.28 m lying on a long side shows 0.40 x 0.28 m
  // up, within the dimension tolerance of its top. Seen from straight above
  // nothing tells the two apart: never a complete top.
  const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(R"(bricks:
  - {name: crate, length_m: 0.40, width_m: 0.30, height_m: 0.28}
)");
  const FrontEndResult result = colourFreeOfOneLyingOnALongSide(catalogue);
  ASSERT_FALSE(result.candidates.empty()) << "the 0.40 x 0.28 m face is found";
  for (const BrickCandidate& candidate : result.candidates)
  {
    EXPECT_FALSE(candidate.complete) << candidate.length_m << " x " << candidate.width_m;
    EXPECT_NE(candidate.partial_reason.find("crate lying on a side"), std::string::npos) << candidate.partial_reason;
  }
}

TEST(TopFaceCheck, ABoxLyingOnItsSideWhoseSideIsNoTopsSizeIsPublishedLyingOnASide)
{
  // A large box 0.40 x 0.30 x 0.25 m lying on a long side shows 0.40 x 0.25
  // m up: 5 cm narrower than its top, no upright top's size. It is the box
  // lying on a side: typed so, its four edges steps down to the ground, and
  // the rig's truth holds its face up as that type's whole top.
  const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(R"(bricks:
  - {name: box_large, length_m: 0.40, width_m: 0.30, height_m: 0.25}
)");
  const FrontEndResult result = colourFreeOfOneLyingOnALongSide(catalogue);
  ASSERT_EQ(result.candidates.size(), 1u) << "the 0.40 x 0.25 m face is found once";
  const BrickCandidate& candidate = result.candidates.front();
  EXPECT_EQ(candidate.type_name, "box_large lying on a side");
  EXPECT_TRUE(candidate.complete) << candidate.partial_reason;
  EXPECT_TRUE(candidate.other_possible_types.empty()) << candidate.type_doubt;
}

TEST(TopFaceCheck, ABoxLyingOnItsSideIsATopOfItsRestingTypeInTheRigsTruth)
{
  // The truth the benchmark scores against: the face up of a box on a side
  // is the whole top of "box_large lying on a side", and a candidate of
  // that type on it is a whole top found, not a false complete face.
  const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(R"(bricks:
  - {name: box_large, length_m: 0.40, width_m: 0.30, height_m: 0.25}
)");
  const BrickType& type = catalogue.types().front();
  const sim::Scene lying = oneLyingOnALongSide(type);
  const Rendered rendered = render(lying);
  ASSERT_TRUE(rendered.synthetic.truth[0].resting_face.has_value());
  const sim::RestingFaceTruth& resting = *rendered.synthetic.truth[0].resting_face;
  EXPECT_EQ(resting.type, "box_large lying on a side");
  EXPECT_NEAR(resting.dimensions_m.x(), 0.40, 1e-9);
  EXPECT_NEAR(resting.dimensions_m.y(), 0.25, 1e-9);
  EXPECT_NEAR(resting.dimensions_m.z(), 0.30, 1e-9);
  // The face's frame: z up (the camera looks down at it), its centre 0.30 m
  // above the ground.
  const Eigen::Isometry3d world_T_face = lying.world_T_camera * resting.camera_T_face;
  EXPECT_GT(world_T_face.linear().col(2).z(), 0.999);
  EXPECT_NEAR(world_T_face.translation().z(), type.width_m, 1e-9);

  const eval::SceneTruth truth = eval::rigSceneTruth(rendered.synthetic, worldUpInCamera(lying));
  int tops = 0;
  for (const eval::FaceTruth& face : truth.faces)
    if (face.role == eval::FaceRole::kTop)
    {
      ++tops;
      EXPECT_EQ(face.type, "box_large lying on a side");
      EXPECT_TRUE(face.whole_in_view) << face.not_whole_reason;
    }
  EXPECT_EQ(tops, 1);
  const FrontEndResult result = colourFreeOf(catalogue, rendered.frame);
  const eval::FrameMatch match = eval::matchCandidates(result.candidates, truth, rendered.frame.camera);
  ASSERT_EQ(match.candidates.size(), 1u);
  EXPECT_EQ(match.candidates[0].outcome, eval::CandidateOutcome::kWholeTop) << toString(match.candidates[0].outcome);
  EXPECT_FALSE(match.candidates[0].false_complete);
  ASSERT_TRUE(match.candidates[0].has_errors);
  EXPECT_LT(match.candidates[0].errors.centre_mm, 10.0);
  EXPECT_LT(match.candidates[0].errors.rotation_deg, 2.0);
}

/// The scene with its brick moved down the view until the lowest top corner
/// projects `past_border_px` below the image's last row.
sim::Scene withCornerPastBottomBorder(sim::Scene bricks, double past_border_px)
{
  const PinholeCamera camera = PinholeCamera::d415Color1280x720();
  for (int pass = 0; pass < 3; ++pass)
  {
    const Rendered rendered = render(bricks);
    double bottom_px = -1e9, depth_m = 1.0;
    for (const Eigen::Vector3d& corner : topCorners(rendered, 0))
      if (camera.project(corner).y() > bottom_px)
      {
        bottom_px = camera.project(corner).y();
        depth_m = corner.z();
      }
    const double shift_m = (camera.height_px - 1 + past_border_px - bottom_px) * depth_m / camera.fy_px;
    bricks.bricks[0].world_T_brick.translation() += bricks.world_T_camera.linear() * Eigen::Vector3d(0.0, shift_m, 0.0);
  }
  return bricks;
}

/// The blue of the border tests below (1.2 m from the camera, seen at 80
/// deg), moved down until its lowest top corner projects `past_border_px`
/// below the image's last row (negative: above it), rendered.
Rendered blueWithCornerPastBottomBorder(double past_border_px)
{
  return render(withCornerPastBottomBorder(scene({{"blue", {0.0, 0.0, 0.2}, 105.0}}, 80.0), past_border_px));
}

TEST(TopFaceCheck, AFaceWithACornerJustPastTheImageBorderIsNotComplete)
{
  FrontEndParams params;
  params.mode = SegmentationMode::kHsv;
  const FrontEnd front_end(BrickCatalogue::mbzirc2020(), params);

  // 5 px past the border the quad still has the catalogue's size and the
  // edges' profiles (which stay clear of the corners) see real edges, but
  // the corner itself was never seen.
  const Rendered cut = blueWithCornerPastBottomBorder(5.0);
  const FrontEndResult cut_result = front_end.process(cut.frame);
  ASSERT_EQ(cut_result.candidates.size(), 1u);
  EXPECT_FALSE(cut_result.candidates[0].complete);
  EXPECT_NE(cut_result.candidates[0].partial_reason.find("image border"), std::string::npos)
      << cut_result.candidates[0].partial_reason;

  // 25 px inside it is whole.
  const Rendered inside = blueWithCornerPastBottomBorder(-25.0);
  const FrontEndResult inside_result = front_end.process(inside.frame);
  ASSERT_EQ(inside_result.candidates.size(), 1u);
  EXPECT_TRUE(inside_result.candidates[0].complete) << inside_result.candidates[0].partial_reason;
}

TEST(TopFaceCheck, ColourFreeABrickCutByTheBorderIsPartialWithItsTypeInDoubtOrRefused)
{
  // A blue (1.20 m) running out of view. What is seen of it may fit a
  // catalogue top (here its own, a corner short) or none; fitting one within
  // the dimension tolerance, it is published partial, typed by its visible
  // part, the doubt in its reason; fitting none (about 1 m seen), refused.
  FrontEndParams params;
  params.mode = SegmentationMode::kColourFree;
  const FrontEnd front_end(BrickCatalogue::mbzirc2020(), params);

  const Rendered corner_cut = blueWithCornerPastBottomBorder(50.0);
  ASSERT_GT(corner_cut.synthetic.truth[0].visible_fraction, 0.9);
  const FrontEndResult corner_result = front_end.process(corner_cut.frame);
  ASSERT_EQ(corner_result.candidates.size(), 1u);
  const BrickCandidate& seen = corner_result.candidates[0];
  EXPECT_FALSE(seen.complete);
  EXPECT_EQ(seen.type_name, "blue");
  EXPECT_NE(seen.partial_reason.find("image border"), std::string::npos) << seen.partial_reason;
  EXPECT_NE(seen.partial_reason.find("type in doubt"), std::string::npos) << seen.partial_reason;

  const Rendered end_cut = blueWithCornerPastBottomBorder(100.0);
  ASSERT_LT(end_cut.synthetic.truth[0].visible_fraction, 0.85);
  const FrontEndResult end_result = front_end.process(end_cut.frame);
  EXPECT_TRUE(end_result.candidates.empty()) << end_result.candidates.front().type_name;
  ASSERT_FALSE(end_result.rejections.empty());
  EXPECT_NE(end_result.rejections.front().reason.find("image border"), std::string::npos)
      << end_result.rejections.front().reason;
}

/// The red brick under test and a green brick held above it whose corner
/// reaches `overlap_m` over the red top's corner (negative: that far clear).
sim::Scene redWithGreenOverItsCorner(double overlap_m)
{
  const double green_x = 0.15 - overlap_m + 0.3, green_y = 0.1 - overlap_m + 0.1;
  return scene({{"red", {0.0, 0.0, 0.2}, 0.0}, {"green", {green_x, green_y, 0.45}, 0.0}}, 89.0);
}

TEST(TopFaceCheck, ABrickOverOnlyTheCornerOfATopMakesItPartial)
{
  FrontEndParams params;
  params.mode = SegmentationMode::kHsv;
  const FrontEnd front_end(BrickCatalogue::mbzirc2020(), params);

  // The green covers a corner of the red top a little over a centimetre
  // square: the quad still has the red's size and the edges' profiles,
  // which stay clear of the corners, see steps down.
  const Rendered covered = render(redWithGreenOverItsCorner(0.012));
  ASSERT_FALSE(covered.synthetic.truth[0].top_face_complete);
  ASSERT_GT(covered.synthetic.truth[0].visible_fraction, 0.97);
  const FrontEndResult covered_result = front_end.process(covered.frame);
  const BrickCandidate* red = candidateOfType(covered_result, "red");
  ASSERT_NE(red, nullptr);
  EXPECT_FALSE(red->complete) << red->partial_reason;
  EXPECT_NE(red->partial_reason.find("occlusion"), std::string::npos) << red->partial_reason;

  // Held 3 cm clear of the corner, the red top is whole.
  const Rendered clear = render(redWithGreenOverItsCorner(-0.03));
  ASSERT_TRUE(clear.synthetic.truth[0].top_face_complete);
  const FrontEndResult clear_result = front_end.process(clear.frame);
  red = candidateOfType(clear_result, "red");
  ASSERT_NE(red, nullptr);
  EXPECT_TRUE(red->complete) << red->partial_reason;
}

/// A frame of bench_frontend's plan: scene class `kind` (the rig's defaults
/// for it, D4xx depth) at `seed`, run through the colour-free front end
/// (`mode`) at 1280x720 with the world's up direction. Returns the candidates
/// the front end marked complete that are not a whole top of their type.
std::vector<std::string> falseCompleteOnBenchFrame(sim::SceneKind kind, const BrickCatalogue& catalogue,
                                                   std::uint64_t seed, sim::Lighting lighting, SegmentationMode mode)
{
  const sim::Scene scene = sim::SceneGenerator(catalogue, sim::SceneParams::defaultsFor(kind)).generate(seed);
  sim::SensorModel sensor = sim::SensorModel::d4xx();
  sensor.lighting = lighting;
  const Rendered rendered = render(scene, sensor, seed);
  FrontEndParams params;
  params.mode = mode;
  params.roi.up_direction = worldUpInCamera(scene);
  const FrontEndResult result = FrontEnd(catalogue, params).process(rendered.frame);
  const eval::FrameMatch match = eval::matchCandidates(
      result.candidates, eval::rigSceneTruth(rendered.synthetic, params.roi.up_direction), rendered.synthetic.camera);
  std::vector<std::string> false_complete;
  for (std::size_t i = 0; i < match.candidates.size(); ++i)
    if (match.candidates[i].false_complete)
      false_complete.push_back(result.candidates[i].type_name + " " + std::to_string(result.candidates[i].length_m) +
                               " x " + std::to_string(result.candidates[i].width_m) + ": " +
                               eval::toString(match.candidates[i].outcome));
  EXPECT_FALSE(result.candidates.empty());
  return false_complete;
}

// bench_frontend's touching-rows frame 120 (low light, region growing): a
// row of red bricks end to end whose seams the stereo window smoothed over
// merged into one blue-sized face. The two lines where the reds meet each
// show only a trace of a seam (4.9 and 4.7 standard errors, under the 5 one
// line needs): together they make the face partial.
TEST(TopFaceCheck, FourTouchingBricksMergedIntoALongerTypesSizeAreNotComplete)
{
  const std::vector<std::string> false_complete =
      falseCompleteOnBenchFrame(sim::SceneKind::kTouchingRows, BrickCatalogue::mbzirc2020(), 1000003ULL + 4000000ULL + 20,
                                sim::Lighting::kLowLight, SegmentationMode::kRegionGrowing);
  EXPECT_TRUE(false_complete.empty()) << false_complete.front();
}

// bench_frontend's pallet-stack frame 166 (sunlight, colour-free): two boxes
// merged into one face of the large box's size, with seams seen along 3 of
// the 4 lines where they would meet but 0.11 of the face left untiled.
TEST(TopFaceCheck, BoxesMergedIntoALargeBoxsSizeWithSeamsAlongTheCutsAreNotComplete)
{
  const BrickCatalogue boxes = BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/boxes.yaml");
  const std::vector<std::string> false_complete =
      falseCompleteOnBenchFrame(sim::SceneKind::kPalletStack, boxes, 1000003ULL + 6000000ULL + 16,
                                sim::Lighting::kSunlight, SegmentationMode::kColourFree);
  EXPECT_TRUE(false_complete.empty()) << false_complete.front();
}
}  // namespace
}  // namespace brick_pose
