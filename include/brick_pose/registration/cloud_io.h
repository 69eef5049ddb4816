#pragma once
// Reading clouds for the registration tools (.pcd and .ply, via PCL).

#include <cstddef>
#include <string>

#include "brick_pose/registration/point_set.h"

namespace brick_pose
{
namespace registration
{
struct LoadedCloud
{
  PointSet cloud;  ///< with normals when the file has normal_x/y/z fields
  std::size_t dropped_non_finite = 0;  ///< points with NaN/Inf coordinates (e.g. organised clouds)
};

/// Reads a .pcd or .ply file (by extension, case-insensitive). Points with a
/// NaN/Inf coordinate are dropped and counted; normals are dropped when any
/// kept point has an unusable normal. Throws InputError naming the file for a
/// missing/unreadable file, an unknown extension or a cloud without x/y/z.
LoadedCloud loadCloudFile(const std::string& path);
}  // namespace registration
}  // namespace brick_pose
