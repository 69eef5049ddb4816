#pragma once
// The part of a model that a viewpoint sees at a pose: the source of the
// whole-view polish (whole_view_registration.cpp), which registers what the
// camera can have seen, not the model's hidden back.

#include <Eigen/Geometry>

#include "brick_pose/registration/model_symmetry.h"
#include "brick_pose/registration/point_set.h"

namespace brick_pose
{
namespace registration
{
/// The model points (model frame; `model` with unit normals) on the surface
/// turned towards `viewpoint_m` (target frame) when the model is placed at
/// `pose` (model -> target), each with the normal of that surface.
///
/// On a box-like model (symmetries.box_like) that is every point within
/// `on_face_tolerance_m` of a face turned towards the viewpoint with a cosine
/// of at least `min_cos`, the face's edges included, and every such point
/// carries the face's normal. A sampled model keeps one normal per point, so
/// an edge point carries one of its two faces' normals; selected by its own
/// normal, a face whose neighbour is hidden would end a model spacing short
/// of its edge. The boundary stage of the polish, whose final pairing
/// radius is about that gap, would then pair the scan's edge with the model's
/// on one side of the face only and drag the face off centre (a lone end face
/// of a brick ended 9 mm off when started from the true pose).
///
/// Otherwise (not box-like) the points whose own normals are turned towards
/// the viewpoint with at least `min_cos`.
PointSet visibleModelSurface(const PointSet& model, const Eigen::Isometry3d& pose, const ModelSymmetries& symmetries,
                             const Eigen::Vector3d& viewpoint_m, double on_face_tolerance_m, double min_cos);
}  // namespace registration
}  // namespace brick_pose
