#include "brick_pose/sim/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brick_pose
{
namespace sim
{
namespace
{
constexpr double kInfinity = std::numeric_limits<double>::infinity();

CuboidFace faceOf(int axis, bool positive_side)
{
  static const CuboidFace kFaces[3][2] = {{CuboidFace::kMinusX, CuboidFace::kPlusX},
                                          {CuboidFace::kMinusY, CuboidFace::kPlusY},
                                          {CuboidFace::kBottom, CuboidFace::kTop}};
  return kFaces[axis][positive_side ? 1 : 0];
}
}  // namespace

RayCaster::RayCaster(const Scene& scene, const PinholeCamera& camera) : camera_(camera)
{
  const Eigen::Isometry3d camera_T_world = scene.world_T_camera.inverse();
  for (const PlacedBrick& brick : scene.bricks)
  {
    const Eigen::Isometry3d camera_T_brick = camera_T_world * brick.world_T_brick;
    camera_T_bricks_.push_back(camera_T_brick);
    Box box;
    box.brick_R_camera = camera_T_brick.linear().transpose();
    box.camera_t_brick = camera_T_brick.translation();
    const BrickType& type = brick.type;
    box.min_corner = Eigen::Vector3d(-0.5 * type.length_m, -0.5 * type.width_m, -type.height_m);
    box.max_corner = Eigen::Vector3d(0.5 * type.length_m, 0.5 * type.width_m, 0.0);
    boxes_.push_back(box);
  }
  ground_normal_ = camera_T_world.linear() * Eigen::Vector3d::UnitZ();
  ground_offset_ = -ground_normal_.dot(camera_T_world.translation());
}

RayHit RayCaster::castBrick(int brick_index, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                            double min_t) const
{
  // Slab test in the brick frame.
  const Box& box = boxes_[brick_index];
  const Eigen::Vector3d o = box.brick_R_camera * (origin - box.camera_t_brick);
  const Eigen::Vector3d d = box.brick_R_camera * direction;
  double t_near = -kInfinity, t_far = kInfinity;
  int near_axis = -1;
  bool near_positive = false;
  for (int axis = 0; axis < 3; ++axis)
  {
    if (std::abs(d[axis]) < 1e-15)
    {
      if (o[axis] < box.min_corner[axis] || o[axis] > box.max_corner[axis]) return {};
      continue;
    }
    const double inverse = 1.0 / d[axis];
    double t0 = (box.min_corner[axis] - o[axis]) * inverse;
    double t1 = (box.max_corner[axis] - o[axis]) * inverse;
    // A ray travelling in -axis enters through the + face.
    const bool enters_positive = d[axis] < 0.0;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > t_near)
    {
      t_near = t0;
      near_axis = axis;
      near_positive = enters_positive;
    }
    t_far = std::min(t_far, t1);
  }
  if (near_axis < 0 || t_near > t_far || t_near <= min_t) return {};
  RayHit hit;
  hit.brick_index = brick_index;
  hit.ray_t = t_near;
  hit.face = faceOf(near_axis, near_positive);
  Eigen::Vector3d normal_brick = Eigen::Vector3d::Zero();
  normal_brick[near_axis] = near_positive ? 1.0 : -1.0;
  hit.normal = box.brick_R_camera.transpose() * normal_brick;
  hit.point_brick = o + t_near * d;
  return hit;
}

RayHit RayCaster::castGround(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double min_t) const
{
  const double denominator = ground_normal_.dot(direction);
  if (std::abs(denominator) < 1e-12) return {};
  const double t = -(ground_normal_.dot(origin) + ground_offset_) / denominator;
  if (t <= min_t) return {};
  RayHit hit;
  hit.brick_index = RayHit::kGround;
  hit.ray_t = t;
  hit.normal = ground_normal_;
  return hit;
}

RayHit RayCaster::cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double min_t) const
{
  RayHit best = castGround(origin, direction, min_t);
  for (int i = 0; i < static_cast<int>(boxes_.size()); ++i)
  {
    const RayHit hit = castBrick(i, origin, direction, min_t);
    if (hit.hitSomething() && (!best.hitSomething() || hit.ray_t < best.ray_t)) best = hit;
  }
  return best;
}

RayHit RayCaster::castPixel(double u_px, double v_px) const
{
  return cast(Eigen::Vector3d::Zero(), camera_.ray(u_px, v_px));
}

bool RayCaster::blocked(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const
{
  const Eigen::Vector3d direction = to - from;
  for (int i = 0; i < static_cast<int>(boxes_.size()); ++i)
  {
    const RayHit hit = castBrick(i, from, direction, 1e-6);
    if (hit.hitSomething() && hit.ray_t < 1.0) return true;
  }
  return false;
}

Eigen::Vector4i RayCaster::pixelBounds(int brick_index) const
{
  const Box& box = boxes_[brick_index];
  const Eigen::Matrix3d camera_R_brick = box.brick_R_camera.transpose();
  double u_min = kInfinity, u_max = -kInfinity, v_min = kInfinity, v_max = -kInfinity;
  bool behind = false;
  for (int corner = 0; corner < 8; ++corner)
  {
    const Eigen::Vector3d in_brick((corner & 1) ? box.max_corner.x() : box.min_corner.x(),
                                   (corner & 2) ? box.max_corner.y() : box.min_corner.y(),
                                   (corner & 4) ? box.max_corner.z() : box.min_corner.z());
    const Eigen::Vector3d in_camera = camera_R_brick * in_brick + box.camera_t_brick;
    if (in_camera.z() < 1e-3)
    {
      behind = true;
      break;
    }
    const Eigen::Vector2d pixel = camera_.project(in_camera);
    u_min = std::min(u_min, pixel.x());
    u_max = std::max(u_max, pixel.x());
    v_min = std::min(v_min, pixel.y());
    v_max = std::max(v_max, pixel.y());
  }
  // A box straddling the camera plane can cover any pixel: test them all.
  if (behind) return Eigen::Vector4i(0, 0, camera_.width_px - 1, camera_.height_px - 1);
  const auto clamp_u = [this](double u) { return static_cast<int>(std::clamp(u, -1.0, double(camera_.width_px))); };
  const auto clamp_v = [this](double v) { return static_cast<int>(std::clamp(v, -1.0, double(camera_.height_px))); };
  Eigen::Vector4i bounds(clamp_u(std::floor(u_min)), clamp_v(std::floor(v_min)), clamp_u(std::ceil(u_max)),
                         clamp_v(std::ceil(v_max)));
  bounds[0] = std::max(bounds[0], 0);
  bounds[1] = std::max(bounds[1], 0);
  bounds[2] = std::min(bounds[2], camera_.width_px - 1);
  bounds[3] = std::min(bounds[3], camera_.height_px - 1);
  return bounds;
}
}  // namespace sim
}  // namespace brick_pose
