#pragma once
// The symmetries of a model found from the model itself, for the whole-view
// acceptance of Super4PCS: which of the 24 axis-aligned rotations of a
// cuboid-like model (about its centre) map it onto itself (true symmetries:
// no scan can tell those poses apart, so they are not wrong answers), and
// which do not (near-symmetries: a wrong pose is most likely one of these
// away from the right one, so the best pose is compared with them).
//
// Found numerically rather than from dimensions so that a partial model (the
// top and two sides of a brick) or a model read from a file is handled alike.

#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/registration/point_grid.h"
#include "brick_pose/registration/point_set.h"

namespace brick_pose
{
namespace registration
{
struct ModelSymmetries
{
  /// False when the model's normals do not cluster along three orthogonal
  /// axes (not a cuboid-like model): then only the identity is listed.
  bool box_like = false;
  /// Centre of the model's bounding box in the axes of its faces (model frame).
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();
  /// Those axes (columns, model frame) and the box's half extents along them.
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d half_extents_m = Eigen::Vector3d::Zero();

  /// Motions of the model frame mapping the model onto itself; identity first.
  std::vector<Eigen::Isometry3d> symmetries{Eigen::Isometry3d::Identity()};
  /// One motion per class of the remaining axis-aligned rotations about the
  /// centre (two that differ by a symmetry are one class).
  std::vector<Eigen::Isometry3d> alternatives;
};

/// `model` with unit normals; `model_grid` indexes model.points (max radius
/// >= match_radius_m); `probe` is a sparse subset of the model to test with.
/// A rotation is a symmetry when at least min_self_overlap of the probe
/// points land within match_radius_m of a model point with a normal within
/// max_normal_difference_deg. The default 0.85 sits between what a true
/// symmetry scores when the model's point lattice does not map onto itself
/// (0.95-0.97 at a match radius of one model spacing: edge points land a
/// spacing off) and what a near-miss scores (at most 0.73, a 0.2 x 0.2 x 0.3
/// box's quarter turn about a short axis); 0.95 flipped with the compiler.
ModelSymmetries findModelSymmetries(const PointSet& model, const PointGrid& model_grid, const PointSet& probe,
                                    double match_radius_m, double max_normal_difference_deg = 20.0,
                                    double min_self_overlap = 0.85);

/// Whether two model -> target poses put the model in the same place up to
/// one of the symmetries: rotations within max_angle_deg and the model's
/// centre within max_offset_m of each other.
bool samePoseModuloSymmetry(const Eigen::Isometry3d& first, const Eigen::Isometry3d& second,
                            const ModelSymmetries& symmetries, double max_angle_deg, double max_offset_m);
}  // namespace registration
}  // namespace brick_pose
