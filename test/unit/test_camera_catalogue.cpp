#include <gtest/gtest.h>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/errors.h"

namespace brick_pose
{
TEST(PinholeCamera, BackProjectionInvertsProjection)
{
  const PinholeCamera camera = PinholeCamera::d415Color1280x720();
  const Eigen::Vector3d point(0.31, -0.12, 1.37);
  const Eigen::Vector2d pixel = camera.project(point);
  EXPECT_TRUE(camera.backProject(pixel.x(), pixel.y(), point.z()).isApprox(point, 1e-12));
}

TEST(PinholeCamera, ValidateNamesTheBadField)
{
  PinholeCamera camera = PinholeCamera::d415Color1280x720();
  camera.fx_px = 0.0;
  try
  {
    camera.validate();
    FAIL() << "zero focal length accepted";
  }
  catch (const ConfigError& e)
  {
    EXPECT_NE(std::string(e.what()).find("fx"), std::string::npos) << e.what();
  }
}

TEST(PinholeCamera, ScalingKeepsTheImageCorner)
{
  const PinholeCamera camera = PinholeCamera::d415Color1280x720();
  const PinholeCamera half = camera.scaled(0.5);
  EXPECT_EQ(half.width_px, 640);
  // The ray through the full image's corner must be the half image's corner ray.
  EXPECT_TRUE(camera.ray(-0.5, -0.5).isApprox(half.ray(-0.5, -0.5), 1e-12));
}

TEST(HsvRange, WrapsThroughZeroForReds)
{
  HsvRange red;
  red.min = {{170, 100, 20}};
  red.max = {{7, 255, 255}};
  EXPECT_TRUE(red.contains(175, 200, 100));
  EXPECT_TRUE(red.contains(3, 200, 100));
  EXPECT_FALSE(red.contains(60, 200, 100));
  EXPECT_FALSE(red.contains(3, 50, 100));
}

TEST(BrickCatalogue, ConfigFileMatchesBuiltInMbzircCatalogue)
{
  const BrickCatalogue file = BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/bricks.yaml");
  const BrickCatalogue builtin = BrickCatalogue::mbzirc2020();
  ASSERT_EQ(file.types().size(), 4u);
  ASSERT_EQ(file.types().size(), builtin.types().size());
  for (const BrickType& expected : builtin.types())
  {
    const BrickType& actual = file.at(expected.name);
    EXPECT_DOUBLE_EQ(actual.length_m, expected.length_m) << expected.name;
    EXPECT_DOUBLE_EQ(actual.width_m, expected.width_m) << expected.name;
    EXPECT_DOUBLE_EQ(actual.height_m, expected.height_m) << expected.name;
    EXPECT_EQ(actual.plate_rgb, expected.plate_rgb) << expected.name;
    ASSERT_TRUE(actual.hasPlateColour()) << expected.name;
    EXPECT_EQ(actual.plate_hsv->min, expected.plate_hsv->min) << expected.name;
    EXPECT_EQ(actual.plate_hsv->max, expected.plate_hsv->max) << expected.name;
  }
  EXPECT_DOUBLE_EQ(file.at("orange").length_m, 1.80);
}

TEST(BrickCatalogue, UserTypeIsAccepted)
{
  const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(
      "bricks:\n"
      "  - name: shoebox\n"
      "    length_m: 0.33\n"
      "    width_m: 0.19\n"
      "    height_m: 0.12\n"
      "    hsv_min: [0, 0, 200]\n"
      "    hsv_max: [180, 40, 255]\n");
  ASSERT_NE(catalogue.find("shoebox"), nullptr);
  EXPECT_DOUBLE_EQ(catalogue.find("shoebox")->height_m, 0.12);
}

TEST(BrickCatalogue, ErrorsNameTheProblem)
{
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  try
  {
    catalogue.at("purple");
    FAIL();
  }
  catch (const ConfigError& e)
  {
    EXPECT_NE(std::string(e.what()).find("purple"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("orange"), std::string::npos) << "lists the known types";
  }
  EXPECT_THROW(BrickCatalogue::fromYamlString("bricks:\n  - name: x\n    length_m: 0.1\n"), ConfigError);
  EXPECT_THROW(BrickCatalogue::fromYamlString("other: 1\n"), ConfigError);
  EXPECT_THROW(BrickCatalogue::fromYamlFile("/nonexistent/bricks.yaml"), ConfigError);
  try
  {
    BrickCatalogue::fromYamlString(
        "bricks:\n  - name: flat\n    length_m: -1\n    width_m: 0.1\n    height_m: 0.1\n"
        "    hsv_min: [0, 0, 0]\n    hsv_max: [10, 255, 255]\n");
    FAIL();
  }
  catch (const ConfigError& e)
  {
    EXPECT_NE(std::string(e.what()).find("length_m"), std::string::npos) << e.what();
  }
}

TEST(BrickCatalogue, TypeWithoutHsvRangeHasNoPlateColour)
{
  const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(
      "bricks:\n"
      "  - name: carton\n"
      "    length_m: 0.40\n"
      "    width_m: 0.30\n"
      "    height_m: 0.25\n");
  ASSERT_NE(catalogue.find("carton"), nullptr);
  EXPECT_FALSE(catalogue.at("carton").hasPlateColour());
  try
  {
    BrickCatalogue::fromYamlString(
        "bricks:\n  - name: half\n    length_m: 0.4\n    width_m: 0.3\n    height_m: 0.2\n"
        "    hsv_min: [0, 0, 0]\n");
    FAIL() << "hsv_min without hsv_max accepted";
  }
  catch (const ConfigError& e)
  {
    EXPECT_NE(std::string(e.what()).find("hsv_max"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("half"), std::string::npos) << e.what();
  }
}

TEST(BrickCatalogue, BoxesConfigHoldsPlainCardboardBoxes)
{
  const BrickCatalogue boxes = BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/boxes.yaml");
  ASSERT_GE(boxes.types().size(), 2u);
  for (const BrickType& type : boxes.types())
    EXPECT_FALSE(type.hasPlateColour()) << type.name;
  EXPECT_DOUBLE_EQ(boxes.at("box_large").height_m, 0.25);
  EXPECT_DOUBLE_EQ(boxes.at("box_small").length_m, 0.30);
}

TEST(BrickCatalogue, ARestingItemCouldRiseByAnyOfItsExtentsOrTwoStacked)
{
  const BrickCatalogue boxes = BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/boxes.yaml");
  // box_flat lying flat (0.07), box_small on its side (0.20), two box_flat
  // (0.14), box_large on an end (0.40).
  for (const double height_m : {0.07, 0.20, 0.14, 0.40})
    EXPECT_TRUE(boxes.couldRiseTo(height_m + 0.01, 0.015)) << height_m;
  // box_large beside box_small (0.10) and beside box_flat (0.18): nothing
  // of the catalogue lying on the lower box rises that high.
  EXPECT_FALSE(boxes.couldRiseTo(0.10, 0.015));
  EXPECT_FALSE(boxes.couldRiseTo(0.18, 0.015));
  // box_small beside box_flat (0.08) is within the margin of a box_flat
  // lying there: ambiguous.
  EXPECT_TRUE(boxes.couldRiseTo(0.08, 0.015));
  EXPECT_FALSE(BrickCatalogue().couldRiseTo(0.1, 0.015));
}
}  // namespace brick_pose
