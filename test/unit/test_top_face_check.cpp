// The top-face check on the synthetic D415: which way is up, side faces of
// the catalogue height below a top's edges, and side faces never taken for
// tops.
#include <cmath>

#include <gtest/gtest.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/roi/side_faces.h"
#include "brick_pose/roi/up_direction.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace
{
/// Bricks given by (type, x, y, z of the top face centre, yaw) seen from
/// `elevation_deg` above the horizon at 1.2 m from the first brick's top.
sim::Scene scene(const std::vector<std::tuple<std::string, Eigen::Vector3d, double>>& bricks, double elevation_deg)
{
  sim::Scene result;
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
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

Rendered render(const sim::Scene& scene)
{
  Rendered rendered;
  rendered.synthetic = sim::SyntheticRig(PinholeCamera::d415Color1280x720(), sim::SensorModel()).render(scene, 5);
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
}  // namespace
}  // namespace brick_pose
