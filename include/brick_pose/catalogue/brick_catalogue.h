#pragma once
// The catalogue of cuboid types the pipeline knows: dimensions and, when the
// type has one, the colour of the face it segments (the ferromagnetic plate
// on the top face). Plain cardboard boxes have none: they are segmented
// without colour.
//
// Brick frame convention (used by ground truth, registration and tf output):
// origin at the centre of the top face, x along the long edge, y along the
// short edge, z out of the top face (away from the body).

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace brick_pose
{
/// An HSV box in OpenCV units (H 0..180, S and V 0..255). When hue_min >
/// hue_max the hue range wraps through 180/0 (reds).
struct HsvRange
{
  std::array<int, 3> min{{0, 0, 0}};
  std::array<int, 3> max{{180, 255, 255}};

  bool wrapsHue() const { return min[0] > max[0]; }
  bool contains(int h, int s, int v) const;
};

/// How a box rests on what carries it: on its bottom (the catalogue's top
/// face up), on a long side, or on an end (see catalogue/resting.h).
enum class Resting
{
  kUpright,
  kOnSide,
  kOnEnd,
};

struct BrickType
{
  std::string name;
  double length_m = 0.0;  // along x, the long edge of the top face
  double width_m = 0.0;   // along y
  double height_m = 0.0;  // along -z, below the top face
  std::array<unsigned char, 3> plate_rgb{{255, 255, 255}};  // top face colour
  std::array<unsigned char, 3> body_rgb{{128, 128, 128}};   // side faces
  /// HSV range of the top face's colour; empty for a type with no plate
  /// colour (a plain box), which HSV segmentation skips.
  std::optional<HsvRange> plate_hsv;
  /// A catalogue type seen resting otherwise (restingAs()): how it rests
  /// and the catalogue type's name. Its length and width are then those of
  /// the face up, and its height the depth below that face.
  Resting resting = Resting::kUpright;
  std::string catalogue_name;

  bool hasPlateColour() const { return plate_hsv.has_value(); }
  /// The catalogue type this is: its own name when upright.
  const std::string& catalogueName() const { return resting == Resting::kUpright ? name : catalogue_name; }
  Eigen::Vector3d dimensions_m() const { return {length_m, width_m, height_m}; }
  /// Throws ConfigError naming the field when a value is unusable.
  void validate() const;
};

class BrickCatalogue
{
public:
  BrickCatalogue() = default;
  explicit BrickCatalogue(std::vector<BrickType> types);

  /// MBZIRC 2020 Challenge 2 bricks, the defaults of config/bricks.yaml.
  static BrickCatalogue mbzirc2020();

  /// Reads the `bricks:` list of a YAML file (format of config/bricks.yaml).
  /// Throws ConfigError with the file and the field at fault.
  static BrickCatalogue fromYamlFile(const std::string& path);

  /// Parses the same format from a string (used by tests and rosparam dumps).
  static BrickCatalogue fromYamlString(const std::string& text);

  const std::vector<BrickType>& types() const { return types_; }
  bool empty() const { return types_.empty(); }

  /// nullptr when there is no type of that name.
  const BrickType* find(const std::string& name) const;

  /// Like find() but throws ConfigError listing the known types.
  const BrickType& at(const std::string& name) const;

  /// A catalogue type, or one resting on a side or an end named as
  /// restingAs() names it ("box_small lying on a side"); nullopt for none.
  std::optional<BrickType> findResting(const std::string& name) const;

  std::string namesJoined() const;

  /// Whether an item of the catalogue lying on a face, on its bottom, a side
  /// or an end, alone or on another one, could rise `height_m` above it
  /// (within `margin_m`): a wall that high beside a face may be resting on
  /// it rather than standing beside it.
  bool couldRiseTo(double height_m, double margin_m) const;

private:
  std::vector<BrickType> types_;
};
}  // namespace brick_pose
