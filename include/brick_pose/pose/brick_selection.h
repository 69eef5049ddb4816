#pragma once
// Which of the detected bricks the grasp planner should go for, and in what
// order the detections are numbered (tf frames brick_<type>_<n>).
//
// ROS-free: the node turns its detections into DetectedBrick values and, when
// tf knows it, passes the base_link z axis expressed in the camera frame as
// `up_in_camera`. Without it "up" is estimated from the bricks themselves:
// their plates face up, so the mean of their z axes is a good vertical.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace brick_pose
{
enum class SelectionPolicy
{
  kNearest,        ///< Smallest distance from the camera origin.
  kHighest,        ///< Largest height of the top face along "up".
  kMostConfident,  ///< Highest registration fitness.
  kPickable,       ///< The highest of the bricks nothing rests on.
};

/// "nearest" (also ""), "highest", "most_confident" or "pickable"; throws
/// ConfigError listing the valid names otherwise.
SelectionPolicy parseSelectionPolicy(const std::string& name);

/// The name parseSelectionPolicy() accepts for `policy`.
const char* toString(SelectionPolicy policy);

/// One brick the pipeline found, as the selection sees it.
struct DetectedBrick
{
  std::string type_name;
  /// Pose of the brick frame (origin at the top-face centre, x along the
  /// long edge, z out of the top face) in the camera optical frame.
  Eigen::Isometry3d T_cam_brick = Eigen::Isometry3d::Identity();
  /// (length, width, height) in metres.
  Eigen::Vector3d dimensions_m = Eigen::Vector3d::Zero();
  /// Registration fitness, 0 (worst) .. 1 (best).
  double fitness = 0.0;
  /// The whole top face was measured (every edge a real edge). Only such a
  /// brick is ever chosen: a partial face gives a good orientation but a
  /// guessed centre, not something to grasp.
  bool complete_face = false;
  /// Stable identity (see brick_tracker.h).
  std::uint32_t id = 0;
};

/// Unit "up" in the camera frame: `up_in_camera` normalised when given, else
/// the normalised mean of the bricks' z axes. Throws InputError when the
/// given vector is zero or not finite, or when nothing is given and the
/// bricks' z axes cancel out (or there are no bricks).
Eigen::Vector3d resolveUpInCamera(const std::vector<DetectedBrick>& bricks,
                                  const std::optional<Eigen::Vector3d>& up_in_camera = std::nullopt);

/// True when another brick rests on bricks[index]: its top face is higher
/// along `unit_up` by more than half of bricks[index]'s height, and the two
/// top faces, projected along `unit_up`, overlap by more than a few
/// millimetres (so that bricks laid edge to edge do not cover each other).
bool isCovered(const std::vector<DetectedBrick>& bricks, std::size_t index, const Eigen::Vector3d& unit_up);

/// pickableMask()[i] == !isCovered(bricks, i, up), with up resolved as in
/// resolveUpInCamera(). Empty for no bricks.
std::vector<bool> pickableMask(const std::vector<DetectedBrick>& bricks,
                               const std::optional<Eigen::Vector3d>& up_in_camera = std::nullopt);

/// Indices of the bricks of `type` ("" = any type), best first for `policy`
/// (ties keep the input order). kPickable lists the pickable bricks highest
/// first, then the covered ones highest first. Every other brick's presence
/// counts for covering, whatever its type.
std::vector<std::size_t> orderBricks(const std::vector<DetectedBrick>& bricks, SelectionPolicy policy,
                                     const std::string& type = "",
                                     const std::optional<Eigen::Vector3d>& up_in_camera = std::nullopt);

/// The index of the brick to pick (the get_brick_pose service's rule): the
/// first of orderBricks() whose whole top face was measured; kPickable also
/// skips covered bricks. Every brick, complete or not, counts for covering
/// others. nullopt when no brick of `type` qualifies (or the list is empty).
std::optional<std::size_t> selectBrick(const std::vector<DetectedBrick>& bricks, SelectionPolicy policy,
                                       const std::string& type = "",
                                       const std::optional<Eigen::Vector3d>& up_in_camera = std::nullopt);

/// Like selectBrick(), but throws InputError saying what was seen ("no green
/// brick that nothing rests on with its whole top face in view (seen: 2
/// green complete, 1 blue partial)") when none qualifies.
std::size_t chooseBrick(const std::vector<DetectedBrick>& bricks, SelectionPolicy policy, const std::string& type = "",
                        const std::optional<Eigen::Vector3d>& up_in_camera = std::nullopt);

/// The index of the brick with identity `id`; throws InputError saying which
/// ids there are when none has it.
std::size_t findBrickById(const std::vector<DetectedBrick>& bricks, std::uint32_t id);

/// "2 green complete, 1 blue partial" ("none" for no bricks).
std::string describeBricks(const std::vector<DetectedBrick>& bricks);
}  // namespace brick_pose
