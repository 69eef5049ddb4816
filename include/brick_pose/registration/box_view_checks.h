#pragma once
// Checks of a whole-view pose of a box-like model that count no points but
// measure the box: how long the scan is along each edge of the faces the pose
// turns to the camera, and how each seen face of the scan is tilted against
// the pose's face.
//
// Coverage scores hardly see two wrong poses of a box seen on one face: a
// quarter turn that puts a 0.4 m face where the camera saw a 0.3 m one (the
// scan is all covered, 75 % of the model face seen, close to a good pose's
// figures), and a tilt of a long narrow face about its long axis (a few
// degrees move its 0.2 m sides by millimetres, within the depth noise). The
// scan's span along the face and the plane fitted to the face's points do.

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/registration/point_set.h"

namespace brick_pose
{
namespace registration
{
/// The box of the model: centre, axes (columns) and half extents, model frame.
struct ModelBox
{
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d half_extents_m = Eigen::Vector3d::Zero();
};

struct BoxViewCheckParams
{
  /// The scan's viewpoint in the target frame (the camera centre).
  Eigen::Vector3d viewpoint_m = Eigen::Vector3d::Zero();
  /// A face of the posed box is turned to the camera when the cosine between
  /// its normal and the direction to the viewpoint is at least this.
  double min_facing_cos = 0.3;
  /// Scan points on a face: normal within this of the face's, and within
  /// max_face_distance_m of its plane.
  double face_normal_deg = 20.0;
  double max_face_distance_m = 0.02;
  /// Fewest points for a face's plane to be fitted and judged.
  int min_face_points = 50;
  /// The scan's span along an edge of a facing face may fall short of the
  /// edge by the larger of these (edge erosion, holes at the border).
  double max_span_shortfall_m = 0.03;
  double max_span_shortfall_fraction = 0.1;
  /// Scan points left out at each end of a span (stray points).
  int span_trim_points = 3;
  /// Largest angle between a seen face's fitted plane and the pose's face.
  double max_face_tilt_deg = 3.0;
  /// Largest turn of a seen face within its plane against the pose's face
  /// (the least-area rectangle around its points, searched in steps of
  /// turn_step_deg up to turn_search_deg either way).
  double max_face_turn_deg = 5.5;
  /// Fewest points on a face for its turn to be judged: the least-area
  /// rectangle of a small face, its corners rounded off by the normals'
  /// radius, turns freely by several degrees.
  int min_turn_face_points = 300;
  double turn_step_deg = 0.5;
  double turn_search_deg = 15.0;

  /// Throws ConfigError naming the first unusable field.
  void validate() const;
};

struct BoxViewCheck
{
  /// Reasons the pose is not trusted; empty when it passes.
  std::vector<std::string> doubts;
  /// The largest tilt of a judged face (degrees), and the smallest ratio of
  /// the scan's span to an edge of a facing face.
  double max_face_tilt_deg = 0.0;
  double max_face_turn_deg = 0.0;
  double min_span_ratio = 1.0;
};

/// `pose` maps the model into the target (scan) frame; `trusted` indexes the
/// scan points (with unit normals) the checks use.
BoxViewCheck checkBoxView(const Eigen::Isometry3d& pose, const ModelBox& box, const PointSet& scan,
                          const std::vector<int>& trusted, const BoxViewCheckParams& params);
}  // namespace registration
}  // namespace brick_pose
