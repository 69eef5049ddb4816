#include "brick_pose/sim/box_layouts.h"
#include "brick_pose/common/angles.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brick_pose
{
namespace sim
{
namespace
{

/// Extent of a box in the layout's x and y when it lies flat, long edge
/// along x (`turned` false) or along y.
struct Footprint
{
  const BrickType* type;
  bool turned;
  double along_x_m() const { return turned ? type->width_m : type->length_m; }
  double along_y_m() const { return turned ? type->length_m : type->width_m; }
};

Eigen::Isometry3d flatPose(const Eigen::Vector3d& top_centre_world, double yaw_rad)
{
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  pose.translation() = top_centre_world;
  return pose;
}

const BrickType& randomType(LayoutContext& context)
{
  return *context.types[context.random.next() % context.types.size()];
}

/// A seam between neighbours: closed, or a few millimetres wide.
double seamGap(LayoutContext& context)
{
  if (context.random.bernoulli(context.params.zero_gap_probability)) return 0.0;
  return context.random.uniform(0.0, context.params.max_gap_m);
}

/// Places a flat box whose footprint centre is `centre_local` in a layout
/// frame rotated by `yaw_rad` about the world's vertical.
PlacedBrick placeFlat(const Footprint& footprint, const Eigen::Vector2d& centre_local, double yaw_rad,
                      const Eigen::Vector2d& offset_world)
{
  const Eigen::Vector3d local(centre_local.x(), centre_local.y(), 0.0);
  Eigen::Vector3d world = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) * local;
  world.head<2>() += offset_world;
  const double box_yaw = yaw_rad + (footprint.turned ? 0.5 * M_PI : 0.0);
  return {*footprint.type, flatPose(world, box_yaw)};
}

double highestCorner(const PlacedBrick& brick)
{
  double top = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& corner : cuboidCornersInBrick(brick.type))
    top = std::max(top, (brick.world_T_brick * corner).z());
  return top;
}

/// One layer packed in strips across the pallet: each strip along x holds
/// boxes of one footprint depth, mostly of the strip's type. Centred on the
/// layout origin.
std::vector<std::pair<Footprint, Eigen::Vector2d>> packLayer(LayoutContext& context)
{
  const SceneParams& params = context.params;
  // A box may overhang the pallet a little, as real loads do.
  const double overhang_m = 0.03;
  const double half_l = 0.5 * params.pallet_length_m, half_w = 0.5 * params.pallet_width_m;
  std::vector<std::pair<Footprint, Eigen::Vector2d>> boxes;
  double y = -half_w;
  for (;;)
  {
    // A strip's footprint: a few tries to find one that still fits.
    Footprint strip{nullptr, false};
    for (int attempt = 0; attempt < 8 && strip.type == nullptr; ++attempt)
    {
      const Footprint candidate{&randomType(context), context.random.bernoulli(0.5)};
      if (y + candidate.along_y_m() <= half_w + overhang_m) strip = candidate;
    }
    if (strip.type == nullptr) break;
    double x = -half_l;
    for (;;)
    {
      Footprint box = strip;
      if (context.random.bernoulli(0.25))
      {
        // A box of another size in the strip: mixed sizes within a layer.
        const Footprint other{&randomType(context), context.random.bernoulli(0.5)};
        if (other.along_y_m() <= strip.along_y_m()) box = other;
      }
      if (x + box.along_x_m() > half_l + overhang_m) break;
      boxes.push_back({box, Eigen::Vector2d(x + 0.5 * box.along_x_m(), y + 0.5 * box.along_y_m())});
      x += box.along_x_m() + seamGap(context);
    }
    y += strip.along_y_m() + seamGap(context);
  }
  if (boxes.empty()) return boxes;
  // Centre what was packed (a strip may end short of the pallet's far end).
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  for (const auto& [footprint, centre] : boxes)
  {
    const Eigen::Vector2d half(0.5 * footprint.along_x_m(), 0.5 * footprint.along_y_m());
    low = low.cwiseMin(centre - half);
    high = high.cwiseMax(centre + half);
  }
  const Eigen::Vector2d middle = 0.5 * (low + high);
  for (auto& entry : boxes)
    entry.second -= middle;
  return boxes;
}

/// Lays a packed layer on what is already placed (or the ground), keeping
/// each box with `keep_probability`.
void addLayer(LayoutContext& context, std::vector<PlacedBrick>& placed, double yaw_rad,
              const Eigen::Vector2d& offset_world, double keep_probability)
{
  const std::vector<PlacedBrick> below = placed;
  for (const auto& [footprint, centre] : packLayer(context))
  {
    const bool missing = context.random.bernoulli(context.params.missing_box_probability);
    const bool kept = context.random.bernoulli(keep_probability);
    if (missing || !kept) continue;
    PlacedBrick box = placeFlat(footprint, centre, yaw_rad, offset_world);
    restBrickOn(box, supportHeightUnder(box, below));
    placed.push_back(box);
  }
}

/// Orientation of a table box: flat, on its long side (large face vertical)
/// or on its end (long edge vertical, tall and narrow).
Eigen::Matrix3d tableOrientation(LayoutContext& context, double yaw_rad)
{
  const Eigen::AngleAxisd yaw(yaw_rad, Eigen::Vector3d::UnitZ());
  if (!context.random.bernoulli(context.params.upright_probability)) return yaw.toRotationMatrix();
  const double sign = context.random.bernoulli(0.5) ? 1.0 : -1.0;
  const Eigen::Vector3d axis = context.random.bernoulli(0.5) ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (yaw * Eigen::AngleAxisd(sign * 0.5 * M_PI, axis)).toRotationMatrix();
}

/// Largest horizontal distance of a corner from the body's centre.
double footprintRadius(const PlacedBrick& brick)
{
  const Eigen::Vector3d centre = brick.world_T_brick * Eigen::Vector3d(0.0, 0.0, -0.5 * brick.type.height_m);
  double radius = 0.0;
  for (const Eigen::Vector3d& corner : cuboidCornersInBrick(brick.type))
    radius = std::max(radius, ((brick.world_T_brick * corner) - centre).head<2>().norm());
  return radius;
}

/// Moves `brick` horizontally so that its body's centre is over `centre_xy`.
void centreBodyOver(PlacedBrick& brick, const Eigen::Vector2d& centre_xy)
{
  const Eigen::Vector3d body = brick.world_T_brick * Eigen::Vector3d(0.0, 0.0, -0.5 * brick.type.height_m);
  brick.world_T_brick.translation().head<2>() += centre_xy - body.head<2>();
}
}  // namespace

