#include "brick_pose/sim/scene_generator.h"

#include <algorithm>
#include <cmath>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/sim/box_layouts.h"
#include "brick_pose/sim/cuboid_overlap.h"
#include "brick_pose/sim/fast_random.h"

namespace brick_pose
{
namespace sim
{
namespace
{

Eigen::Isometry3d brickPose(const Eigen::Vector3d& top_centre_world, double yaw_rad,
                            const Eigen::Vector3d& tilt_axis = Eigen::Vector3d::UnitX(), double tilt_rad = 0.0)
{
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = (Eigen::AngleAxisd(tilt_rad, tilt_axis.normalized()) * Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()))
                      .toRotationMatrix();
  pose.translation() = top_centre_world;
  return pose;
}

/// Highest top surface among `placed` under the footprint of `brick`, sampled
/// on a grid over its footprint (0 = the ground).
double supportHeight(const PlacedBrick& brick, const std::vector<PlacedBrick>& placed)
{
  double height = 0.0;
  const double half_l = 0.5 * brick.type.length_m, half_w = 0.5 * brick.type.width_m;
  for (int i = 0; i <= 6; ++i)
    for (int j = 0; j <= 3; ++j)
    {
      const Eigen::Vector3d sample_brick(-half_l + 2.0 * half_l * i / 6.0, -half_w + 2.0 * half_w * j / 3.0, 0.0);
      const Eigen::Vector3d sample_world = brick.world_T_brick * sample_brick;
      for (const PlacedBrick& other : placed)
      {
        const Eigen::Vector3d local = other.world_T_brick.inverse() * sample_world;
        if (std::abs(local.x()) <= 0.5 * other.type.length_m && std::abs(local.y()) <= 0.5 * other.type.width_m)
          height = std::max(height, other.world_T_brick.translation().z());
      }
    }
  return height;
}

class Builder
{
public:
  Builder(const BrickCatalogue& catalogue, const SceneParams& params, std::uint64_t seed)
    : catalogue_(catalogue), params_(params), random_(seed)
  {
  }

  Scene build()
  {
    Scene scene;
    switch (params_.kind)
    {
      case SceneKind::kOrganisedPile:
        scene.bricks = organisedPile();
        break;
      case SceneKind::kUnorganisedPile:
        scene.bricks = unorganisedPile();
        break;
      case SceneKind::kTouchingRows:
      case SceneKind::kPalletLayer:
      case SceneKind::kPalletStack:
      case SceneKind::kTableBoxes:
        return buildBoxLayout();
      case SceneKind::kSingle:
      default:
        scene.bricks = {singleBrick()};
        break;
    }
    scene.world_T_camera = cameraLookingAt(scene.bricks);
    scene.edge_radius_m = params_.edge_radius_m;
    return scene;
  }

private:
  Scene buildBoxLayout()
  {
    LayoutContext context{typesToDraw(), params_, random_};
    Scene scene;
    switch (params_.kind)
    {
      case SceneKind::kTouchingRows:
        scene.bricks = touchingRows(context);
        break;
      case SceneKind::kPalletLayer:
        scene.bricks = palletLayer(context);
        break;
      case SceneKind::kPalletStack:
        scene.bricks = palletStack(context);
        break;
      case SceneKind::kTableBoxes:
      default:
        scene.bricks = tableBoxes(context);
        scene.ground_rgb = {{196, 170, 134}};  // a light wooden table top
        break;
    }
    // A pallet whose every box went missing still shows one box.
    if (scene.bricks.empty()) scene.bricks = {singleBrick()};
    scene.world_T_camera = cameraLookingAtBodies(scene.bricks);
    scene.edge_radius_m = params_.edge_radius_m;
    return scene;
  }

  std::vector<const BrickType*> typesToDraw() const
  {
    std::vector<const BrickType*> types;
    if (params_.types.empty())
      for (const BrickType& type : catalogue_.types())
        types.push_back(&type);
    else
      for (const std::string& name : params_.types)
        types.push_back(&catalogue_.at(name));
    return types;
  }

