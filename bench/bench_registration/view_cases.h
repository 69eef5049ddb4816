#pragma once
// Whole-cuboid view cases: one brick (each MBZIRC type, and a cardboard box)
// on the ground, seen by the synthetic D415 so that one, two or three of its
// faces are visible; the scan is every pixel of the brick, back-projected
// from the noisy depth (holes skipped, flying pixels at the silhouette kept).
// The single-brick rendering lives here, not in sim/, which is read-only for
// this benchmark.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/registration/point_set.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace bench_registration
{
struct ViewCase
{
  brick_pose::BrickType type;
  int faces_wanted = 0;  ///< 1, 2 or 3: how the camera was placed
  int faces_seen = 0;  ///< faces holding at least 3 % of the brick's pixels
  std::string layout;  ///< "top", "side", "top+side", "side+end", "corner"
  brick_pose::registration::PointSet scan;  ///< camera frame, viewpoint at the origin
  Eigen::Isometry3d camera_T_brick = Eigen::Isometry3d::Identity();
  double distance_m = 0.0;
};

/// The brick types of the view cases: the catalogue's, then a cardboard box
/// with three different dimensions (0.40 x 0.30 x 0.20 m).
std::vector<brick_pose::BrickType> viewCaseTypes(const brick_pose::BrickCatalogue& catalogue);

class RigViewSource
{
public:
  RigViewSource(std::uint64_t seed, std::vector<brick_pose::BrickType> types);

  /// Case `index`: type index % types, faces 1 + (index / types) % 3. Camera
  /// poses that do not show the whole brick in the image are drawn again;
  /// `redraws` counts them.
  ViewCase make(int index, int& redraws) const;

private:
  std::uint64_t seed_;
  std::vector<brick_pose::BrickType> types_;
  brick_pose::PinholeCamera camera_;
  brick_pose::sim::SyntheticRig rig_;
};
}  // namespace bench_registration
