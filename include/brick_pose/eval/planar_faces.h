#pragma once
// Splits the 3D points of one labelled object into its planar faces:
// sequential RANSAC (samples drawn close together in the image, so that all
// three usually lie on one face), a least-squares refit of each plane, then
// every point goes to the nearest plane within the inlier distance and tiny
// image components are dropped. The ground-truth side of the evaluation, not
// a segmenter: it knows which pixels belong to the object.

#include <algorithm>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "brick_pose/geometry/plane_fit.h"

namespace brick_pose
{
namespace eval
{
struct PlanarFaceParams
{
  /// Inlier distance at 1 m; it grows with depth squared like the Kinect's
  /// disparity quantisation (about 3 mm per step at 1 m).
  double inlier_distance_at_1m_m = 0.008;
  int iterations = 300;
  int min_face_points = 60;
  /// The second and third RANSAC sample lie within this many pixels of the first.
  int sample_radius_px = 10;
  int max_faces = 6;
  /// Image components of a face smaller than this are left unassigned.
  int min_component_px = 20;
  std::uint64_t seed = 1;

  void validate() const;  ///< Throws ConfigError naming the field.
  double inlierDistance(double depth_m) const { return inlier_distance_at_1m_m * std::max(1.0, depth_m * depth_m); }
};

struct PlanarFace
{
  PlaneFit plane;             ///< Least-squares plane of the members, normal toward the camera.
  std::vector<int> members;   ///< Indices into the input points.
};

/// `points[i]` is the back-projection of image pixel `pixels[i]` (v * width + u).
/// Faces come largest first. Deterministic for a given seed.
std::vector<PlanarFace> extractPlanarFaces(const std::vector<Eigen::Vector3d>& points, const std::vector<int>& pixels,
                                           int image_width_px, int image_height_px, const PlanarFaceParams& params);
}  // namespace eval
}  // namespace brick_pose