  /// Looks at the middle of the bodies' footprint, at the height of the
  /// highest corner: upright boxes' frames sit on their sides, so the brick
  /// origins would pull the view off centre.
  Eigen::Isometry3d cameraLookingAtBodies(const std::vector<PlacedBrick>& bricks)
  {
    Eigen::Vector3d target = Eigen::Vector3d::Zero();
    double top_z = 0.0;
    for (const PlacedBrick& brick : bricks)
    {
      target += brick.world_T_brick * Eigen::Vector3d(0.0, 0.0, -0.5 * brick.type.height_m);
      for (const Eigen::Vector3d& corner : cuboidCornersInBrick(brick.type))
        top_z = std::max(top_z, (brick.world_T_brick * corner).z());
    }
    target /= static_cast<double>(bricks.size());
    target.z() = top_z;
    return lookAt(target, random_.uniform(params_.min_distance_m, params_.max_distance_m),
                  random_.uniform(params_.min_elevation_deg, params_.max_elevation_deg), random_.uniform(-180.0, 180.0));
  }

  const BrickType& randomType()
  {
    if (params_.types.empty())
      return catalogue_.types()[random_.next() % catalogue_.types().size()];
    return catalogue_.at(params_.types[random_.next() % params_.types.size()]);
  }

  Eigen::Vector3d randomHorizontalAxis()
  {
    const double angle = random_.uniform(0.0, 2.0 * M_PI);
    return {std::cos(angle), std::sin(angle), 0.0};
  }

  PlacedBrick singleBrick()
  {
    PlacedBrick brick{randomType(), {}};
    const double tilt_rad = random_.uniform(0.0, params_.max_tilt_deg) * kDegToRad;
    brick.world_T_brick =
        brickPose(Eigen::Vector3d::Zero(), random_.uniform(-M_PI, M_PI), randomHorizontalAxis(), tilt_rad);
    restBrickOn(brick, 0.0);
    return brick;
  }

