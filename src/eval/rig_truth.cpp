#include "brick_pose/eval/rig_truth.h"

#include <cmath>
#include <cstdio>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace eval
{
namespace
{
constexpr int kFacesPerBrick = 6;

/// Outward normal of a cuboid face in the brick frame.
Eigen::Vector3d faceNormalInBrick(sim::CuboidFace face)
{
  switch (face)
  {
    case sim::CuboidFace::kTop: return Eigen::Vector3d::UnitZ();
    case sim::CuboidFace::kBottom: return -Eigen::Vector3d::UnitZ();
    case sim::CuboidFace::kPlusX: return Eigen::Vector3d::UnitX();
    case sim::CuboidFace::kMinusX: return -Eigen::Vector3d::UnitX();
    case sim::CuboidFace::kPlusY: return Eigen::Vector3d::UnitY();
    case sim::CuboidFace::kMinusY: return -Eigen::Vector3d::UnitY();
    case sim::CuboidFace::kNone: break;
  }
  return Eigen::Vector3d::Zero();
}

FaceRole roleOf(sim::CuboidFace face, const Eigen::Vector3d& normal_in_camera, const Eigen::Vector3d& up,
                double max_tilt_deg)
{
  const double cos_up = normal_in_camera.dot(up);
  const double cos_tilt = std::cos(max_tilt_deg * kDegToRad);
  const double sin_tilt = std::sin(max_tilt_deg * kDegToRad);
  // Only the catalogue's top face is a top here: another face turned up is
  // not the face whose size the catalogue gives (a box resting on a side or
  // an end is the top of another type: setRestingTop).
  if (face == sim::CuboidFace::kTop) return cos_up >= cos_tilt ? FaceRole::kTop : FaceRole::kOther;
  if (std::abs(cos_up) <= sin_tilt) return FaceRole::kSide;
  if (face == sim::CuboidFace::kBottom && cos_up <= -cos_tilt) return FaceRole::kBottom;
  return FaceRole::kOther;
}

TopFaceGeometry topGeometry(const sim::BrickTruth& truth)
{
  TopFaceGeometry geometry;
  geometry.centre_m = truth.camera_T_brick.translation();
  geometry.normal = truth.camera_T_brick.linear().col(2);
  geometry.long_axis = truth.camera_T_brick.linear().col(0);
  geometry.length_m = truth.dimensions_m.x();
  geometry.width_m = truth.dimensions_m.y();
  geometry.corners_m = sim::topFaceCornersInCamera(truth);
  return geometry;
}

/// The rig's own verdict on a top's edges (every edge sample in the image
/// and unhidden), and the visible fraction for what lies inside the edges
/// (a smaller box standing on a larger one's top): why the top is not
/// whole, empty when it is.
std::string notWholeReason(const FaceTruth& face, const sim::TopFaceVisibility& view, bool edges_seen,
                           const RigTruthParams& params)
{
  char reason[96];
  if (face.role != FaceRole::kTop) return "the top face does not face up";
  if (view.cut_by_border) return "cut by the image border";
  if (view.occluded || !edges_seen)
  {
    std::snprintf(reason, sizeof(reason), "occluded (%.1f%% visible)", 100.0 * face.visible_fraction);
    return reason;
  }
  if (face.visible_fraction < params.min_visible_fraction)
  {
    std::snprintf(reason, sizeof(reason), "covered inside its edges (%.1f%% visible)", 100.0 * face.visible_fraction);
    return reason;
  }
  return {};
}

/// The face up of a box on a side or an end, as the top of the type it is
/// resting so (a plain box's face a picker grasps).
void setRestingTop(const sim::RestingFaceTruth& resting, const RigTruthParams& params, FaceTruth& face)
{
  face.role = FaceRole::kTop;
  face.type = resting.type;
  face.visible_fraction = resting.visible_fraction;
  face.has_geometry = true;
  sim::BrickTruth as_top;
  as_top.dimensions_m = resting.dimensions_m;
  as_top.camera_T_brick = resting.camera_T_face;
  face.geometry = topGeometry(as_top);
  face.not_whole_reason = notWholeReason(face, resting.view, resting.view.complete(), params);
  face.whole_in_view = face.not_whole_reason.empty();
}
}  // namespace

void RigTruthParams::validate() const
{
  if (!(min_visible_fraction > 0.0 && min_visible_fraction <= 1.0))
    throw ConfigError("min_visible_fraction must be in (0, 1]");
  if (!(max_up_tilt_deg > 0.0 && max_up_tilt_deg < 45.0)) throw ConfigError("max_up_tilt_deg must be in (0, 45)");
}

SceneTruth rigSceneTruth(const sim::SyntheticFrame& frame, const Eigen::Vector3d& up_in_camera,
                         const RigTruthParams& params)
{
  params.validate();
  if (!(std::abs(up_in_camera.norm() - 1.0) < 1e-6)) throw InputError("rigSceneTruth: up_in_camera must be a unit vector");
  SceneTruth truth;
  const int brick_count = static_cast<int>(frame.truth.size());
  const int support_index = brick_count * kFacesPerBrick;
  truth.faces.resize(static_cast<std::size_t>(support_index + 1));
  for (int b = 0; b < brick_count; ++b)
  {
    const sim::BrickTruth& brick = frame.truth[static_cast<std::size_t>(b)];
    for (int f = 0; f < kFacesPerBrick; ++f)
    {
      const auto face = static_cast<sim::CuboidFace>(f + 1);
      FaceTruth& face_truth = truth.faces[static_cast<std::size_t>(b * kFacesPerBrick + f)];
      face_truth.object_id = brick.instance_id;
      face_truth.type = brick.type;
      const Eigen::Vector3d normal = brick.camera_T_brick.linear() * faceNormalInBrick(face);
      face_truth.role = roleOf(face, normal, up_in_camera, params.max_up_tilt_deg);
      if (brick.resting_face && brick.resting_face->face == face)
      {
        if (normal.dot(up_in_camera) >= std::cos(params.max_up_tilt_deg * kDegToRad))
          setRestingTop(*brick.resting_face, params, face_truth);
        continue;
      }
      if (face != sim::CuboidFace::kTop) continue;
      face_truth.visible_fraction = brick.visible_fraction;
      face_truth.has_geometry = true;
      face_truth.geometry = topGeometry(brick);
      face_truth.not_whole_reason = notWholeReason(face_truth, brick.top_face, brick.top_face_complete, params);
      face_truth.whole_in_view = face_truth.not_whole_reason.empty();
    }
  }
  truth.faces[static_cast<std::size_t>(support_index)].role = FaceRole::kSupport;

  truth.face_index = cv::Mat(frame.instance_labels.size(), CV_32SC1, cv::Scalar(-1));
  for (int v = 0; v < frame.instance_labels.rows; ++v)
  {
    const auto* instances = frame.instance_labels.ptr<std::uint16_t>(v);
    const auto* faces = frame.face_labels.ptr<std::uint8_t>(v);
    const auto* depth = frame.depth_clean_m.ptr<float>(v);
    int* index = truth.face_index.ptr<int>(v);
    for (int u = 0; u < frame.instance_labels.cols; ++u)
    {
      if (instances[u] > 0 && instances[u] <= brick_count && faces[u] > 0)
        index[u] = (instances[u] - 1) * kFacesPerBrick + faces[u] - 1;
      else if (std::isfinite(depth[u]))
        index[u] = support_index;
    }
  }
  for (int pixel = 0; pixel < static_cast<int>(truth.face_index.total()); ++pixel)
    if (truth.faceAt(pixel) >= 0) ++truth.faces[static_cast<std::size_t>(truth.faceAt(pixel))].visible_px;
  return truth;
}
}  // namespace eval
}  // namespace brick_pose
