// How a box rests: the face up as the top of a type of its own, and its
// frame on the box.
#include <gtest/gtest.h>

#include "brick_pose/catalogue/resting.h"
#include "brick_pose/sim/scene.h"
#include "plain_box.h"

namespace brick_pose
{
TEST(Resting, ABoxOnASideOrAnEndIsATypeWhoseTopIsTheFaceUp)
{
  const BrickType small = plainBox("box_small", 0.30, 0.20, 0.15);
  const BrickType side = restingAs(small, Resting::kOnSide);
  EXPECT_EQ(side.name, "box_small lying on a side");
  EXPECT_EQ(side.catalogueName(), "box_small");
  EXPECT_EQ(side.resting, Resting::kOnSide);
  EXPECT_DOUBLE_EQ(side.length_m, 0.30);
  EXPECT_DOUBLE_EQ(side.width_m, 0.15);
  EXPECT_DOUBLE_EQ(side.height_m, 0.20);
  const BrickType end = restingAs(small, Resting::kOnEnd);
  EXPECT_EQ(end.name, "box_small standing on an end");
  EXPECT_DOUBLE_EQ(end.length_m, 0.20);
  EXPECT_DOUBLE_EQ(end.width_m, 0.15);
  EXPECT_DOUBLE_EQ(end.height_m, 0.30);
  // A flat box's end: its height is the shorter edge of the face up.
  const BrickType flat_end = restingAs(plainBox("box_flat", 0.30, 0.20, 0.07), Resting::kOnEnd);
  EXPECT_DOUBLE_EQ(flat_end.length_m, 0.20);
  EXPECT_DOUBLE_EQ(flat_end.width_m, 0.07);
  EXPECT_EQ(restingAs(small, Resting::kUpright).name, "box_small");
  EXPECT_EQ(restingAs(small, Resting::kUpright).catalogueName(), "box_small");
  EXPECT_STREQ(toString(Resting::kOnSide), "on_side");
  EXPECT_STREQ(toString(Resting::kOnEnd), "on_end");
  EXPECT_STREQ(toString(Resting::kUpright), "upright");
}

TEST(Resting, TheCatalogueFindsItsTypesRestingOtherwiseByName)
{
  const BrickCatalogue catalogue({plainBox("box_small", 0.30, 0.20, 0.15)});
  ASSERT_TRUE(catalogue.findResting("box_small").has_value());
  const std::optional<BrickType> side = catalogue.findResting("box_small lying on a side");
  ASSERT_TRUE(side.has_value());
  EXPECT_DOUBLE_EQ(side->width_m, 0.15);
  EXPECT_FALSE(catalogue.findResting("box_large lying on a side").has_value());
  EXPECT_EQ(catalogue.find("box_small lying on a side"), nullptr);
}

TEST(Resting, OnlyAPlainBoxMayBePublishedRestingOtherwise)
{
  BrickType brick = plainBox("green", 0.60, 0.20, 0.20);
  brick.plate_hsv = HsvRange();
  EXPECT_FALSE(mayRestOtherwise(brick));
  EXPECT_TRUE(mayRestOtherwise(plainBox("box_small", 0.30, 0.20, 0.15)));
}

TEST(Resting, AFacesFrameHasItsCentreItsOutwardNormalAndItsLongEdge)
{
  const BrickType small = plainBox("box_small", 0.30, 0.20, 0.15);
  // +Y (a long side): 0.30 x 0.15, centred half a width out and half the
  // height down from the top's centre.
  const Eigen::Isometry3d side = sim::brickTFace(small, sim::CuboidFace::kPlusY);
  EXPECT_TRUE(side.translation().isApprox(Eigen::Vector3d(0.0, 0.10, -0.075)));
  EXPECT_TRUE(side.linear().col(2).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(side.linear().col(0).isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_NEAR(side.linear().determinant(), 1.0, 1e-12);
  // -X (an end): 0.20 x 0.15, its long edge along y.
  const Eigen::Isometry3d end = sim::brickTFace(small, sim::CuboidFace::kMinusX);
  EXPECT_TRUE(end.translation().isApprox(Eigen::Vector3d(-0.15, 0.0, -0.075)));
  EXPECT_TRUE(end.linear().col(2).isApprox(-Eigen::Vector3d::UnitX()));
  EXPECT_TRUE(end.linear().col(0).isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_NEAR(end.linear().determinant(), 1.0, 1e-12);
  EXPECT_TRUE(sim::brickTFace(small, sim::CuboidFace::kTop).isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_EQ(sim::restingWithFaceUp(sim::CuboidFace::kMinusY), Resting::kOnSide);
  EXPECT_EQ(sim::restingWithFaceUp(sim::CuboidFace::kPlusX), Resting::kOnEnd);
  EXPECT_EQ(sim::restingWithFaceUp(sim::CuboidFace::kTop), Resting::kUpright);
}
}  // namespace brick_pose