void restBrickOn(PlacedBrick& brick, double floor_z)
{
  double lowest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& corner : cuboidCornersInBrick(brick.type))
    lowest = std::min(lowest, (brick.world_T_brick * corner).z());
  brick.world_T_brick.translation().z() += floor_z - lowest;
}

double supportHeightUnder(const PlacedBrick& brick, const std::vector<PlacedBrick>& placed)
{
  // The face whose outward normal points most nearly down rests on the support.
  const Eigen::Matrix3d& rotation = brick.world_T_brick.linear();
  int down_axis = 2;
  double down_sign = -1.0, most_down = 0.0;
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {-1.0, 1.0})
      if (sign * rotation(2, axis) < most_down)
      {
        most_down = sign * rotation(2, axis);
        down_axis = axis;
        down_sign = sign;
      }
  const Eigen::Vector3d low(-0.5 * brick.type.length_m, -0.5 * brick.type.width_m, -brick.type.height_m);
  const Eigen::Vector3d high(0.5 * brick.type.length_m, 0.5 * brick.type.width_m, 0.0);
  const int a = (down_axis + 1) % 3, b = (down_axis + 2) % 3;
  // Samples reach the face's edges (less a hair, so that a box merely
  // touching the edge line does not carry it) and lie closer than any box is
  // wide: a box under the face cannot slip between them.
  constexpr double kInsetM = 1e-4, kSpacingM = 0.02;
  const auto samplesAcross = [&](int axis) {
    return 1 + static_cast<int>(std::ceil((high[axis] - low[axis]) / kSpacingM));
  };
  const int count_a = samplesAcross(a), count_b = samplesAcross(b);
  const auto at = [&](int axis, int index, int count) {
    return low[axis] + kInsetM + (high[axis] - low[axis] - 2.0 * kInsetM) * index / (count - 1);
  };
  double height = 0.0;
  for (const PlacedBrick& other : placed)
  {
    const double other_top = highestCorner(other);
    if (other_top <= height) continue;
    const Eigen::Isometry3d other_T_world = other.world_T_brick.inverse();
    bool under = false;
    for (int i = 0; i < count_a && !under; ++i)
      for (int j = 0; j < count_b && !under; ++j)
      {
        Eigen::Vector3d sample;
        sample[down_axis] = down_sign > 0.0 ? high[down_axis] : low[down_axis];
        sample[a] = at(a, i, count_a);
        sample[b] = at(b, j, count_b);
        Eigen::Vector3d probe = brick.world_T_brick * sample;
        probe.z() = other_top - 1e-6;
        const Eigen::Vector3d local = other_T_world * probe;
        under = std::abs(local.x()) <= 0.5 * other.type.length_m && std::abs(local.y()) <= 0.5 * other.type.width_m &&
                local.z() <= 0.0 && local.z() >= -other.type.height_m;
      }
    if (under) height = other_top;
  }
  return height;
}

