#include "brick_pose/frame/organized_cloud.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace
{
/// (u - cx) / fx for every column and (v - cy) / fy for every row: the
/// inverse projection then costs two multiplications per pixel.
struct RayFactors
{
  std::vector<float> x_per_column;
  std::vector<float> y_per_row;

  RayFactors(const PinholeCamera& camera, int width_px, int height_px)
    : x_per_column(static_cast<std::size_t>(width_px)), y_per_row(static_cast<std::size_t>(height_px))
  {
    for (int u = 0; u < width_px; ++u)
      x_per_column[u] = static_cast<float>((u - camera.cx_px) / camera.fx_px);
    for (int v = 0; v < height_px; ++v)
      y_per_row[v] = static_cast<float>((v - camera.cy_px) / camera.fy_px);
  }
};

/// An organised cloud of width x height points (to be filled), in the
/// frame's coordinate frame, for a reduced copy of the frame.
pcl::PointCloud<pcl::PointXYZ>::Ptr reducedOrganizedCloud(const RgbdFrame& frame, int width, int height)
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(static_cast<std::size_t>(width) * height);
  cloud->width = static_cast<std::uint32_t>(width);
  cloud->height = static_cast<std::uint32_t>(height);
  cloud->is_dense = false;
  cloud->header.frame_id = frame.frame_id;
  return cloud;
}
}  // namespace

void fillOrganizedCloud(const RgbdFrame& frame, pcl::PointCloud<pcl::PointXYZRGB>& cloud)
{
  const int width = frame.width_px();
  const int height = frame.height_px();
  const RayFactors factors(frame.camera, width, height);

  // Resizing a cloud constructs every point; a reused cloud of the right size
  // skips that and the page faults of 30 MB of fresh memory.
  const std::size_t count = static_cast<std::size_t>(width) * height;
  if (cloud.size() != count) cloud.resize(count);
  cloud.width = static_cast<std::uint32_t>(width);
  cloud.height = static_cast<std::uint32_t>(height);
  cloud.is_dense = false;
  cloud.header.frame_id = frame.frame_id;
  cloud.header.stamp = static_cast<std::uint64_t>(frame.stamp_ns / 1000);  // PCL stamps are µs

  pcl::PointXYZRGB* out = cloud.points.data();
  for (int v = 0; v < height; ++v)
  {
    const float* depth_row = frame.depth_m.ptr<float>(v);
    const std::uint8_t* rgb_row = frame.rgb.ptr<std::uint8_t>(v);
    const float* x_factor = factors.x_per_column.data();
    const float y_factor = factors.y_per_row[v];
    for (int u = 0; u < width; ++u, ++out)
    {
      // No branch for holes: NaN depth makes x, y and z NaN by itself.
      const float z = depth_row[u];
      out->x = x_factor[u] * z;
      out->y = y_factor * z;
      out->z = z;
      out->r = rgb_row[3 * u];
      out->g = rgb_row[3 * u + 1];
      out->b = rgb_row[3 * u + 2];
      out->a = 255;
    }
  }
}