  std::vector<PlacedBrick> organisedPile()
  {
    // Rows of identical bricks side by side along y, layers stacked on top.
    const BrickType& type = randomType();
    const int rows = 1 + static_cast<int>(random_.next() % params_.max_rows);
    const int layers = 1 + static_cast<int>(random_.next() % params_.max_layers);
    const double pile_yaw = random_.uniform(-M_PI, M_PI);
    const double gap_m = random_.uniform(0.01, 0.03);
    std::vector<PlacedBrick> bricks;
    for (int layer = 0; layer < layers; ++layer)
      for (int row = 0; row < rows; ++row)
      {
        const double y = (row - 0.5 * (rows - 1)) * (type.width_m + gap_m) + random_.uniform(-0.005, 0.005);
        const double x = random_.uniform(-0.01, 0.01);
        const Eigen::Vector3d local(x, y, (layer + 1) * type.height_m);
        const Eigen::Vector3d world = Eigen::AngleAxisd(pile_yaw, Eigen::Vector3d::UnitZ()) * local;
        const double yaw = pile_yaw + random_.uniform(-2.0, 2.0) * kDegToRad;
        PlacedBrick brick{type, brickPose(world, yaw)};
        // Rows go up along the pile's y: a row that reached into the one
        // before (a long brick's yaw jitter) is moved on until the pile's
        // gap lies between them again.
        if (row > 0 && interpenetrationM(brick, bricks.back()) > 0.0)
          moveClearOf(brick, {bricks.back()}, Eigen::AngleAxisd(pile_yaw, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d::UnitY(),
                      -gap_m);
        bricks.push_back(brick);
      }
    return bricks;
  }

  std::vector<PlacedBrick> unorganisedPile()
  {
    const int count = 2 + static_cast<int>(random_.next() % std::max(1, params_.max_pile_bricks - 1));
    std::vector<PlacedBrick> bricks;
    for (int i = 0; i < count; ++i)
    {
      PlacedBrick brick{randomType(), {}};
      const double radius_m = 0.25 + 0.15 * count;
      const Eigen::Vector3d drop(random_.uniform(-radius_m, radius_m) * 0.5, random_.uniform(-radius_m, radius_m) * 0.5, 0.0);
      const double yaw_rad = random_.uniform(-M_PI, M_PI);
      brick.world_T_brick = brickPose(drop, yaw_rad);
      const double support = supportHeight(brick, bricks);
      // A brick resting on others lies a little tilted; one on the ground lies flat.
      const double tilt_rad = support > 0.0 ? random_.uniform(0.0, params_.max_tilt_deg) * kDegToRad : 0.0;
      brick.world_T_brick = brickPose(drop, yaw_rad, randomHorizontalAxis(), tilt_rad);
      restBrickOn(brick, supportHeight(brick, bricks));
      // The support samples can miss a neighbour's corner: never inside it.
      liftClearOf(brick, bricks);
      bricks.push_back(brick);
    }
    return bricks;
  }

  Eigen::Isometry3d cameraLookingAt(const std::vector<PlacedBrick>& bricks)
  {
    Eigen::Vector3d target = Eigen::Vector3d::Zero();
    double top_z = 0.0;
    for (const PlacedBrick& brick : bricks)
    {
      target += brick.world_T_brick.translation();
      top_z = std::max(top_z, brick.world_T_brick.translation().z());
    }
    target /= static_cast<double>(bricks.size());
    target.z() = top_z;
    return lookAt(target, random_.uniform(params_.min_distance_m, params_.max_distance_m),
                  random_.uniform(params_.min_elevation_deg, params_.max_elevation_deg), random_.uniform(-180.0, 180.0));
  }

  const BrickCatalogue& catalogue_;
  const SceneParams& params_;
  FastRandom random_;
};
}  // namespace

namespace
{
const std::vector<std::pair<SceneKind, std::string>>& kindNames()
{
  static const std::vector<std::pair<SceneKind, std::string>> names = {
      {SceneKind::kSingle, "single"},
      {SceneKind::kOrganisedPile, "organised_pile"},
      {SceneKind::kUnorganisedPile, "unorganised_pile"},
      {SceneKind::kTouchingRows, "touching_rows"},
      {SceneKind::kPalletLayer, "pallet_layer"},
      {SceneKind::kPalletStack, "pallet_stack"},
      {SceneKind::kTableBoxes, "table_boxes"},
  };
  return names;
}
/// Cardboard, tape and labels for every brick whose type has no plate
/// colour. From a random source of their own, so that the layouts (and the
/// scenes of earlier versions) do not change with them.
void addMarkings(Scene& scene, std::uint64_t seed, SceneKind kind)
{
  FastRandom random(seed ^ 0x6D61726B696E6773ULL);
  for (PlacedBrick& brick : scene.bricks)
  {
    if (brick.type.hasPlateColour()) continue;
    SurfaceMarkings& markings = brick.markings;
    markings.cardboard = true;
    // Boxes on a table are mostly printed packaging, as in the mOSD scenes.
    if (kind == SceneKind::kTableBoxes) markings.printed = random.bernoulli(0.7);
    const double tape = random.uniform();
    markings.tape = tape < 0.55 ? SurfaceMarkings::Tape::kBrown
                                : tape < 0.8 ? SurfaceMarkings::Tape::kClear : SurfaceMarkings::Tape::kNone;
    markings.labels = static_cast<int>(random.next() % 3);
    markings.seed = random.next();
  }
}
}  // namespace

SceneKind sceneKindFromString(const std::string& name)
{
  std::string known;
  for (const auto& [kind, kind_name] : kindNames())
  {
    if (kind_name == name) return kind;
    known += (known.empty() ? "" : ", ") + kind_name;
  }
  throw ConfigError("parameter 'scene': unknown scene kind '" + name + "' (expected " + known + ")");
}

std::string toString(SceneKind kind)
{
  for (const auto& [known_kind, name] : kindNames())
    if (known_kind == kind) return name;
  return "single";
}

void SceneParams::applyView(const std::string& view)
{
  if (view == "top")
  {
    min_elevation_deg = 65.0;
    max_elevation_deg = 89.0;
  }
  else if (view == "oblique")
  {
    // 30-70 degrees from the vertical: side faces are large.
    min_elevation_deg = 20.0;
    max_elevation_deg = 60.0;
  }
  else
    throw ConfigError("parameter 'view': unknown view '" + view + "' (expected top or oblique)");
}

SceneParams SceneParams::defaultsFor(SceneKind kind)
{
  SceneParams params;
  params.kind = kind;
  const bool box_kind = kind == SceneKind::kTouchingRows || kind == SceneKind::kPalletLayer ||
                        kind == SceneKind::kPalletStack || kind == SceneKind::kTableBoxes;
  // Cardboard boxes have edges rounded over a few millimetres.
  if (box_kind) params.edge_radius_m = 0.004;
  switch (kind)
  {
    case SceneKind::kTouchingRows:
      params.min_distance_m = 1.0;
      params.max_distance_m = 2.0;
      params.max_rows = 4;
      params.max_layers = 1;
      break;
    case SceneKind::kPalletLayer:
    case SceneKind::kPalletStack:
      // A camera above a pallet, as in the pallet recordings (~1.2-2 m).
      params.min_distance_m = 1.2;
      params.max_distance_m = 2.0;
      params.applyView("top");
      params.max_layers = 3;
      break;
    case SceneKind::kTableBoxes:
      // Seen obliquely, so that the boxes' side faces are large.
      params.min_distance_m = 0.6;
      params.max_distance_m = 1.5;
      params.applyView("oblique");
      break;
    default:
      break;
  }
  return params;
}

void SceneParams::validate(const BrickCatalogue& catalogue) const
{
  auto check = [](bool ok, const std::string& message) {
    if (!ok) throw ConfigError("scene: " + message);
  };
  check(!catalogue.empty(), "the brick catalogue is empty");
  for (const std::string& type : types)
    check(catalogue.find(type) != nullptr,
          "parameter 'types': unknown brick type '" + type + "' (known: " + catalogue.namesJoined() + ")");
  check(min_distance_m > 0.0 && max_distance_m >= min_distance_m, "need 0 < min_distance_m <= max_distance_m");
  check(min_elevation_deg > 0.0 && max_elevation_deg <= 89.9 && min_elevation_deg <= max_elevation_deg,
        "need 0 < min_elevation_deg <= max_elevation_deg <= 89.9");
  check(max_tilt_deg >= 0.0 && max_tilt_deg < 60.0, "max_tilt_deg must be in [0, 60)");
  check(max_pile_bricks >= 2, "max_pile_bricks must be >= 2");
  check(max_rows >= 1 && max_layers >= 1, "max_rows and max_layers must be >= 1");
  check(max_gap_m >= 0.0 && max_gap_m <= 0.05, "parameter 'max_gap_m' must be in [0, 0.05]");
  check(zero_gap_probability >= 0.0 && zero_gap_probability <= 1.0,
        "parameter 'zero_gap_probability' must be in [0, 1]");
  check(max_row_length_m > 0.0, "parameter 'max_row_length_m' must be > 0");
  check(pallet_length_m > 0.0 && pallet_length_m <= 5.0, "parameter 'pallet_length_m' must be in (0, 5]");
  check(pallet_width_m > 0.0 && pallet_width_m <= 5.0, "parameter 'pallet_width_m' must be in (0, 5]");
  check(missing_box_probability >= 0.0 && missing_box_probability < 1.0,
        "parameter 'missing_box_probability' must be in [0, 1)");
  check(layer_offset_m >= 0.0 && layer_offset_m <= 0.5, "parameter 'layer_offset_m' must be in [0, 0.5]");
  check(max_table_boxes >= 1 && max_table_boxes <= 20, "parameter 'max_table_boxes' must be in [1, 20]");
  check(upright_probability >= 0.0 && upright_probability <= 1.0, "parameter 'upright_probability' must be in [0, 1]");
  check(stack_probability >= 0.0 && stack_probability <= 1.0, "parameter 'stack_probability' must be in [0, 1]");
  check(edge_radius_m >= 0.0 && edge_radius_m <= 0.02, "parameter 'edge_radius_m' must be in [0, 0.02]");
}

SceneGenerator::SceneGenerator(BrickCatalogue catalogue, SceneParams params)
  : catalogue_(std::move(catalogue)), params_(std::move(params))
{
  params_.validate(catalogue_);
}

Scene SceneGenerator::generate(std::uint64_t seed) const
{
  Scene scene = Builder(catalogue_, params_, seed).build();
  if (params_.markings) addMarkings(scene, seed, params_.kind);
  return scene;
}

Eigen::Isometry3d lookAt(const Eigen::Vector3d& target_world, double distance_m, double elevation_deg,
                         double azimuth_deg)
{
  const double elevation = elevation_deg * kDegToRad, azimuth = azimuth_deg * kDegToRad;
  // Optical axis pointing from the camera to the target.
  const Eigen::Vector3d forward(-std::cos(elevation) * std::cos(azimuth), -std::cos(elevation) * std::sin(azimuth),
                                -std::sin(elevation));
  // Right = forward x up; at straight-down views fall back to the azimuth.
  Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ());
  if (right.norm() < 1e-6) right = Eigen::Vector3d(-std::sin(azimuth), std::cos(azimuth), 0.0);
  right.normalize();
  const Eigen::Vector3d down = forward.cross(right);
  Eigen::Isometry3d world_T_camera = Eigen::Isometry3d::Identity();
  world_T_camera.linear().col(0) = right;
  world_T_camera.linear().col(1) = down;
  world_T_camera.linear().col(2) = forward;
  world_T_camera.translation() = target_world - distance_m * forward;
  return world_T_camera;
}
}  // namespace sim
}  // namespace brick_pose
