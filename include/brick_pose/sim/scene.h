#pragma once
// What the synthetic D415 rig looks at: cuboids on a ground plane, seen by a
// camera, and the ground truth it reports back.
//
// World frame: z up, the ground is the plane z = 0. Brick frame: origin at the
// centre of the top face, x along the long edge, y along the short edge, z out
// of the top face; the body spans z in [-height, 0].

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/geometry/cuboid.h"

namespace brick_pose
{
namespace sim
{
/// Colour-only details of a plain box's surface: none of them changes depth,
/// all of them put edges into the colour image that are not a box's edges.
struct SurfaceMarkings
{
  enum class Tape : unsigned char
  {
    kNone,
    kBrown,  // packing tape, darker than the cardboard
    kClear,  // clear tape: a faint sheen
  };

  /// Kraft cardboard: fibre texture, and a dark flap seam along the top's
  /// long axis where no tape covers it.
  bool cardboard = false;
  /// Printed packaging (cereal and tea boxes, as in the mOSD scenes): every
  /// face covered in patches of vivid colour with hard edges. Replaces the
  /// cardboard look when set.
  bool printed = false;
  /// A 48 mm tape stripe along the top's long axis and 7 cm down both ends.
  Tape tape = Tape::kNone;
  /// Printed labels on the top (0..2): white, lines of text, a barcode.
  int labels = 0;
  /// Places the labels, the barcodes' bars and the texture.
  std::uint64_t seed = 0;
};

struct PlacedBrick
{
  BrickType type;
  Eigen::Isometry3d world_T_brick = Eigen::Isometry3d::Identity();
  SurfaceMarkings markings{};  // braced: aggregate initialisers may leave it out
};

struct Scene
{
  std::vector<PlacedBrick> bricks;
  /// Pose of the camera's optical frame (x right, y down, z forward).
  Eigen::Isometry3d world_T_camera = Eigen::Isometry3d::Identity();
  std::array<unsigned char, 3> ground_rgb{{120, 112, 100}};
  /// Radius of the rounded edges of every brick's top face (cardboard boxes:
  /// a few millimetres; 0 = sharp). The rounding dips the surface by up to
  /// this much next to an edge and darkens it, so that boxes touching with
  /// no gap still show a crease in depth and a dark line in colour.
  double edge_radius_m = 0.0;
};

/// Faces of a cuboid, as stored in the face label image.
enum class CuboidFace : unsigned char
{
  kNone = 0,
  kTop = 1,     // +z, the plate
  kBottom = 2,  // -z
  kPlusX = 3,
  kMinusX = 4,
  kPlusY = 5,
  kMinusY = 6,
};

/// Whether a brick's top face is wholly in view, and why not: decided by
/// rays to samples along its four edges (sim/top_face_visibility.h).
struct TopFaceVisibility
{
  bool facing_camera = false;
  bool cut_by_border = false;
  bool occluded = false;
  std::array<double, 4> edge_visible_fraction{{0.0, 0.0, 0.0, 0.0}};
  double tilt_deg = 0.0;  // brick +z against the world's up
  CuboidFace up_face = CuboidFace::kTop;

  /// Facing the camera, at most kTopFaceMaxTiltDeg from up, every edge sample seen.
  bool complete() const;
};

/// The face up of a box resting on a long side or an end, seen as the top
/// of the type restingAs() makes of it (catalogue/resting.h): what a
/// detector that types it so must find.
struct RestingFaceTruth
{
  std::string type;  // restingAs()'s name: "box_small lying on a side"
  CuboidFace face = CuboidFace::kNone;  // which of the brick's faces is up
  /// Length and width of the face up, and the depth of the box below it.
  Eigen::Vector3d dimensions_m = Eigen::Vector3d::Zero();
  /// The face's frame: origin at its centre, z out of it, x along its long edge.
  Eigen::Isometry3d camera_T_face = Eigen::Isometry3d::Identity();
  /// As BrickTruth's for a top: visible share, and its edges as seen.
  double visible_fraction = 0.0;
  TopFaceVisibility view;
};

/// Ground truth of one brick in one rendered frame.
struct BrickTruth
{
  int instance_id = 0;  // value of this brick in the instance label image (1-based)
  std::string type;
  Eigen::Vector3d dimensions_m = Eigen::Vector3d::Zero();
  Eigen::Isometry3d camera_T_brick = Eigen::Isometry3d::Identity();
  /// Visible pixels of the top face over the pixels it would cover if nothing
  /// occluded it and the image were unbounded (0..1).
  double visible_fraction = 0.0;
  int visible_top_pixels = 0;

  /// True when the top face is wholly in view: it faces the camera and up
  /// (tilted at most kTopFaceMaxTiltDeg from the world's vertical), and every
  /// sample along each of its four edges projects at least one pixel inside
  /// the image and is not hidden by another brick. A detector that calls a
  /// face "complete" when this is false gave a confident wrong answer.
  bool top_face_complete = false;
  /// Its edges as seen: cut by the border (within one pixel of it), hidden
  /// by another brick, the fraction of each edge's samples seen (corner k to
  /// corner k+1 of topFaceCornersInBrick()), the tilt of the brick's +z from
  /// the world's up (near 90 for a box standing on a side or an end: its
  /// catalogue top is then vertical and must not be taken for a top) and the
  /// face that points most nearly up.
  TopFaceVisibility top_face;
  /// Other bricks with a side face within kTouchingToleranceM of one of this
  /// brick's side faces (side by side or end to end, any gap 0..3 mm).
  int touching_neighbours = 0;
  /// Set when the face most nearly up is a long side or an end.
  std::optional<RestingFaceTruth> resting_face;
};

/// Tilt beyond which a top face counts as a side face in BrickTruth.
constexpr double kTopFaceMaxTiltDeg = 45.0;
/// Gap up to which two bricks count as touching in BrickTruth.
constexpr double kTouchingToleranceM = 0.0035;

using brick_pose::cuboidCornersInBrick;
using brick_pose::topFaceCornersInBrick;

/// Top-face corners expressed in the camera frame.
std::array<Eigen::Vector3d, 4> topFaceCornersInCamera(const BrickTruth& truth);

/// The frame of `face` of a brick of `type`, in the brick frame: origin at
/// the face's centre, z along its outward normal, x along its longer edge
/// (identity for the top).
Eigen::Isometry3d brickTFace(const BrickType& type, CuboidFace face);

/// How a brick with `face` up rests (kUpright for the top or the bottom).
Resting restingWithFaceUp(CuboidFace face);
}  // namespace sim
}  // namespace brick_pose