pcl::PointCloud<pcl::PointXYZRGB>::Ptr makeOrganizedCloud(const RgbdFrame& frame)
{
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZRGB>);
  fillOrganizedCloud(frame, *cloud);
  return cloud;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr backProjectPixels(const RgbdFrame& frame,
                                                      const std::vector<int>& pixel_indices,
                                                      std::vector<int>* kept_pixels)
{
  const int width = frame.width_px();
  const int pixel_count = width * frame.height_px();
  const double fx_inv = 1.0 / frame.camera.fx_px;
  const double fy_inv = 1.0 / frame.camera.fy_px;
  const float* depth = frame.depth_m.ptr<float>(0);  // validated frames are continuous
  const bool continuous = frame.depth_m.isContinuous();

  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->reserve(pixel_indices.size());
  if (kept_pixels) kept_pixels->clear();
  for (const int index : pixel_indices)
  {
    if (index < 0 || index >= pixel_count) throw InputError("backProjectPixels: pixel index out of range");
    const int v = index / width;
    const int u = index - v * width;
    const float z = continuous ? depth[index] : frame.depthAt(u, v);
    if (std::isnan(z)) continue;
    cloud->push_back(pcl::PointXYZ(static_cast<float>((u - frame.camera.cx_px) * fx_inv * z),
                                   static_cast<float>((v - frame.camera.cy_px) * fy_inv * z), z));
    if (kept_pixels) kept_pixels->push_back(index);
  }
  cloud->header.frame_id = frame.frame_id;
  cloud->is_dense = true;
  return cloud;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr makeStridedCloud(const RgbdFrame& frame, int stride,
                                                     std::vector<int>& source_pixels)
{
  if (stride < 1) throw InputError("makeStridedCloud: stride must be >= 1");
  const int width = frame.width_px();
  const int out_width = (width + stride - 1) / stride;
  const int out_height = (frame.height_px() + stride - 1) / stride;
  const RayFactors factors(frame.camera, width, frame.height_px());
  const float nan = std::numeric_limits<float>::quiet_NaN();

  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud = reducedOrganizedCloud(frame, out_width, out_height);
  source_pixels.resize(cloud->size());

  std::size_t i = 0;
  for (int row = 0; row < out_height; ++row)
  {
    const int v = row * stride;
    const float* depth_row = frame.depth_m.ptr<float>(v);
    for (int col = 0; col < out_width; ++col, ++i)
    {
      const int u = col * stride;
      source_pixels[i] = v * width + u;
      pcl::PointXYZ& point = (*cloud)[i];
      const float z = depth_row[u];
      if (std::isnan(z))
      {
        point.x = point.y = point.z = nan;
        continue;
      }
      point.x = factors.x_per_column[u] * z;
      point.y = factors.y_per_row[v] * z;
      point.z = z;
    }
  }
  return cloud;
}
pcl::PointCloud<pcl::PointXYZ>::Ptr makeBlockMedianCloud(const RgbdFrame& frame, int block,
                                                         std::vector<int>& source_pixels)
{
  if (block < 1) throw InputError("makeBlockMedianCloud: block must be >= 1");
  const int width = frame.width_px();
  const int height = frame.height_px();
  const int out_width = width / block;
  const int out_height = height / block;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::size_t min_valid = static_cast<std::size_t>(std::max(1, block * block / 4));

  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud = reducedOrganizedCloud(frame, out_width, out_height);
  source_pixels.resize(cloud->size());

  std::vector<float> depths;
  depths.reserve(static_cast<std::size_t>(block) * block);
  std::size_t i = 0;
  for (int row = 0; row < out_height; ++row)
    for (int col = 0; col < out_width; ++col, ++i)
    {
      depths.clear();
      for (int v = row * block; v < (row + 1) * block; ++v)
      {
        const float* depth_row = frame.depth_m.ptr<float>(v);
        for (int u = col * block; u < (col + 1) * block; ++u)
          if (!std::isnan(depth_row[u])) depths.push_back(depth_row[u]);
      }
      const int u_centre = col * block + block / 2, v_centre = row * block + block / 2;
      source_pixels[i] = v_centre * width + u_centre;
      pcl::PointXYZ& point = (*cloud)[i];
      if (depths.size() < min_valid)
      {
        point.x = point.y = point.z = nan;
        continue;
      }
      auto middle = depths.begin() + static_cast<std::ptrdiff_t>(depths.size() / 2);
      std::nth_element(depths.begin(), middle, depths.end());
      const double z = *middle;
      // The block's centre is at (col + 0.5) * block - 0.5 in pixel-centre coordinates.
      const double u = (col + 0.5) * block - 0.5, v = (row + 0.5) * block - 0.5;
      const Eigen::Vector3d p = frame.camera.backProject(u, v, z);
      point.x = static_cast<float>(p.x());
      point.y = static_cast<float>(p.y());
      point.z = static_cast<float>(p.z());
    }
  return cloud;
}
}  // namespace brick_pose
