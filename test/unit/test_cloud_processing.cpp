// Cloud processing: each switchable PCL step on small synthetic clouds.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "brick_pose/cloud/cloud_processor.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/geometry/plane_fit.h"

namespace brick_pose
{
namespace
{
/// A fronto-parallel square patch at depth z with optional depth noise.
pcl::PointCloud<pcl::PointXYZ>::Ptr patch(double z_m, double size_m, double step_m, double noise_m = 0.0)
{
  std::mt19937 generator(7);
  std::normal_distribution<double> noise(0.0, noise_m > 0.0 ? noise_m : 1.0);
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  for (double x = 0.0; x < size_m; x += step_m)
    for (double y = 0.0; y < size_m; y += step_m)
      cloud->push_back(pcl::PointXYZ(x, y, z_m + (noise_m > 0.0 ? noise(generator) : 0.0)));
  return cloud;
}

CloudProcessorParams allOff()
{
  CloudProcessorParams params;
  params.crop_enabled = false;
  params.outlier_removal_enabled = false;
  params.voxel_enabled = false;
  params.mls_enabled = false;
  return params;
}

TEST(CloudProcessor, CropKeepsTheDepthBandAndDropsNan)
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->push_back(pcl::PointXYZ(0, 0, 0.1f));
  cloud->push_back(pcl::PointXYZ(0, 0, 1.0f));
  cloud->push_back(pcl::PointXYZ(0, 0, 2.9f));
  cloud->push_back(pcl::PointXYZ(0, 0, 3.5f));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  cloud->push_back(pcl::PointXYZ(nan, nan, nan));
  const auto cropped = CloudProcessor().crop(cloud);
  ASSERT_EQ(cropped->size(), 2u);
  EXPECT_FLOAT_EQ((*cropped)[0].z, 1.0f);
  EXPECT_FLOAT_EQ((*cropped)[1].z, 2.9f);
}

TEST(CloudProcessor, OrganisedCropStaysOrganised)
{
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZRGB>(2, 2));
  for (auto& p : *cloud) p.z = 1.0f;
  (*cloud)[3].z = 5.0f;
  const auto cropped = CloudProcessor().cropOrganized(cloud);
  EXPECT_EQ(cropped->width, 2u);
  EXPECT_EQ(cropped->height, 2u);
  EXPECT_TRUE(std::isnan((*cropped)[3].z));
  EXPECT_FLOAT_EQ((*cropped)[0].z, 1.0f);
}

TEST(CloudProcessor, VoxelGridThinsToOnePointPerLeaf)
{
  const auto cloud = patch(1.0, 0.1, 0.001);  // 100 x 100 points, 1 mm apart
  CloudProcessorParams params = allOff();
  params.voxel_leaf_m = 0.01;
  const auto thinned = CloudProcessor(params).downsample(cloud);
  EXPECT_GE(thinned->size(), 100u);  // 10 x 10 leaves (plus boundary leaves)
  EXPECT_LE(thinned->size(), 121u);
}

TEST(CloudProcessor, OutlierRemovalDropsIsolatedPoints)
{
  auto cloud = patch(1.0, 0.1, 0.005);
  const std::size_t plane_points = cloud->size();
  cloud->push_back(pcl::PointXYZ(0.05f, 0.05f, 1.3f));
  cloud->push_back(pcl::PointXYZ(0.5f, 0.5f, 1.0f));
  const auto kept = CloudProcessor().removeOutliers(cloud);
  EXPECT_GE(kept->size(), plane_points - plane_points / 50);
  EXPECT_LE(kept->size(), plane_points);
  for (const auto& p : *kept)
  {
    EXPECT_LT(p.z, 1.1f);
    EXPECT_LT(p.x, 0.2f);
  }
}

TEST(CloudProcessor, MlsSmoothsNoiseAndGivesPlaneNormals)
{
  const auto cloud = patch(1.0, 0.15, 0.004, 0.002);
  CloudProcessorParams params = allOff();
  params.mls_enabled = true;
  params.mls_search_radius_m = 0.02;
  const ProcessedCloud processed = CloudProcessor(params).process(cloud);
  ASSERT_TRUE(processed.with_normals);
  ASSERT_GT(processed.with_normals->size(), cloud->size() / 2);
  // Away from the border (where the neighbourhood is one-sided) the normals
  // are those of the plane.
  int interior = 0, aligned = 0;
  for (const auto& p : *processed.with_normals)
  {
    if (p.x < 0.03f || p.x > 0.12f || p.y < 0.03f || p.y > 0.12f) continue;
    ++interior;
    if (std::abs(p.normal_z) > std::cos(5.0 * M_PI / 180.0)) ++aligned;
  }
  ASSERT_GT(interior, 100);
  EXPECT_GT(aligned, static_cast<int>(0.95 * interior));
  const double rms_before = fitPlane(*cloud, PlaneFitParams{0}).rms_m;
  const double rms_after = fitPlane(*processed.points, PlaneFitParams{0}).rms_m;
  EXPECT_LT(rms_after, 0.5 * rms_before);
}

TEST(CloudProcessor, DisabledStepsReturnACopyAndNoTime)
{
  const auto cloud = patch(1.0, 0.05, 0.005);
  const ProcessedCloud processed = CloudProcessor(allOff()).process(cloud);
  EXPECT_NE(processed.points.get(), cloud.get());
  EXPECT_EQ(processed.points->size(), cloud->size());
  EXPECT_FALSE(processed.with_normals);
  EXPECT_EQ(processed.timings.total(), 0.0);
}

TEST(CloudProcessor, DefaultChainRunsEveryEnabledStep)
{
  auto cloud = patch(1.0, 0.2, 0.002, 0.001);
  cloud->push_back(pcl::PointXYZ(0.0f, 0.0f, 4.0f));  // beyond the crop
  CloudProcessorParams params;
  params.mls_enabled = true;
  const ProcessedCloud processed = CloudProcessor(params).process(cloud);
  EXPECT_LT(processed.points->size(), cloud->size() / 3);  // 5 mm voxels on a 2 mm grid
  EXPECT_GT(processed.timings.mls_ms, 0.0);
  for (const auto& p : *processed.points) EXPECT_LT(p.z, 1.05f);
}

TEST(CloudProcessor, RejectsBadParametersNamingTheField)
{
  CloudProcessorParams params;
  params.max_depth_m = 0.1;
  try
  {
    CloudProcessor processor(params);
    FAIL() << "expected ConfigError";
  }
  catch (const ConfigError& error)
  {
    EXPECT_NE(std::string(error.what()).find("max_depth_m"), std::string::npos);
  }
  params = CloudProcessorParams();
  params.voxel_leaf_m = 0.0;
  EXPECT_THROW(CloudProcessor{params}, ConfigError);
}
}  // namespace
}  // namespace brick_pose
