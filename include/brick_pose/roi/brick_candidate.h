#pragma once
// A segment that passed ROI filtration: everything the pose stage needs about
// one visible brick top face, in the camera optical frame.

#include <array>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "brick_pose/roi/edge_evidence.h"
#include "brick_pose/roi/least_area_quad.h"
#include "brick_pose/roi/oriented_bounding_box.h"
#include "brick_pose/geometry/plane_fit.h"

namespace brick_pose
{
struct BrickCandidate
{
  std::string type_name;
  /// The type came from the segment's plate colour (hsv). False for a
  /// colour-free face, typed by its size or by the tiling that cut it out.
  bool typed_by_colour = false;

  /// Segment points after cloud processing that lie on the fitted plane
  /// (camera frame, metres).
  pcl::PointCloud<pcl::PointXYZ>::Ptr points;
  /// MLS-smoothed points with normals; null when MLS is disabled.
  pcl::PointCloud<pcl::PointNormal>::Ptr smoothed_points;
  /// Image pixels of the segment that have depth (v * width + u).
  std::vector<int> pixel_indices;
  int area_px = 0;  ///< Mask pixels, with or without depth.
  /// The segment's pixel footprint (CV_8UC1, 255 inside) over `bounding_box_px`.
  cv::Mat mask;
  cv::Rect bounding_box_px;

  OrientedBoundingBox obb;  ///< PCA box of `points`.
  PlaneFit plane;           ///< Least-squares plane of `points`, normal toward the camera.

  /// Least-area quadrilateral, clockwise on screen, starting with a long
  /// edge: corners 0->1 and 2->3 are the long edges (measured in 3D); of the
  /// two possible starts the one higher in the image (smaller v) is taken.
  QuadCorners corners_px;
  /// The corners' rays intersected with `plane`.
  std::array<Eigen::Vector3d, 4> corners_m;

  /// Centre of the face: the mean of `corners_m` (on the plane), and its image.
  Eigen::Vector2d centroid_px = Eigen::Vector2d::Zero();
  Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();
  /// Points on the long axis at +/- length/4 from the centre (T1 toward the
  /// middle of edge 1->2, T2 toward the middle of edge 3->0).
  Eigen::Vector2d t1_px = Eigen::Vector2d::Zero();
  Eigen::Vector2d t2_px = Eigen::Vector2d::Zero();
  Eigen::Vector3d t1_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d t2_m = Eigen::Vector3d::Zero();

  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< Unit, toward the camera.
  double length_m = 0.0;  ///< Mean of the two long quad edges in 3D.
  /// Distance between the two long quad edges in 3D (the short edges'
  /// length for a whole face; still the width when the face is cut slantwise).
  /// Both stay as measured when a complete colour-free face's corners are
  /// then placed at its catalogue size (RoiFilterParams::place_on_catalogue_size).
  double width_m = 0.0;
  /// Area inside the segment's outline over the quad's area (1 for a whole,
  /// unoccluded face; lower for notched or irregular segments).
  double fill_ratio = 0.0;
  /// The same measured RoiFilterParams::ragged_outline_px inside the quad's
  /// sides (a ragged depth boundary left out); measured only where
  /// fill_ratio falls short by no more than such a rim holds, else NaN.
  double inset_fill_ratio = std::numeric_limits<double>::quiet_NaN();
  /// What lies beyond edge k (corner k to k+1): a real edge of the brick
  /// (step down, crease, seam) or not (occlusion boundary, image border, a
  /// plane that continues, no depth).
  EdgeKinds edge_kinds{{EdgeKind::kUnknown, EdgeKind::kUnknown, EdgeKind::kUnknown, EdgeKind::kUnknown}};
  /// Edge k ends the visible face without being the brick's edge because
  /// the image border or a closer surface (an occluder) lies right outside
  /// it (edge_kinds[k] is kImageBorder or kOcclusion).
  std::array<bool, 4> edge_truncated{{false, false, false, false}};
  /// Edge k is a step up to a wall as high as a catalogue item resting on
  /// the face could be (kept as kOcclusion): the wall's height above the
  /// face (m), else NaN. Only a wall clear of the edge's ends is recorded.
  std::array<double, 4> resting_wall_m{{std::numeric_limits<double>::quiet_NaN(),
                                        std::numeric_limits<double>::quiet_NaN(),
                                        std::numeric_limits<double>::quiet_NaN(),
                                        std::numeric_limits<double>::quiet_NaN()}};
  /// Angle between the face's normal and the frame's up direction (deg);
  /// NaN when up is unknown.
  double tilt_from_up_deg = 0.0;
  /// Why the type is a best guess, when it is: colour-free, several catalogue
  /// types have this top and the sides seen do not rule all but one out, or
  /// smaller catalogue tops touching make up the same face.
  /// Empty when the type is certain; a doubtful type is never complete.
  std::string type_doubt;
  /// The other catalogue types (or lying poses of one, named as in
  /// type_doubt) this face fits as well as type_name: of its size, standing
  /// as exactly at its height, and not ruled out by a side seen. A box_flat
  /// on a box_small and a box_small on a box_flat show the same top at the
  /// same height, and only their sides tell them apart. Empty when the
  /// evidence leaves type_name alone.
  std::vector<std::string> other_possible_types;
  /// True only when the face is seen whole as a brick's top: length and
  /// width match the catalogue type, it faces up, all four edges are real
  /// edges, and any side face seen to its foot has the catalogue height.
  bool complete = false;
  /// Why the face is not complete, for people ("edge 2 is an occlusion
  /// boundary", "cut by the image border", "no side face of the catalogue
  /// height seen: ..."); empty iff complete.
  std::string partial_reason;
};
}  // namespace brick_pose
