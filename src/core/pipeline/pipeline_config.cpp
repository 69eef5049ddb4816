#include "brick_pose/pipeline/pipeline_config.h"

#include "brick_pose/common/errors.h"
#include "brick_pose/correction/correction_mode.h"

namespace brick_pose
{
void StageParams::validate() const
{
  const ParamCheck check("pipeline");
  check.require(max_latency_ms > 0.0, "max_latency_ms", "must be > 0");
  check.require(queue_size >= 1 && queue_size <= 100, "queue_size", "must be in [1, 100]");
  check.require(report_period_s > 0.0, "report_period_s", "must be > 0");
}

void RegistrationStageParams::validate() const
{
  const ParamCheck check("pipeline");
  check.require(max_frame_registration_ms > 0.0, "max_frame_registration_ms", "must be > 0");
}

void FrontEndReuseParams::validate() const
{
  const ParamCheck check("pipeline");
  check.require(keyframe_max_age_s >= 0.0, "keyframe_max_age_s", "must be >= 0", keyframe_max_age_s);
  change.validate();
}

namespace
{
ParamBindings frontEndReuseBindings(FrontEndReuseParams& params)
{
  return {{"reuse_unchanged_frames", &params.enabled},
          {"keyframe_max_age_s", &params.keyframe_max_age_s},
          {"scene_change_depth_sigmas", &params.change.depth_change_sigmas},
          {"scene_change_step_fraction", &params.change.step_fraction},
          {"scene_change_colour_levels", &params.change.colour_change_levels},
          {"scene_change_max_blocks", &params.change.max_changed_blocks}};
}

ParamBindings stageBindings(StageParams& params)
{
  return {{"max_latency_ms", &params.max_latency_ms},
          {"queue_size", &params.queue_size},
          {"report_period_s", &params.report_period_s}};
}

ParamBindings registrationStageBindings(RegistrationStageParams& params)
{
  return {{"max_frame_registration_ms", &params.max_frame_registration_ms}};
}

ParamBindings trackerBindings(BrickTrackerParams& params)
{
  return {{"track_match_distance_m", &params.match_distance_m},
          {"track_match_angle_deg", &params.match_angle_deg},
          {"track_forget_after_s", &params.forget_after_s},
          {"pose_smoothing_weight", &params.smoothing_weight}};
}

ParamBindings trackedPoseBindings(TrackedPoseParams& params)
{
  return {{"track_poses", &params.enabled},
          {"moved_translation_m", &params.moved_translation_m},
          {"moved_rotation_deg", &params.moved_rotation_deg}};
}

/// The front end's plain parameters; `mode` and `voxel_leaf_m` are read apart
/// (an enum; 0 switches the voxel grid off), and `min_area_px` is the hsv
/// segmenter's, copied to the other two segmenters.
ParamBindings frontEndBindings(FrontEndParams& params)
{
  CloudProcessorParams& cloud = params.cloud;
  RoiFilterParams& roi = params.roi;
  ColourFreeParams& colour_free = params.colour_free;
  return {{"min_area_px", &params.hsv.min_area_px},
          {"colour_free_cell_px", &colour_free.cell_px},
          {"colour_free_estimate_noise", &colour_free.estimate_noise},
          {"colour_free_noise_at_1m_m", &colour_free.noise_at_1m_m},
          {"colour_free_max_noise_at_1m_m", &colour_free.max_noise_at_1m_m},
          {"colour_free_parallel", &colour_free.parallel},
          {"colour_free_skip_supporting_plane", &params.skip_supporting_plane},
          {"region_growing_block_angle_mrad", &params.region_growing.block_angle_mrad},
          {"crop_min_depth_m", &cloud.min_depth_m},
          {"crop_max_depth_m", &cloud.max_depth_m},
          {"outlier_removal", &cloud.outlier_removal_enabled},
          {"mls", &cloud.mls_enabled},
          {"mls_search_radius_m", &cloud.mls_search_radius_m},
          {"dimension_tolerance_m", &roi.dimensions.tolerance_m},
          {"max_plane_rms_m", &roi.max_plane_rms_m},
          {"ragged_outline_px", &roi.ragged_outline_px},
          {"place_on_catalogue_size", &roi.place_on_catalogue_size},
          // The top-face check and the splitting of touching bricks (issue 10).
          {"max_tilt_deg", &roi.max_tilt_deg},
          {"edge_min_step_m", &roi.edges.min_step_m},
          {"edge_min_groove_m", &roi.edges.min_groove_m},
          {"edge_min_line_contrast", &roi.edges.min_line_contrast},
          {"edge_seam_noise_factor", &roi.edges.seam_noise_factor},
          {"edge_max_overrun_m", &roi.edges.max_overrun_m},
          {"edge_max_hidden_by_wall_m", &roi.edges.max_hidden_by_wall_m},
          {"edge_max_wall_foot_shift_px", &roi.edges.max_wall_foot_shift_px},
          {"resting_height_margin_m", &roi.resting_height_margin_m},
          {"tiling_min_seam_strength", &roi.tiling.min_seam_strength},
          {"plain_seam_line_share", &roi.plain_seam_line_share},
          {"size_placed_line_tolerance_m", &roi.size_placed_line_tolerance_m},
          {"confirm_seams_along_lines", &roi.confirm_seams_along_lines},
          {"height_above_support_tolerance_m", &roi.height_above_support_tolerance_m},
          {"side_height_tolerance_m", &roi.sides.height_tolerance_m},
          {"side_height_tolerance_fraction", &roi.sides.height_tolerance_fraction},
          {"up_min_support_fraction", &params.up.min_support_fraction},
          {"front_end_threads", &params.worker_threads}};
}

/// The estimator's plain parameters; `seed`, `refinement` and
/// `correction_mode` are read apart (an unsigned seed, two enums).
ParamBindings estimatorBindings(BrickPoseEstimatorParams& params)
{
  return {{"overlap", &params.super4pcs.overlap},
          {"delta_m", &params.super4pcs.delta_m},
          {"sample_size", &params.super4pcs.sample_size},
          {"max_time_s", &params.super4pcs.max_time_s},
          {"partial_face_max_time_s", &params.partial_face_max_time_s},
          {"correction_good_enough_ratio", &params.correction_good_enough_ratio},
          {"icp_max_correspondence_m", &params.icp.max_correspondence_distance_m},
          {"icp_max_iterations", &params.icp.max_iterations}};
}

/// voxel_leaf_m 0 switches the voxel grid off (and keeps a valid leaf size);
/// unset, the struct's default (off) stands.
void readVoxelLeaf(const ParamReader& read, CloudProcessorParams& cloud)
{
  const auto leaf = read.text("voxel_leaf_m");
  if (!leaf) return;
  const double voxel_leaf_m = parseDouble("voxel_leaf_m", *leaf);
  cloud.voxel_enabled = voxel_leaf_m > 0.0;
  if (cloud.voxel_enabled) cloud.voxel_leaf_m = voxel_leaf_m;
}

void validateFrontEnd(const FrontEndParams& params)
{
  const ParamCheck check("pipeline");
  check.require(params.worker_threads >= 1 && params.worker_threads <= 64, "front_end_threads", "must be in [1, 64]");
  params.hsv.validate();
  params.region_growing.validate();
  params.colour_free.validate();
  params.cloud.validate();
  params.roi.validate();
  params.up.validate();
}

void insertAll(std::map<std::string, std::string>& into, const std::map<std::string, std::string>& values)
{
  into.insert(values.begin(), values.end());
}
}  // namespace

StageParams stageParamsFrom(const ParamLookup& lookup) { return readValidated(lookup, stageBindings); }

RegistrationStageParams registrationStageParamsFrom(const ParamLookup& lookup)
{
  return readValidated(lookup, registrationStageBindings);
}

BrickTrackerParams trackerParamsFrom(const ParamLookup& lookup) { return readValidated(lookup, trackerBindings); }

FrontEndReuseParams frontEndReuseParamsFrom(const ParamLookup& lookup)
{
  return readValidated(lookup, frontEndReuseBindings);
}

TrackedPoseParams trackedPoseParamsFrom(const ParamLookup& lookup)
{
  return readValidated(lookup, trackedPoseBindings);
}

BrickCatalogue catalogueFrom(const ParamLookup& lookup)
{
  const auto path = lookup("catalogue_path");
  return path && !path->empty() ? BrickCatalogue::fromYamlFile(*path) : BrickCatalogue::mbzirc2020();
}

FrontEndParams frontEndParamsFrom(const ParamLookup& lookup)
{
  const ParamReader read(lookup);
  FrontEndParams params;
  if (const auto mode = read.text("mode")) params.mode = parseSegmentationMode(*mode);
  readBound(read, frontEndBindings(params));
  params.region_growing.min_area_px = params.hsv.min_area_px;
  params.colour_free.min_area_px = params.hsv.min_area_px;
  readVoxelLeaf(read, params.cloud);
  validateFrontEnd(params);
  return params;
}

BrickPoseEstimatorParams estimatorParamsFrom(const ParamLookup& lookup)
{
  const ParamReader read(lookup);
  BrickPoseEstimatorParams params;
  readBound(read, estimatorBindings(params));
  if (const auto seed = read.text("seed"))
  {
    const long long value = parseInteger("seed", *seed);
    if (value < 0) throw ConfigError("parameter 'seed' must be >= 0");
    params.super4pcs.seed = static_cast<std::uint64_t>(value);
  }
  if (const auto refinement = read.text("refinement")) params.refinement = parseRefinementMethod(*refinement);
  if (const auto mode = read.text("correction_mode")) params.correction.mode = parseCorrectionMode(*mode);
  params.validate();
  return params;
}

std::map<std::string, std::string> pipelineParamsInEffect(const ParamLookup& lookup)
{
  FrontEndParams front_end = frontEndParamsFrom(lookup);
  BrickPoseEstimatorParams estimator = estimatorParamsFrom(lookup);
  StageParams stage = stageParamsFrom(lookup);
  RegistrationStageParams registration = registrationStageParamsFrom(lookup);
  BrickTrackerParams tracker = trackerParamsFrom(lookup);
  TrackedPoseParams tracked = trackedPoseParamsFrom(lookup);
  FrontEndReuseParams reuse = frontEndReuseParamsFrom(lookup);
  std::map<std::string, std::string> effect = {
      {"mode", toString(front_end.mode)},
      {"seed", std::to_string(estimator.super4pcs.seed)},
      {"refinement", toString(estimator.refinement)},
      {"correction_mode", toString(estimator.correction.mode)},
  };
  // Reported as read: 0 when the voxel grid is off.
  double voxel_leaf_m = front_end.cloud.voxel_enabled ? front_end.cloud.voxel_leaf_m : 0.0;
  insertAll(effect, boundValues({{"voxel_leaf_m", &voxel_leaf_m}}));
  insertAll(effect, boundValues(frontEndBindings(front_end)));
  insertAll(effect, boundValues(estimatorBindings(estimator)));
  insertAll(effect, boundValues(stageBindings(stage)));
  insertAll(effect, boundValues(registrationStageBindings(registration)));
  insertAll(effect, boundValues(trackerBindings(tracker)));
  insertAll(effect, boundValues(trackedPoseBindings(tracked)));
  insertAll(effect, boundValues(frontEndReuseBindings(reuse)));
  return effect;
}
}  // namespace brick_pose
