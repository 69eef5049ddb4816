#include "brick_pose/registration/visible_surface.h"

#include <cmath>

namespace brick_pose
{
namespace registration
{
namespace
{
/// The outward normal (model frame) of the box face that `point` (model
/// frame) lies on, within tolerance_m of its plane and of its rectangle, when
/// that face is turned towards the viewpoint at `pose` with at least min_cos;
/// zero when there is none.
Eigen::Vector3d facingBoxFaceNormal(const Eigen::Vector3d& point, const Eigen::Isometry3d& pose,
                                    const ModelSymmetries& box, const Eigen::Vector3d& viewpoint_m, double tolerance_m,
                                    double min_cos)
{
  const Eigen::Vector3d local = box.axes.transpose() * (point - box.centre_m);
  const Eigen::Vector3d to_viewpoint = (viewpoint_m - pose * point).normalized();
  for (int axis = 0; axis < 3; ++axis)
  {
    if (std::abs(std::abs(local(axis)) - box.half_extents_m(axis)) > tolerance_m)
      continue;
    bool inside = true;
    for (int other = 0; other < 3; ++other)
      inside = inside && (other == axis || std::abs(local(other)) <= box.half_extents_m(other) + tolerance_m);
    const Eigen::Vector3d normal = (local(axis) > 0.0 ? 1.0 : -1.0) * box.axes.col(axis);
    if (inside && (pose.linear() * normal).dot(to_viewpoint) >= min_cos)
      return normal;
  }
  return Eigen::Vector3d::Zero();
}
}  // namespace

PointSet visibleModelSurface(const PointSet& model, const Eigen::Isometry3d& pose, const ModelSymmetries& symmetries,
                             const Eigen::Vector3d& viewpoint_m, double on_face_tolerance_m, double min_cos)
{
  PointSet visible;
  for (std::size_t i = 0; i < model.size(); ++i)
  {
    const Eigen::Vector3d& point = model.points[i];
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    if (symmetries.box_like)
      normal = facingBoxFaceNormal(point, pose, symmetries, viewpoint_m, on_face_tolerance_m, min_cos);
    else if ((pose.linear() * model.normals[i]).dot((viewpoint_m - pose * point).normalized()) >= min_cos)
      normal = model.normals[i];
    if (normal.squaredNorm() == 0.0)
      continue;
    visible.points.push_back(point);
    visible.normals.push_back(normal);
  }
  return visible;
}
}  // namespace registration
}  // namespace brick_pose
