#pragma once
// Placing a box-like model on a scan once its orientation is chosen: the
// whole-view search compares the best pose with the model's other
// axis-aligned orientations (model_symmetry.h), and an orientation is only
// judged fairly at the position where the scan lies on it as the camera saw
// it. Turning the best pose about the model's centre leaves a box of other
// proportions off the scan (a brick's 0.2 m end face, matched as part of a
// 0.3 m side, is 5 cm off once the brick is turned end-on), by more than the
// local fit reaches.

#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/registration/model_symmetry.h"

namespace brick_pose
{
namespace registration
{
/// `pose` (model -> target) moved along each axis of the model's box
/// (symmetries.box_like) so that the scan's points (target frame) lie where a
/// camera at `viewpoint_m` would see the box's surface:
///  - along an axis on which the camera lies beyond the scan's extent, the
///    box's face on that side is turned to the camera, and the scan's
///    extreme there (that face, or the edges of its neighbours) meets it;
///  - along an axis on which the camera lies within the scan's extent, and
///    so between the box's two faces (neither is seen), both extremes are
///    silhouette edges: the scan is centred.
/// Extremes leave out `trim_points` points at each end (stray points). The
/// pose is returned unchanged for a model that is not box-like or fewer than
/// 2 * trim_points + 2 scan points.
Eigen::Isometry3d anchoredToScanExtent(const Eigen::Isometry3d& pose, const ModelSymmetries& symmetries,
                                       const std::vector<Eigen::Vector3d>& scan_points,
                                       const Eigen::Vector3d& viewpoint_m, int trim_points);
}  // namespace registration
}  // namespace brick_pose