std::vector<PlacedBrick> touchingRows(LayoutContext& context)
{
  const SceneParams& params = context.params;
  const BrickType& type = randomType(context);
  const int max_columns = std::max(1, static_cast<int>(std::floor(params.max_row_length_m / type.length_m)));
  int rows = 1 + static_cast<int>(context.random.next() % params.max_rows);
  int columns = 1 + static_cast<int>(context.random.next() % max_columns);
  // Something must touch.
  if (rows * columns < 2) (max_columns >= 2 ? columns : rows) = 2;
  const int layers = 1 + static_cast<int>(context.random.next() % params.max_layers);
  const double yaw_rad = context.random.uniform(-M_PI, M_PI);
  const Footprint footprint{&type, false};

  // Seams are drawn once and shared by the layers, so that stacked layers
  // stand exactly on each other.
  std::vector<double> row_y(rows, 0.0);
  for (int row = 1; row < rows; ++row)
    row_y[row] = row_y[row - 1] + type.width_m + seamGap(context);
  std::vector<std::vector<double>> column_x(rows, std::vector<double>(columns, 0.0));
  for (int row = 0; row < rows; ++row)
  {
    // Some rows are laid half a brick along (running bond).
    column_x[row][0] = context.random.bernoulli(0.25) ? 0.5 * type.length_m : 0.0;
    for (int column = 1; column < columns; ++column)
      column_x[row][column] = column_x[row][column - 1] + type.length_m + seamGap(context);
  }
  const double centre_y = 0.5 * row_y.back();
  const double centre_x = 0.5 * (columns - 1) * type.length_m;

  std::vector<PlacedBrick> bricks;
  for (int layer = 0; layer < layers; ++layer)
    for (int row = 0; row < rows; ++row)
      for (int column = 0; column < columns; ++column)
      {
        PlacedBrick brick =
            placeFlat(footprint, Eigen::Vector2d(column_x[row][column] - centre_x, row_y[row] - centre_y), yaw_rad,
                      Eigen::Vector2d::Zero());
        brick.world_T_brick.translation().z() = (layer + 1) * type.height_m;
        bricks.push_back(brick);
      }
  return bricks;
}

std::vector<PlacedBrick> palletLayer(LayoutContext& context)
{
  std::vector<PlacedBrick> boxes;
  const double yaw_rad = context.random.uniform(-M_PI, M_PI);
  addLayer(context, boxes, yaw_rad, Eigen::Vector2d::Zero(), 1.0);
  return boxes;
}

std::vector<PlacedBrick> palletStack(LayoutContext& context)
{
  const SceneParams& params = context.params;
  const int layers = params.max_layers < 2 ? 1 : 2 + static_cast<int>(context.random.next() % (params.max_layers - 1));
  const double yaw_rad = context.random.uniform(-M_PI, M_PI);
  std::vector<PlacedBrick> boxes;
  addLayer(context, boxes, yaw_rad, Eigen::Vector2d::Zero(), 1.0);
  for (int layer = 1; layer < layers; ++layer)
  {
    const Eigen::Vector2d offset(context.random.uniform(-params.layer_offset_m, params.layer_offset_m),
                                 context.random.uniform(-params.layer_offset_m, params.layer_offset_m));
    // Upper layers are partly unloaded, so lower tops show beside them.
    addLayer(context, boxes, yaw_rad, offset, context.random.uniform(0.4, 1.0));
  }
  return boxes;
}

std::vector<PlacedBrick> tableBoxes(LayoutContext& context)
{
  const SceneParams& params = context.params;
  const int count = 1 + static_cast<int>(context.random.next() % params.max_table_boxes);
  constexpr double kSpreadM = 0.35;   // boxes stand within this radius of the table's centre
  constexpr double kClearanceM = 0.02;
  std::vector<PlacedBrick> boxes;
  for (int i = 0; i < count; ++i)
  {
    PlacedBrick box{randomType(context), Eigen::Isometry3d::Identity()};
    box.world_T_brick.linear() = tableOrientation(context, context.random.uniform(-M_PI, M_PI));
    if (!boxes.empty() && context.random.bernoulli(params.stack_probability))
    {
      // On top of an earlier box, roughly centred.
      const PlacedBrick& base = boxes[context.random.next() % boxes.size()];
      const Eigen::Vector3d base_centre =
          base.world_T_brick * Eigen::Vector3d(0.0, 0.0, -0.5 * base.type.height_m);
      centreBodyOver(box, base_centre.head<2>() + Eigen::Vector2d(context.random.uniform(-0.02, 0.02),
                                                                   context.random.uniform(-0.02, 0.02)));
    }
    else
    {
      bool placed = false;
      for (int attempt = 0; attempt < 30 && !placed; ++attempt)
      {
        const Eigen::Vector2d centre(context.random.uniform(-kSpreadM, kSpreadM),
                                     context.random.uniform(-kSpreadM, kSpreadM));
        centreBodyOver(box, centre);
        placed = true;
        for (const PlacedBrick& other : boxes)
        {
          const Eigen::Vector3d other_centre =
              other.world_T_brick * Eigen::Vector3d(0.0, 0.0, -0.5 * other.type.height_m);
          if ((other_centre.head<2>() - centre).norm() < footprintRadius(other) + footprintRadius(box) + kClearanceM)
            placed = false;
        }
      }
      if (!placed) continue;
    }
    restBrickOn(box, supportHeightUnder(box, boxes));
    boxes.push_back(box);
  }
  return boxes;
}
}  // namespace sim
}  // namespace brick_pose
