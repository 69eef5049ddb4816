#include "brick_pose/registration/cloud_io.h"

#include <algorithm>
#include <cctype>
#include <fstream>

#include <pcl/PCLPointCloud2.h>
#include <pcl/conversions.h>
#include <pcl/io/pcd_io.h>
#include <pcl/io/ply_io.h>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace registration
{
namespace
{
std::string lowerExtension(const std::string& path)
{
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return "";
  std::string extension = path.substr(dot + 1);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

bool hasField(const pcl::PCLPointCloud2& blob, const std::string& name)
{
  return std::any_of(blob.fields.begin(), blob.fields.end(),
                     [&](const pcl::PCLPointField& field) { return field.name == name; });
}
}  // namespace

LoadedCloud loadCloudFile(const std::string& path)
{
  const std::string extension = lowerExtension(path);
  if (extension != "pcd" && extension != "ply")
    throw InputError("'" + path + "': unknown cloud format (expected .pcd or .ply)");
  if (!std::ifstream(path).good())
    throw InputError("'" + path + "': cannot open file");

  pcl::PCLPointCloud2 blob;
  if (extension == "pcd")
  {
    // PCL 1.13's PCDReader::read crashes on some malformed files: check the
    // header on its own first.
    pcl::PCDReader reader;
    Eigen::Vector4f origin;
    Eigen::Quaternionf orientation;
    int version = 0;
    int data_type = 0;
    unsigned int data_index = 0;
    if (reader.readHeader(path, blob, origin, orientation, version, data_type, data_index) < 0 ||
        blob.fields.empty() || blob.width * blob.height == 0)
      throw InputError("'" + path + "': not a readable .pcd file (bad header or no points)");
  }
  // PCL prints its own diagnostics on failure; the return code decides.
  const int status = extension == "pcd" ? pcl::io::loadPCDFile(path, blob) : pcl::io::loadPLYFile(path, blob);
  if (status < 0)
    throw InputError("'" + path + "': not a readable ." + extension + " file");
  if (!hasField(blob, "x") || !hasField(blob, "y") || !hasField(blob, "z"))
    throw InputError("'" + path + "': the cloud has no x/y/z fields");

  const bool with_normals = hasField(blob, "normal_x") && hasField(blob, "normal_y") && hasField(blob, "normal_z");
  PointSet all;
  if (with_normals)
  {
    pcl::PointCloud<pcl::PointNormal> cloud;
    pcl::fromPCLPointCloud2(blob, cloud);
    all = fromPcl(cloud);
  }
  else
  {
    pcl::PointCloud<pcl::PointXYZ> cloud;
    pcl::fromPCLPointCloud2(blob, cloud);
    all = fromPcl(cloud);
  }

  LoadedCloud loaded;
  bool normals_usable = with_normals;
  for (std::size_t i = 0; i < all.size(); ++i)
  {
    if (!all.points[i].allFinite())
    {
      ++loaded.dropped_non_finite;
      continue;
    }
    loaded.cloud.points.push_back(all.points[i]);
    if (with_normals)
    {
      const Eigen::Vector3d& n = all.normals[i];
      normals_usable = normals_usable && n.allFinite() && n.squaredNorm() > 1e-12;
      loaded.cloud.normals.push_back(n);
    }
  }
  if (!normals_usable)
    loaded.cloud.normals.clear();
  return loaded;
}
}  // namespace registration
}  // namespace brick_pose
