// Cardboard boxes without a plate colour: tape, flap seam, labels and
// barcodes in colour only.

#include <gtest/gtest.h>

#include <array>
#include <set>

#include "brick_pose/sim/box_print.h"
#include "brick_pose/sim/d415_modes.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace sim
{
namespace
{
BrickType carton()
{
  BrickType box;
  box.name = "carton";
  box.length_m = 0.40;
  box.width_m = 0.30;
  box.height_m = 0.25;
  box.plate_rgb = box.body_rgb = {{186, 146, 102}};
  return box;
}

SurfaceMarkings markings(SurfaceMarkings::Tape tape, int labels, std::uint64_t seed = 7)
{
  SurfaceMarkings result;
  result.cardboard = true;
  result.tape = tape;
  result.labels = labels;
  result.seed = seed;
  return result;
}

const Eigen::Vector3d kCardboard(186.0, 146.0, 102.0);

double grey(const Eigen::Vector3d& rgb) { return rgb.mean(); }

/// Largest grey level over a grid on the top face.
double brightestOnTop(const BoxPrint& print)
{
  double brightest = 0.0;
  for (double x = -0.19; x <= 0.19; x += 0.005)
    for (double y = -0.14; y <= 0.14; y += 0.005)
      brightest = std::max(brightest, grey(print.colourAt(kCardboard, CuboidFace::kTop, {x, y, 0.0}, 0.001)));
  return brightest;
}
}  // namespace

TEST(BoxPrint, BrownTapeRunsAlongTheTopAndDownTheEnds)
{
  const BoxPrint print(carton(), markings(SurfaceMarkings::Tape::kBrown, 0));
  const double tape = grey(print.colourAt(kCardboard, CuboidFace::kTop, {0.1, 0.0, 0.0}, 0.001));
  const double board = grey(print.colourAt(kCardboard, CuboidFace::kTop, {0.1, 0.1, 0.0}, 0.001));
  EXPECT_LT(tape, 0.85 * board);
  const double end_tape = grey(print.colourAt(kCardboard, CuboidFace::kPlusX, {0.2, 0.0, -0.03}, 0.001));
  const double end_below = grey(print.colourAt(kCardboard, CuboidFace::kPlusX, {0.2, 0.0, -0.15}, 0.001));
  EXPECT_LT(end_tape, 0.85 * end_below);
}

TEST(BoxPrint, UntapedFlapSeamIsADarkLineThatBlursWithDistance)
{
  const BoxPrint print(carton(), markings(SurfaceMarkings::Tape::kNone, 0));
  const double seam_near = grey(print.colourAt(kCardboard, CuboidFace::kTop, {0.0, 0.0, 0.0}, 0.001));
  const double seam_far = grey(print.colourAt(kCardboard, CuboidFace::kTop, {0.0, 0.0, 0.0}, 0.01));
  const double board = grey(print.colourAt(kCardboard, CuboidFace::kTop, {0.0, 0.05, 0.0}, 0.001));
  EXPECT_LT(seam_near, 0.5 * board) << "a 2 mm seam fills a 1 mm pixel";
  EXPECT_GT(seam_far, seam_near) << "a 1 cm pixel averages the seam with the board beside it";
  EXPECT_LT(seam_far, board);
}

TEST(BoxPrint, LabelsAreWhitePaperOnTheTop)
{
  EXPECT_LT(brightestOnTop(BoxPrint(carton(), markings(SurfaceMarkings::Tape::kNone, 0))), 200.0);
  EXPECT_GT(brightestOnTop(BoxPrint(carton(), markings(SurfaceMarkings::Tape::kNone, 2))), 220.0);
  // A label's barcode: dark bars on the paper, seen from close.
  const BoxPrint print(carton(), markings(SurfaceMarkings::Tape::kNone, 1, 3));
  int dark_on_label = 0, white = 0;
  for (double x = -0.19; x <= 0.19; x += 0.0005)
    for (double y = -0.14; y <= 0.14; y += 0.002)
    {
      const double level = grey(print.colourAt(kCardboard, CuboidFace::kTop, {x, y, 0.0}, 0.0003));
      white += level > 220.0 ? 1 : 0;
      dark_on_label += level < 60.0 ? 1 : 0;
    }
  EXPECT_GT(white, 100);
  EXPECT_GT(dark_on_label, 100) << "text and bars";
}

TEST(BoxPrint, MarkingsChangeColourOnlyNotDepth)
{
  SceneParams params = SceneParams::defaultsFor(SceneKind::kPalletLayer);
  const BrickCatalogue boxes({carton()});
  const Scene printed = SceneGenerator(boxes, params).generate(2);
  params.markings = false;
  const Scene plain = SceneGenerator(boxes, params).generate(2);
  ASSERT_EQ(printed.bricks.size(), plain.bricks.size());
  int labelled = 0;
  for (std::size_t i = 0; i < printed.bricks.size(); ++i)
  {
    EXPECT_TRUE(printed.bricks[i].markings.cardboard);
    EXPECT_FALSE(plain.bricks[i].markings.cardboard);
    EXPECT_TRUE(printed.bricks[i].world_T_brick.isApprox(plain.bricks[i].world_T_brick, 0.0)) << "same layout";
    labelled += printed.bricks[i].markings.labels;
  }
  EXPECT_GT(labelled, 0);
  const SyntheticRig rig(d415ColourMode("640x480"), SensorModel::d4xx());
  const SyntheticFrame a = rig.render(printed, 5), b = rig.render(plain, 5);
  EXPECT_EQ(cv::norm(a.depth_mm, b.depth_mm, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a.rgb, b.rgb, cv::NORM_L1), 0.0);
}

TEST(BoxPrint, PrintedPackagingHasPatchesOfColourOnEveryFace)
{
  SurfaceMarkings printed = markings(SurfaceMarkings::Tape::kNone, 0, 11);
  printed.printed = true;
  const BoxPrint print(carton(), printed);
  for (const CuboidFace face : {CuboidFace::kTop, CuboidFace::kPlusX, CuboidFace::kMinusY})
  {
    std::set<std::array<int, 3>> colours;
    for (double a = -0.12; a <= 0.12; a += 0.01)
      for (double b = -0.12; b <= 0.0; b += 0.01)
      {
        const Eigen::Vector3d point = face == CuboidFace::kTop     ? Eigen::Vector3d(a, b + 0.06, 0.0)
                                      : face == CuboidFace::kPlusX ? Eigen::Vector3d(0.2, a, b)
                                                                   : Eigen::Vector3d(a, -0.15, b);
        const Eigen::Vector3d colour = print.colourAt(kCardboard, face, point, 0.001);
        colours.insert({{int(colour[0]), int(colour[1]), int(colour[2])}});
      }
    EXPECT_GE(colours.size(), 3u) << "face " << int(face);
  }
}

TEST(BoxPrint, TableBoxesAreMostlyPrintedPackaging)
{
  const SceneGenerator generator(BrickCatalogue({carton()}), SceneParams::defaultsFor(SceneKind::kTableBoxes));
  int printed = 0, boxes = 0;
  for (std::uint64_t seed = 0; seed < 20; ++seed)
    for (const PlacedBrick& brick : generator.generate(seed).bricks)
    {
      ++boxes;
      printed += brick.markings.printed ? 1 : 0;
    }
  EXPECT_GT(printed, boxes / 2);
  EXPECT_LT(printed, boxes);
}

TEST(BoxPrint, BricksWithAPlateColourStayPlain)
{
  SceneParams params = SceneParams::defaultsFor(SceneKind::kTouchingRows);
  const Scene scene = SceneGenerator(BrickCatalogue::mbzirc2020(), params).generate(1);
  for (const PlacedBrick& brick : scene.bricks)
    EXPECT_FALSE(brick.markings.cardboard) << brick.type.name;
}
}  // namespace sim
}  // namespace brick_pose
