#include "brick_pose/sim/top_face_visibility.h"

#include <algorithm>
#include <cmath>

#include "brick_pose/catalogue/resting.h"
#include "brick_pose/common/angles.h"

namespace brick_pose
{
namespace sim
{
namespace
{
// Samples sit this far inside the face, so that a ray to a sample of a brick
// whose neighbour touches it (zero gap, coplanar tops) meets this brick's top
// and not the neighbour's edge.
constexpr double kInsetM = 0.0005;
// An edge on the image's outermost pixel cannot be told from the border.
constexpr double kBorderMarginPx = 1.0;

CuboidFace faceMostUp(const Eigen::Matrix3d& world_R_brick)
{
  const CuboidFace faces[6] = {CuboidFace::kPlusX, CuboidFace::kMinusX, CuboidFace::kPlusY,
                               CuboidFace::kMinusY, CuboidFace::kTop,   CuboidFace::kBottom};
  CuboidFace best = CuboidFace::kTop;
  double best_up = -2.0;
  for (int k = 0; k < 6; ++k)
  {
    const double up = (k % 2 == 0 ? 1.0 : -1.0) * world_R_brick(2, k / 2);
    if (up > best_up)
    {
      best_up = up;
      best = faces[k];
    }
  }
  return best;
}

bool insideImage(const PinholeCamera& camera, const Eigen::Vector2d& pixel)
{
  const double low = -0.5 + kBorderMarginPx;
  return pixel.x() >= low && pixel.y() >= low && pixel.x() <= camera.width_px - 0.5 - kBorderMarginPx &&
         pixel.y() <= camera.height_px - 0.5 - kBorderMarginPx;
}
}  // namespace

bool TopFaceVisibility::complete() const
{
  return facing_camera && tilt_deg <= kTopFaceMaxTiltDeg && !cut_by_border && !occluded;
}

TopFaceVisibility topFaceVisibility(const Scene& scene, const RayCaster& caster, const PinholeCamera& camera,
                                    int brick_index)
{
  return faceVisibility(scene, caster, camera, brick_index, CuboidFace::kTop);
}

TopFaceVisibility faceVisibility(const Scene& scene, const RayCaster& caster, const PinholeCamera& camera,
                                 int brick_index, CuboidFace face)
{
  TopFaceVisibility result;
  const PlacedBrick& brick = scene.bricks[brick_index];
  const Eigen::Matrix3d world_R_brick = brick.world_T_brick.linear();
  const Eigen::Isometry3d brick_T_face = brickTFace(brick.type, face);
  const Eigen::Vector3d world_normal = world_R_brick * brick_T_face.linear().col(2);
  result.tilt_deg = std::acos(std::clamp(world_normal.z(), -1.0, 1.0)) * kRadToDeg;
  result.up_face = faceMostUp(world_R_brick);

  const Eigen::Isometry3d camera_T_face = caster.cameraTBricks()[brick_index] * brick_T_face;
  result.facing_camera = camera_T_face.linear().col(2).dot(camera_T_face.translation()) < 0.0;
  if (!result.facing_camera) return result;

  // The face's corners in its own frame: the top of the type it is the top of.
  const BrickType as_top = restingAs(brick.type, restingWithFaceUp(face));
  const auto corners = topFaceCornersInBrick(as_top);
  for (int edge = 0; edge < 4; ++edge)
  {
    const Eigen::Vector3d& a = corners[edge];
    const Eigen::Vector3d& b = corners[(edge + 1) % 4];
    // The midpoint of a rectangle's edge, seen from its centre, is the
    // edge's outward normal.
    const Eigen::Vector3d inward = -(0.5 * (a + b)).normalized();
    int seen = 0;
    for (int s = 0; s < kTopEdgeSamples; ++s)
    {
      const double t = (s + 0.5) / kTopEdgeSamples;
      const Eigen::Vector3d point_camera = camera_T_face * (a + t * (b - a) + kInsetM * inward);
      if (point_camera.z() <= 1e-3 || !insideImage(camera, camera.project(point_camera)))
      {
        result.cut_by_border = true;
        continue;
      }
      // Ray parameter 1 is the sample itself: the nearest hit must be it.
      const RayHit hit = caster.cast(Eigen::Vector3d::Zero(), point_camera);
      if (hit.brick_index == brick_index && hit.face == face)
        ++seen;
      else
        result.occluded = true;
    }
    result.edge_visible_fraction[edge] = static_cast<double>(seen) / kTopEdgeSamples;
  }
  return result;
}
}  // namespace sim
}  // namespace brick_pose
