#include "bench_registration/view_cases.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/registration/uniform_sampling.h"
#include "brick_pose/sim/scene_generator.h"

namespace bench_registration
{
using namespace brick_pose;

namespace
{
constexpr int kMaxScanPoints = 3000;
constexpr int kMinScanPoints = 300;
constexpr int kMaxRedraws = 50;
constexpr double kMinDistanceM = 0.6;
constexpr double kMaxDistanceM = 2.0;
constexpr int kImageMarginPx = 10;
// A face counts as seen when it holds this fraction of the brick's pixels.
constexpr double kSeenFaceFraction = 0.03;

/// The camera placement of one case, angles relative to the brick's axes.
struct Placement
{
  std::string layout;
  double elevation_deg = 0.0;
  double azimuth_from_x_deg = 0.0;  ///< azimuth relative to the brick's +x axis
};

/// Angles that show the wanted number of faces. Faces the camera sees at a
/// cosine below about 0.1 return almost no depth on a D415 (grazing).
Placement drawPlacement(int faces, std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto between = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  const double axis = 90.0 * std::floor(between(0.0, 4.0));  // which side of the brick
  const double sign = unit(rng) < 0.5 ? -1.0 : 1.0;
  Placement placement;
  if (faces == 1)
  {
    if (unit(rng) < 0.5)
      placement = {"top", between(84.5, 89.5), between(0.0, 360.0)};
    else
      placement = {"side", between(0.5, 4.0), axis + sign * between(0.0, 4.0)};
  }
  else if (faces == 2)
  {
    if (unit(rng) < 0.75)
      placement = {"top+side", between(25.0, 65.0), axis + sign * between(0.0, 4.0)};
    else
      placement = {"side+end", between(0.5, 4.0), axis + sign * between(25.0, 65.0)};
  }
  else
    placement = {"corner", between(20.0, 65.0), axis + sign * between(20.0, 70.0)};
  return placement;
}

bool wholeBrickInImage(const sim::Scene& scene, const PinholeCamera& camera)
{
  const Eigen::Isometry3d camera_T_brick = scene.world_T_camera.inverse() * scene.bricks[0].world_T_brick;
  for (const Eigen::Vector3d& corner : sim::cuboidCornersInBrick(scene.bricks[0].type))
  {
    const Eigen::Vector3d in_camera = camera_T_brick * corner;
    if (!(in_camera.z() > 0.1))
      return false;
    const Eigen::Vector2d pixel = camera.project(in_camera);
    if (pixel.x() < kImageMarginPx || pixel.y() < kImageMarginPx || pixel.x() > camera.width_px - kImageMarginPx ||
        pixel.y() > camera.height_px - kImageMarginPx)
      return false;
  }
  return true;
}
}  // namespace

std::vector<BrickType> viewCaseTypes(const BrickCatalogue& catalogue)
{
  std::vector<BrickType> types = catalogue.types();
  BrickType box;
  box.name = "cardboard";
  box.length_m = 0.40;
  box.width_m = 0.30;
  box.height_m = 0.20;
  box.plate_rgb = {{190, 150, 100}};
  box.body_rgb = {{180, 140, 95}};
  box.validate();
  types.push_back(box);
  return types;
}

RigViewSource::RigViewSource(std::uint64_t seed, std::vector<BrickType> types)
  : seed_(seed),
    types_(std::move(types)),
    camera_(PinholeCamera::d415Color1280x720()),
    rig_(camera_, sim::SensorModel())
{
  if (types_.empty())
    throw ConfigError("RigViewSource: no brick types");
}

ViewCase RigViewSource::make(int index, int& redraws) const
{
  ViewCase view;
  view.type = types_[index % types_.size()];
  view.faces_wanted = 1 + (index / static_cast<int>(types_.size())) % 3;
  for (int attempt = 0; attempt < kMaxRedraws; ++attempt)
  {
    const std::uint64_t case_seed = seed_ * 1000003ull + static_cast<std::uint64_t>(index) * 101ull + attempt;
    std::mt19937_64 rng(case_seed);
    const Placement placement = drawPlacement(view.faces_wanted, rng);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double yaw_deg = 360.0 * unit(rng);
    const double distance_m = kMinDistanceM + (kMaxDistanceM - kMinDistanceM) * unit(rng);

    sim::Scene scene;
    sim::PlacedBrick brick;
    brick.type = view.type;
    brick.world_T_brick = Eigen::Isometry3d::Identity();
    brick.world_T_brick.linear() = Eigen::AngleAxisd(yaw_deg * kDegToRad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    brick.world_T_brick.translation() = Eigen::Vector3d(0.0, 0.0, view.type.height_m);
    scene.bricks.push_back(brick);
    scene.world_T_camera = sim::lookAt(Eigen::Vector3d(0.0, 0.0, 0.5 * view.type.height_m), distance_m,
                                       placement.elevation_deg, yaw_deg + placement.azimuth_from_x_deg);
    if (!wholeBrickInImage(scene, camera_))
    {
      ++redraws;
      continue;
    }
    const sim::SyntheticFrame frame = rig_.render(scene, case_seed);
    registration::PointSet all;
    int face_pixels[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    int brick_pixels = 0;
    for (int v = 0; v < frame.instance_labels.rows; ++v)
      for (int u = 0; u < frame.instance_labels.cols; ++u)
      {
        if (frame.instance_labels.at<std::uint16_t>(v, u) != 1)
          continue;
        ++brick_pixels;
        ++face_pixels[std::min<int>(7, frame.face_labels.at<std::uint8_t>(v, u))];
        const std::uint16_t depth_mm = frame.depth_mm.at<std::uint16_t>(v, u);
        if (depth_mm != 0)
          all.points.push_back(frame.camera.backProject(u, v, 1e-3 * depth_mm));
      }
    if (static_cast<int>(all.size()) < kMinScanPoints || frame.truth.empty())
    {
      ++redraws;
      continue;
    }
    view.faces_seen = 0;
    for (int face = 1; face < 8; ++face)
      view.faces_seen += face_pixels[face] >= kSeenFaceFraction * brick_pixels ? 1 : 0;
    view.layout = placement.layout;
    view.camera_T_brick = frame.truth[0].camera_T_brick;
    view.distance_m = view.camera_T_brick.translation().norm();
    view.scan = all.subset(registration::uniformSubsample(all.points, kMaxScanPoints, rng));
    return view;
  }
  throw InputError("view case " + std::to_string(index) + ": no camera pose shows the whole " + view.type.name +
                   " brick");
}
}  // namespace bench_registration
