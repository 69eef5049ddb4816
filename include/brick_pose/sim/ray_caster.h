#pragma once
// Exact ray casting of cuboids on a ground plane: the geometry half of the
// synthetic rig, with no noise and no colour.

#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/sim/scene.h"

namespace brick_pose
{
namespace sim
{
/// What a ray hit. brick_index is an index into Scene::bricks, kGround for
/// the ground plane or kNothing.
struct RayHit
{
  static constexpr int kNothing = -2;
  static constexpr int kGround = -1;

  int brick_index = kNothing;
  CuboidFace face = CuboidFace::kNone;
  double ray_t = 0.0;  // point = origin + ray_t * direction
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  /// Where a brick was hit, in that brick's frame (zero for the ground).
  Eigen::Vector3d point_brick = Eigen::Vector3d::Zero();

  bool hitSomething() const { return brick_index != kNothing; }
  bool hitBrick() const { return brick_index >= 0; }
};

/// The scene expressed in the camera's optical frame, ready for rays.
class RayCaster
{
public:
  RayCaster(const Scene& scene, const PinholeCamera& camera);

  /// Nearest hit along origin + t * direction, t > min_t.
  RayHit cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double min_t = 1e-9) const;

  /// Nearest hit through pixel (u, v) from the camera centre. ray_t is then
  /// the depth Z along the optical axis, since the ray has z = 1.
  RayHit castPixel(double u_px, double v_px) const;

  /// True when a brick lies strictly between `from` and `to`.
  bool blocked(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

  /// Brick hits only, tested against one brick.
  RayHit castBrick(int brick_index, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                   double min_t = 1e-9) const;
  RayHit castGround(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double min_t = 1e-9) const;

  /// Pixel rectangle [u_min, u_max] x [v_min, v_max] (clipped to the image)
  /// that can contain brick `index`; empty (u_min > u_max) when it cannot be seen.
  Eigen::Vector4i pixelBounds(int brick_index) const;

  const std::vector<Eigen::Isometry3d>& cameraTBricks() const { return camera_T_bricks_; }

private:
  struct Box
  {
    Eigen::Matrix3d brick_R_camera;  // rotates camera-frame vectors into the brick frame
    Eigen::Vector3d camera_t_brick;
    Eigen::Vector3d min_corner;
    Eigen::Vector3d max_corner;
  };

  PinholeCamera camera_;
  std::vector<Eigen::Isometry3d> camera_T_bricks_;
  std::vector<Box> boxes_;
  Eigen::Vector3d ground_normal_;  // camera frame, pointing up
  double ground_offset_ = 0.0;     // plane: normal . p + offset = 0
};
}  // namespace sim
}  // namespace brick_pose
