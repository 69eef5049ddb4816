#pragma once
// Stable identities for detected bricks. A detection keeps its id (and so
// its tf frame brick_<type>_<id>) while it is the same physical brick: same
// type, top-face centre within match_distance_m and top-face normal within
// match_angle_deg of where the brick was last seen. Ids count up from 1 (0
// means "no id" in the service request) and are never given to another brick: a brick gone for longer than
// forget_after_s is forgotten, and comes back, if it does, under a new id.
// Optionally the pose of a brick that has not moved is smoothed over frames
// (exponential averaging of position and orientation), which removes the
// sensor's frame-to-frame jitter; any real motion resets the average.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace brick_pose
{
struct BrickTrackerParams
{
  double match_distance_m = 0.05;
  double match_angle_deg = 20.0;
  /// A brick not seen for this long (in the frames' own time) is forgotten.
  double forget_after_s = 2.0;
  /// Weight of the newest pose in the average of a static brick, in (0, 1];
  /// 1 turns smoothing off.
  double smoothing_weight = 1.0;
  /// A brick whose new pose is within these of its average has not moved.
  double static_translation_m = 0.003;
  double static_rotation_deg = 1.0;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// One brick of the current frame, as the tracker needs it.
struct TrackerObservation
{
  std::string type_name;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< T_cam_brick
};

/// What the tracker made of an observation.
struct TrackedBrick
{
  std::uint32_t id = 0;
  /// The pose to publish: the observation's, or the static average.
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  bool new_track = true;      ///< first seen in this frame
  int frames_seen = 1;        ///< consecutive frames this id has been matched
  int frames_averaged = 1;    ///< observations in the smoothed pose
};

class BrickTracker
{
public:
  explicit BrickTracker(const BrickTrackerParams& params = BrickTrackerParams());

  /// Matches this frame's observations to the known bricks (closest pairs
  /// first), starts new tracks for the rest, forgets bricks gone too long.
  /// `stamp_s` is the frame's time; a stamp going back (a looped bag) keeps
  /// the tracks and restarts their clocks.
  std::vector<TrackedBrick> update(const std::vector<TrackerObservation>& observations, double stamp_s);

  std::size_t trackCount() const { return tracks_.size(); }

private:
  struct Track
  {
    std::uint32_t id = 0;
    std::string type_name;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    double last_seen_s = 0.0;
    int frames_seen = 0;
    int frames_averaged = 0;
  };
  bool matches(const Track& track, const TrackerObservation& observation) const;
  void follow(Track& track, const TrackerObservation& observation, double stamp_s);

  BrickTrackerParams params_;
  std::vector<Track> tracks_;
  std::uint32_t next_id_ = 1;
  double last_stamp_s_ = 0.0;
  bool started_ = false;
};
}  // namespace brick_pose
