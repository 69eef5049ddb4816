#pragma once
// Named parameters of the pipeline stages (front end, registration,
// refinement, the stages' budgets), read through a ParamLookup: the nodelets
// feed them from rosparam (private first, then the pipeline's namespace),
// the tools from the command line or a YAML file. The defaults are those of
// the params structs; config/pipeline.yaml repeats them for users to edit,
// and a unit test checks that the two agree.

#include <map>
#include <string>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/frame/scene_change.h"
#include "brick_pose/common/param_parsing.h"
#include "brick_pose/pose/brick_pose_estimator.h"
#include "brick_pose/pose/brick_tracker.h"
#include "brick_pose/pose/tracked_pose.h"
#include "brick_pose/pipeline/front_end.h"

namespace brick_pose
{
/// What every stage nodelet shares.
struct StageParams
{
  /// A stage drops a frame that is older than this (since it arrived) when
  /// it reaches it: a backlog then costs one frame, not the next ones too.
  /// Bricks do not move, so the default is generous.
  double max_latency_ms = 3000.0;
  /// Subscriber and publisher queue length between stages.
  int queue_size = 2;
  /// Period of each stage's summary log line and /diagnostics status.
  double report_period_s = 5.0;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// The registration stage's budget for a whole frame: it takes no further
/// candidates of a frame once it has spent this long; the ones it skipped
/// go first in the next frame.
struct RegistrationStageParams
{
  double max_frame_registration_ms = 400.0;

  void validate() const;
};

/// Reusing a static scene's front end (stages 2-3): while a frame shows
/// nothing changed since the keyframe (the last frame the front end ran
/// on), the keyframe's segments and candidates stand for it.
struct FrontEndReuseParams
{
  bool enabled = true;
  /// The front end runs again at least this often on a static scene, so a
  /// change below the test's sensitivity (a brick creeping by a few
  /// millimetres with nothing else in view changing) is measured within
  /// this time. 0: only on a change.
  double keyframe_max_age_s = 2.0;
  SceneChangeParams change;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// `reuse_unchanged_frames`, `keyframe_max_age_s`, `scene_change_depth_sigmas`,
/// `scene_change_step_fraction`, `scene_change_colour_levels`, `scene_change_max_blocks`.
FrontEndReuseParams frontEndReuseParamsFrom(const ParamLookup& lookup);

/// `track_match_distance_m`, `track_match_angle_deg`, `track_forget_after_s`,
/// `pose_smoothing_weight` (1: off).
BrickTrackerParams trackerParamsFrom(const ParamLookup& lookup);

/// `track_poses` (the tracked path), `moved_translation_m`, `moved_rotation_deg`.
TrackedPoseParams trackedPoseParamsFrom(const ParamLookup& lookup);

/// `max_latency_ms`, `queue_size`, `report_period_s`.
StageParams stageParamsFrom(const ParamLookup& lookup);
/// `max_frame_registration_ms`.
RegistrationStageParams registrationStageParamsFrom(const ParamLookup& lookup);

/// `catalogue_path` (empty or unset: the built-in MBZIRC 2020 bricks).
BrickCatalogue catalogueFrom(const ParamLookup& lookup);

/// `mode` (hsv | region_growing | colour_free), `min_area_px`, `crop_min_depth_m`,
/// `crop_max_depth_m`, `outlier_removal`, `voxel_leaf_m` (0 disables),
/// `mls`, `mls_search_radius_m`, `dimension_tolerance_m`, `max_plane_rms_m`, `ragged_outline_px`,
/// `front_end_threads`;
/// the top-face check: `max_tilt_deg`, `edge_min_step_m`, `edge_min_groove_m`,
/// `edge_min_line_contrast`, `edge_seam_noise_factor`, `edge_max_overrun_m`, `tiling_min_seam_strength`,
/// `plain_seam_line_share`, `confirm_seams_along_lines`,
/// `side_height_tolerance_m`, `side_height_tolerance_fraction`,
/// `up_min_support_fraction`.
/// for colour_free: `colour_free_cell_px`, `colour_free_estimate_noise`,
/// `colour_free_noise_at_1m_m` (fixed or fallback noise), `colour_free_max_noise_at_1m_m`,
/// `colour_free_parallel`, `colour_free_skip_supporting_plane`.
/// Throws ConfigError naming the parameter.
FrontEndParams frontEndParamsFrom(const ParamLookup& lookup);

/// `overlap`, `delta_m`, `sample_size`, `max_time_s`, `partial_face_max_time_s`,
/// `correction_good_enough_ratio`, `seed`, `refinement`
/// (correction | icp | none), `correction_mode` (paper | full),
/// `icp_max_correspondence_m`, `icp_max_iterations`.
BrickPoseEstimatorParams estimatorParamsFrom(const ParamLookup& lookup);

/// Every parameter above as the text of its value in effect (after parsing
/// and defaults), by name: logged by the stages at start, and used by the
/// test that config/pipeline.yaml agrees with the structs' defaults.
std::map<std::string, std::string> pipelineParamsInEffect(const ParamLookup& lookup);
}  // namespace brick_pose
