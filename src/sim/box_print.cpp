#include "brick_pose/sim/box_print.h"

#include <algorithm>
#include <cmath>

#include "brick_pose/sim/fast_random.h"

namespace brick_pose
{
namespace sim
{
namespace
{
constexpr double kTapeHalfWidthM = 0.024;  // 48 mm packing tape
constexpr double kTapeDownEndsM = 0.07;
constexpr double kSeamHalfWidthM = 0.001;  // the gap between the top flaps
constexpr double kLabelMarginM = 0.01;

/// Fraction of the footprint [centre - size/2, centre + size/2] inside [low, high].
double coverage(double centre, double low, double high, double size)
{
  const double half = 0.5 * size;
  return std::max(0.0, std::min(centre + half, high) - std::max(centre - half, low)) / size;
}

double latticeValue(std::int64_t i, std::int64_t j, std::uint64_t seed)
{
  std::uint64_t h = seed ^ (static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL) ^
                    (static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4FULL);
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDULL;
  h ^= h >> 33;
  h *= 0xC4CEB9FE1A85EC53ULL;
  h ^= h >> 33;
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
}

/// Smooth value noise in [0, 1) with features `cell_m` apart.
double valueNoise(double a, double b, double cell_m, std::uint64_t seed)
{
  const double ga = a / cell_m, gb = b / cell_m;
  const double fa = std::floor(ga), fb = std::floor(gb);
  const auto i = static_cast<std::int64_t>(fa), j = static_cast<std::int64_t>(fb);
  const auto smooth = [](double t) { return t * t * (3.0 - 2.0 * t); };
  const double ta = smooth(ga - fa), tb = smooth(gb - fb);
  const double low = latticeValue(i, j, seed) * (1 - ta) + latticeValue(i + 1, j, seed) * ta;
  const double high = latticeValue(i, j + 1, seed) * (1 - ta) + latticeValue(i + 1, j + 1, seed) * ta;
  return low * (1 - tb) + high * tb;
}

Eigen::Vector3d mix(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t) { return a + t * (b - a); }
}  // namespace

BoxPrint::BoxPrint(const BrickType& type, const SurfaceMarkings& markings)
  : markings_(markings), half_length_m_(0.5 * type.length_m), half_width_m_(0.5 * type.width_m)
{
  FastRandom random(markings.seed);
  if (markings.printed)
  {
    // A packaging design: a few saturated colours and a light one.
    for (int k = 0; k < 4; ++k)
    {
      Eigen::Vector3d colour;
      for (int c = 0; c < 3; ++c) colour[c] = random.uniform(20.0, 250.0);
      palette_.push_back(colour);
    }
    palette_.push_back(Eigen::Vector3d(235.0, 230.0, 215.0));
  }
  for (int k = 0; k < markings.labels; ++k)
  {
    Label label;
    const double long_m = random.uniform(0.08, 0.15), short_m = long_m * random.uniform(0.6, 0.75);
    label.text_along_x = random.bernoulli(0.7);
    const double extent_x = label.text_along_x ? long_m : short_m;
    const double extent_y = label.text_along_x ? short_m : long_m;
    const double room_x = half_length_m_ - kLabelMarginM - 0.5 * extent_x;
    const double room_y = half_width_m_ - kLabelMarginM - 0.5 * extent_y;
    if (room_x < 0.0 || room_y < 0.0) continue;  // too small a box for a label
    const double cx = random.uniform(-room_x, room_x), cy = random.uniform(-room_y, room_y);
    label.x = {cx - 0.5 * extent_x, cx + 0.5 * extent_x};
    label.y = {cy - 0.5 * extent_y, cy + 0.5 * extent_y};
    // Text in the first half of the short side, a barcode below it.
    double row = 0.08;
    const int rows = 3 + static_cast<int>(random.next() % 4);
    for (int r = 0; r < rows && row < 0.5; ++r)
    {
      const double height = random.uniform(0.05, 0.08);
      label.text_rows.push_back({row, row + height});
      row += height + random.uniform(0.03, 0.06);
    }
    label.barcode_rows = {0.6, 0.9};
    const double module = 0.008;  // of the long side: ~1 mm bars on a 10 cm label
    for (double along = 0.1; along < 0.9;)
    {
      const double width = (1 + random.next() % 3) * module;
      label.bars.push_back({along, std::min(0.9, along + width)});
      along += width + (1 + random.next() % 3) * module;
    }
    labels_.push_back(label);
  }
}

double BoxPrint::fibre(double a, double b) const
{
  // Blotches a few centimetres across and a fine grain; the grain fades when
  // a pixel covers many of its cells, as a camera would average it.
  constexpr double kBlotchM = 0.025, kGrainM = 0.004;
  return 1.0 + 0.10 * (valueNoise(a, b, kBlotchM, markings_.seed) - 0.5) +
         0.06 * (valueNoise(a, b, kGrainM, markings_.seed ^ 0xA5A5A5A5ULL) - 0.5);
}

Eigen::Vector3d BoxPrint::topColour(const Eigen::Vector3d& base_rgb, double x, double y, double footprint_m) const
{
  Eigen::Vector3d colour = base_rgb * fibre(x, y);
  if (markings_.tape == SurfaceMarkings::Tape::kNone)
    colour = mix(colour, 0.35 * colour, coverage(y, -kSeamHalfWidthM, kSeamHalfWidthM, footprint_m));
  else
  {
    const Eigen::Vector3d tape = markings_.tape == SurfaceMarkings::Tape::kBrown
                                     ? Eigen::Vector3d(150.0, 104.0, 58.0)
                                     : (1.08 * colour + Eigen::Vector3d::Constant(10.0)).eval();
    colour = mix(colour, tape, coverage(y, -kTapeHalfWidthM, kTapeHalfWidthM, footprint_m));
  }
  for (const Label& label : labels_)
  {
    const double area = coverage(x, label.x.low, label.x.high, footprint_m) *
                        coverage(y, label.y.low, label.y.high, footprint_m);
    if (area <= 0.0) continue;
    // Label coordinates as fractions: along its long side and across it.
    const double length_x = label.x.high - label.x.low, length_y = label.y.high - label.y.low;
    const double along = label.text_along_x ? (x - label.x.low) / length_x : (y - label.y.low) / length_y;
    const double across = label.text_along_x ? (y - label.y.low) / length_y : (x - label.x.low) / length_x;
    const double long_m = label.text_along_x ? length_x : length_y, short_m = label.text_along_x ? length_y : length_x;
    double ink = 0.0;
    for (const Span& row : label.text_rows)
      ink += 0.55 * coverage(across, row.low, row.high, footprint_m / short_m) *
             coverage(along, 0.08, 0.92, footprint_m / long_m);
    const double in_barcode = coverage(across, label.barcode_rows.low, label.barcode_rows.high, footprint_m / short_m);
    if (in_barcode > 0.0)
    {
      double bars = 0.0;
      for (const Span& bar : label.bars)
        bars += coverage(along, bar.low, bar.high, footprint_m / long_m);
      ink += 0.9 * in_barcode * std::min(1.0, bars);
    }
    const Eigen::Vector3d paper(238.0, 238.0, 232.0);
    colour = mix(colour, paper * (1.0 - std::min(1.0, ink)), area);
  }
  return colour;
}

Eigen::Vector3d BoxPrint::printedColour(CuboidFace face, double a, double b) const
{
  // Posterised value noise: patches 4-8 cm across with hard edges between
  // colours, different on every face.
  const std::uint64_t seed = markings_.seed + 0x9E37ULL * static_cast<std::uint64_t>(face);
  const double level = valueNoise(a, b, 0.06, seed) * 0.7 + valueNoise(a, b, 0.02, seed ^ 0x5A5AULL) * 0.3;
  const std::size_t index = std::min(palette_.size() - 1, static_cast<std::size_t>(level * palette_.size()));
  return palette_[index];
}

Eigen::Vector3d BoxPrint::colourAt(const Eigen::Vector3d& base_rgb, CuboidFace face, const Eigen::Vector3d& point_brick,
                                   double footprint_m) const
{
  const double size = std::max(footprint_m, 1e-5);
  const double x = point_brick.x(), y = point_brick.y(), z = point_brick.z();
  if (markings_.printed)
  {
    switch (face)
    {
      case CuboidFace::kPlusX:
      case CuboidFace::kMinusX:
        return printedColour(face, y, z);
      case CuboidFace::kPlusY:
      case CuboidFace::kMinusY:
        return printedColour(face, x, z);
      default:
        return printedColour(face, x, y);
    }
  }
  switch (face)
  {
    case CuboidFace::kTop:
      return topColour(base_rgb, x, y, size);
    case CuboidFace::kPlusX:
    case CuboidFace::kMinusX:
    {
      Eigen::Vector3d colour = base_rgb * fibre(y, z);
      if (markings_.tape == SurfaceMarkings::Tape::kBrown)
        colour = mix(colour, Eigen::Vector3d(150.0, 104.0, 58.0),
                     coverage(y, -kTapeHalfWidthM, kTapeHalfWidthM, size) * coverage(z, -kTapeDownEndsM, 0.0, size));
      else if (markings_.tape == SurfaceMarkings::Tape::kClear)
        colour = mix(colour, 1.08 * colour + Eigen::Vector3d::Constant(10.0),
                     coverage(y, -kTapeHalfWidthM, kTapeHalfWidthM, size) * coverage(z, -kTapeDownEndsM, 0.0, size));
      return colour;
    }
    case CuboidFace::kPlusY:
    case CuboidFace::kMinusY:
      return base_rgb * fibre(x, z);
    default:
      return base_rgb * fibre(x, y);
  }
}
}  // namespace sim
}  // namespace brick_pose
