#pragma once
// Ground truth of one frame in the one form the matcher scores against, from
// the synthetic rig (exact) or from a real scene's labels (measured): every
// visible face of every object, what role it plays (top, side, ...), whether
// a top is whole in view, and a face index per pixel.

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace brick_pose
{
namespace eval
{
enum class FaceRole
{
  kTop,      ///< Faces up (along gravity's opposite): the face a picker grasps.
  kSide,     ///< Vertical face of a cuboid.
  kBottom,   ///< Faces down (seen only when a cuboid is tipped over).
  kOther,    ///< A face of an object that is neither (tilted cuboid, unclassified plane).
  kSupport,  ///< Table or ground: not an object at all.
};

const char* toString(FaceRole role);

/// Top-face geometry of a cuboid (camera frame, metres): what a correct
/// candidate measures.
struct TopFaceGeometry
{
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< Unit, toward the camera.
  Eigen::Vector3d long_axis = Eigen::Vector3d::UnitX();  ///< Unit, along the length.
  double length_m = 0.0;
  double width_m = 0.0;
  /// Corners on the face's plane, in order around it.
  std::array<Eigen::Vector3d, 4> corners_m;
};

struct FaceTruth
{
  int object_id = 0;  ///< 1-based object in this frame; 0 for the support.
  FaceRole role = FaceRole::kOther;
  /// Catalogue type of the object, empty when unknown (then the matcher does
  /// not check the candidate's type).
  std::string type;
  int visible_px = 0;  ///< Pixels of the face index image holding this face.

  // Tops only:
  /// Visible share of the whole face (0..1), occlusion and the image border
  /// counted.
  double visible_fraction = 0.0;
  /// The whole face is in view: inside the image, nothing in front of any
  /// part of it, nothing lying on it. Only such a face may be called complete.
  bool whole_in_view = false;
  /// Measured truth that cannot tell whether the top is whole (real scenes
  /// only): candidates on it are neither counted right nor false complete.
  bool whole_uncertain = false;
  std::string not_whole_reason;  ///< Why not (or why uncertain), when not whole.
  bool has_geometry = false;
  TopFaceGeometry geometry;
};

struct SceneTruth
{
  /// CV_32SC1: index into `faces` per pixel, -1 where there is no face
  /// (nothing, unlabelled or unassigned pixels).
  cv::Mat face_index;
  std::vector<FaceTruth> faces;

  int faceAt(int pixel) const { return face_index.ptr<int>(0)[pixel]; }
};
}  // namespace eval
}  // namespace brick_pose
