#include "brick_pose/catalogue/brick_catalogue.h"

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <opencv2/core.hpp>

#include "brick_pose/catalogue/resting.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/common/yaml_document.h"

namespace brick_pose
{
namespace
{
template <std::size_t N, typename T>
std::array<T, N> readArray(const cv::FileNode& node, const std::string& field, const std::string& brick)
{
  std::array<T, N> values{};
  if (!node.isSeq() || node.size() != N)
    throw ConfigError("brick catalogue: brick '" + brick + "' field '" + field + "' must be a list of " +
                      std::to_string(N) + " numbers");
  for (std::size_t i = 0; i < N; ++i)
    values[i] = static_cast<T>(static_cast<int>(node[static_cast<int>(i)]));
  return values;
}

double readPositive(const cv::FileNode& node, const std::string& field, const std::string& brick)
{
  if (node[field].empty() || !node[field].isReal())
  {
    if (!node[field].isInt())
      throw ConfigError("brick catalogue: brick '" + brick + "' is missing number '" + field + "'");
  }
  return static_cast<double>(node[field]);
}

BrickType parseBrick(const cv::FileNode& node)
{
  if (!node.isMap())
    throw ConfigError("brick catalogue: every entry of 'bricks' must be a map of name, length_m, ...");
  BrickType type;
  if (!node["name"].isString())
    throw ConfigError("brick catalogue: every brick needs a string 'name'");
  type.name = static_cast<std::string>(node["name"]);
  type.length_m = readPositive(node, "length_m", type.name);
  type.width_m = readPositive(node, "width_m", type.name);
  type.height_m = readPositive(node, "height_m", type.name);
  if (!node["plate_rgb"].empty())
    type.plate_rgb = readArray<3, unsigned char>(node["plate_rgb"], "plate_rgb", type.name);
  if (!node["body_rgb"].empty())
    type.body_rgb = readArray<3, unsigned char>(node["body_rgb"], "body_rgb", type.name);
  // Both or neither: a type without them has no plate colour.
  const bool has_min = !node["hsv_min"].empty(), has_max = !node["hsv_max"].empty();
  if (has_min != has_max)
    throw ConfigError("brick catalogue: brick '" + type.name + "' has " + (has_min ? "hsv_min" : "hsv_max") +
                      " without " + (has_min ? "hsv_max" : "hsv_min") + " (give both, or neither for a type with no plate colour)");
  if (has_min)
  {
    HsvRange range;
    range.min = readArray<3, int>(node["hsv_min"], "hsv_min", type.name);
    range.max = readArray<3, int>(node["hsv_max"], "hsv_max", type.name);
    type.plate_hsv = range;
  }
  type.validate();
  return type;
}
}  // namespace

bool HsvRange::contains(int h, int s, int v) const
{
  const bool hue_ok = wrapsHue() ? (h >= min[0] || h <= max[0]) : (h >= min[0] && h <= max[0]);
  return hue_ok && s >= min[1] && s <= max[1] && v >= min[2] && v <= max[2];
}

void BrickType::validate() const
{
  auto fail = [this](const std::string& what) {
    throw ConfigError("brick type '" + name + "': " + what);
  };
  if (name.empty()) throw ConfigError("brick type: empty name");
  if (!(length_m > 0.0) || !std::isfinite(length_m)) fail("length_m must be > 0");
  if (!(width_m > 0.0) || !std::isfinite(width_m)) fail("width_m must be > 0");
  if (!(height_m > 0.0) || !std::isfinite(height_m)) fail("height_m must be > 0");
  // x is the long edge by convention; the registration's symmetry handling
  // relies on it.
  if (width_m > length_m) fail("width_m must not exceed length_m (x is the long edge)");
  if (!plate_hsv) return;
  for (int i = 0; i < 3; ++i)
  {
    const int limit = i == 0 ? 180 : 255;
    if (plate_hsv->min[i] < 0 || plate_hsv->min[i] > limit || plate_hsv->max[i] < 0 || plate_hsv->max[i] > limit)
      fail("hsv_min/hsv_max channel " + std::to_string(i) + " must be in 0.." + std::to_string(limit));
    if (i > 0 && plate_hsv->min[i] > plate_hsv->max[i])
      fail("hsv_min must not exceed hsv_max for saturation and value");
  }
}

BrickCatalogue::BrickCatalogue(std::vector<BrickType> types) : types_(std::move(types))
{
  for (std::size_t i = 0; i < types_.size(); ++i)
  {
    types_[i].validate();
    for (std::size_t j = 0; j < i; ++j)
      if (types_[j].name == types_[i].name)
        throw ConfigError("brick catalogue: type '" + types_[i].name + "' is defined twice");
  }
}

BrickCatalogue BrickCatalogue::mbzirc2020()
{
  auto make = [](const std::string& name, double length_m, std::array<unsigned char, 3> plate,
                 std::array<unsigned char, 3> body, std::array<int, 3> hsv_min, std::array<int, 3> hsv_max) {
    BrickType type;
    type.name = name;
    type.length_m = length_m;
    type.width_m = 0.20;
    type.height_m = 0.20;
    type.plate_rgb = plate;
    type.body_rgb = body;
    HsvRange range;
    range.min = hsv_min;
    range.max = hsv_max;
    type.plate_hsv = range;
    return type;
  };
  // Keep in step with config/bricks.yaml (a unit test checks they agree).
  return BrickCatalogue({
      make("red", 0.30, {{200, 25, 25}}, {{215, 150, 150}}, {{170, 120, 25}}, {{7, 255, 255}}),
      make("green", 0.60, {{30, 170, 50}}, {{150, 205, 160}}, {{45, 120, 25}}, {{85, 255, 255}}),
      make("blue", 1.20, {{25, 60, 200}}, {{150, 165, 215}}, {{100, 120, 25}}, {{130, 255, 255}}),
      make("orange", 1.80, {{245, 140, 15}}, {{235, 200, 160}}, {{11, 120, 25}}, {{24, 255, 255}}),
  });
}

BrickCatalogue BrickCatalogue::fromYamlString(const std::string& text)
{
  cv::FileStorage storage = openYamlDocument(text, "brick catalogue", "a top-level list 'bricks:'");
  std::vector<BrickType> types;
  // OpenCV asserts (cv::Exception) on lookups in nodes of the wrong kind;
  // the checks below come first, the catch is for what they do not foresee.
  try
  {
    if (!storage.root().isMap())
      throw ConfigError("brick catalogue: expected a map with a top-level list 'bricks:'");
    const cv::FileNode bricks = storage["bricks"];
    if (bricks.empty() || !bricks.isSeq())
      throw ConfigError("brick catalogue: expected a top-level list 'bricks:'");
    for (const cv::FileNode& node : bricks)
      types.push_back(parseBrick(node));
  }
  catch (const cv::Exception& e)
  {
    throw ConfigError(std::string("brick catalogue: malformed YAML: ") + e.what());
  }
  catch (const std::length_error& e)
  {
    throw ConfigError(std::string("brick catalogue: malformed YAML: ") + e.what());
  }
  return BrickCatalogue(std::move(types));
}

BrickCatalogue BrickCatalogue::fromYamlFile(const std::string& path)
{
  std::ifstream file(path);
  if (!file)
    throw ConfigError("brick catalogue: cannot open file '" + path + "'");
  std::stringstream text;
  text << file.rdbuf();
  try
  {
    return fromYamlString(text.str());
  }
  catch (const ConfigError& e)
  {
    throw ConfigError(path + ": " + e.what());
  }
}

const BrickType* BrickCatalogue::find(const std::string& name) const
{
  for (const BrickType& type : types_)
    if (type.name == name) return &type;
  return nullptr;
}

std::optional<BrickType> BrickCatalogue::findResting(const std::string& name) const
{
  for (const BrickType& type : types_)
    for (const Resting resting : {Resting::kUpright, Resting::kOnSide, Resting::kOnEnd})
    {
      BrickType variant = restingAs(type, resting);
      if (variant.name == name) return variant;
    }
  return std::nullopt;
}

bool BrickCatalogue::couldRiseTo(double height_m, double margin_m) const
{
  std::vector<double> extents_m;
  for (const BrickType& type : types_) extents_m.insert(extents_m.end(), {type.height_m, type.width_m, type.length_m});
  for (std::size_t i = 0; i < extents_m.size(); ++i)
  {
    if (std::abs(extents_m[i] - height_m) <= margin_m) return true;
    for (std::size_t j = i; j < extents_m.size(); ++j)
      if (std::abs(extents_m[i] + extents_m[j] - height_m) <= margin_m) return true;
  }
  return false;
}

const BrickType& BrickCatalogue::at(const std::string& name) const
{
  const BrickType* type = find(name);
  if (type == nullptr)
    throw ConfigError("unknown brick type '" + name + "' (known: " + namesJoined() + ")");
  return *type;
}

std::string BrickCatalogue::namesJoined() const
{
  std::string joined;
  for (const BrickType& type : types_)
    joined += (joined.empty() ? "" : ", ") + type.name;
  return joined;
}
}  // namespace brick_pose
