#include "brick_pose/pipeline/pipeline_config.h"

#include <sstream>

#include "brick_pose/common/errors.h"
#include "brick_pose/correction/correction_mode.h"

namespace brick_pose
{
namespace
{
void require(bool condition, const char* field, const char* rule)
{
  if (!condition) throw ConfigError(std::string("parameter '") + field + "' " + rule);
}

std::string text(double value)
{
  std::ostringstream out;
  out.precision(10);
  out << value;
  return out.str();
}

std::string text(bool value) { return value ? "true" : "false"; }
std::string text(int value) { return std::to_string(value); }
}  // namespace

void StageParams::validate() const
{
  require(max_latency_ms > 0.0, "max_latency_ms", "must be > 0");
  require(queue_size >= 1 && queue_size <= 100, "queue_size", "must be in [1, 100]");
  require(report_period_s > 0.0, "report_period_s", "must be > 0");
}

void RegistrationStageParams::validate() const
{
  require(max_frame_registration_ms > 0.0, "max_frame_registration_ms", "must be > 0");
}

StageParams stageParamsFrom(const ParamLookup& lookup)
{
  const ParamReader read(lookup);
  StageParams params;
  read.number("max_latency_ms", params.max_latency_ms);
  read.integer("queue_size", params.queue_size);
  read.number("report_period_s", params.report_period_s);
  params.validate();
  return params;
}

RegistrationStageParams registrationStageParamsFrom(const ParamLookup& lookup)
{
  const ParamReader read(lookup);
  RegistrationStageParams params;
  read.number("max_frame_registration_ms", params.max_frame_registration_ms);
  params.validate();
  return params;
}

BrickTrackerParams trackerParamsFrom(const ParamLookup& lookup)
{
  const ParamReader read(lookup);
  BrickTrackerParams params;
  read.number("track_match_distance_m", params.match_distance_m);
  read.number("track_match_angle_deg", params.match_angle_deg);
  read.number("track_forget_after_s", params.forget_after_s);
  read.number("pose_smoothing_weight", params.smoothing_weight);
  params.validate();
  return params;
}

TrackedPoseParams trackedPoseParamsFrom(const ParamLookup& lookup)
{
  const ParamReader read(lookup);
  TrackedPoseParams params;
  read.flag("track_poses", params.enabled);
  read.number("moved_translation_m", params.moved_translation_m);
  read.number("moved_rotation_deg", params.moved_rotation_deg);
  params.validate();
  return params;
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
  read.integer("min_area_px", params.hsv.min_area_px);
  params.region_growing.min_area_px = params.hsv.min_area_px;
  params.colour_free.min_area_px = params.hsv.min_area_px;
  read.integer("colour_free_cell_px", params.colour_free.cell_px);
  read.flag("colour_free_estimate_noise", params.colour_free.estimate_noise);
  read.number("colour_free_noise_at_1m_m", params.colour_free.noise_at_1m_m);
  read.number("colour_free_max_noise_at_1m_m", params.colour_free.max_noise_at_1m_m);
  read.flag("colour_free_parallel", params.colour_free.parallel);
  read.flag("colour_free_skip_supporting_plane", params.skip_supporting_plane);
  read.number("crop_min_depth_m", params.cloud.min_depth_m);
  read.number("crop_max_depth_m", params.cloud.max_depth_m);
  read.flag("outlier_removal", params.cloud.outlier_removal_enabled);
  // voxel_leaf_m 0 switches the voxel grid off (and keeps a valid leaf size);
  // unset, the struct's default (off) stands.
  if (const auto leaf = read.text("voxel_leaf_m"))
  {
    const double voxel_leaf_m = parseDouble("voxel_leaf_m", *leaf);
    params.cloud.voxel_enabled = voxel_leaf_m > 0.0;
    if (params.cloud.voxel_enabled) params.cloud.voxel_leaf_m = voxel_leaf_m;
  }
  read.flag("mls", params.cloud.mls_enabled);
  read.number("mls_search_radius_m", params.cloud.mls_search_radius_m);
  read.number("dimension_tolerance_m", params.roi.dimensions.tolerance_m);
  read.number("max_plane_rms_m", params.roi.max_plane_rms_m);
  // The top-face check and the splitting of touching bricks (issue 10).
  read.number("max_tilt_deg", params.roi.max_tilt_deg);
  read.number("edge_min_step_m", params.roi.edges.min_step_m);
  read.number("edge_min_groove_m", params.roi.edges.min_groove_m);
  read.number("edge_min_line_contrast", params.roi.edges.min_line_contrast);
  read.number("edge_seam_noise_factor", params.roi.edges.seam_noise_factor);
  read.number("edge_max_overrun_m", params.roi.edges.max_overrun_m);
  read.number("tiling_min_seam_strength", params.roi.tiling.min_seam_strength);
  read.number("side_height_tolerance_m", params.roi.sides.height_tolerance_m);
  read.number("side_height_tolerance_fraction", params.roi.sides.height_tolerance_fraction);
  read.number("up_min_support_fraction", params.up.min_support_fraction);
  read.integer("front_end_threads", params.worker_threads);
  require(params.worker_threads >= 1 && params.worker_threads <= 64, "front_end_threads", "must be in [1, 64]");
  params.hsv.validate();
  params.region_growing.validate();
  params.colour_free.validate();
  params.cloud.validate();
  params.roi.validate();
  params.up.validate();
  return params;
}

BrickPoseEstimatorParams estimatorParamsFrom(const ParamLookup& lookup)
{
  const ParamReader read(lookup);
  BrickPoseEstimatorParams params;
  read.number("overlap", params.super4pcs.overlap);
  read.number("delta_m", params.super4pcs.delta_m);
  read.integer("sample_size", params.super4pcs.sample_size);
  read.number("max_time_s", params.super4pcs.max_time_s);
  read.number("partial_face_max_time_s", params.partial_face_max_time_s);
  read.number("correction_good_enough_ratio", params.correction_good_enough_ratio);
  if (const auto seed = read.text("seed"))
  {
    const long long value = parseInteger("seed", *seed);
    if (value < 0) throw ConfigError("parameter 'seed' must be >= 0");
    params.super4pcs.seed = static_cast<std::uint64_t>(value);
  }
  if (const auto refinement = read.text("refinement")) params.refinement = parseRefinementMethod(*refinement);
  if (const auto mode = read.text("correction_mode")) params.correction.mode = parseCorrectionMode(*mode);
  read.number("icp_max_correspondence_m", params.icp.max_correspondence_distance_m);
  read.integer("icp_max_iterations", params.icp.max_iterations);
  params.validate();
  return params;
}

std::map<std::string, std::string> pipelineParamsInEffect(const ParamLookup& lookup)
{
  const FrontEndParams front_end = frontEndParamsFrom(lookup);
  const BrickPoseEstimatorParams estimator = estimatorParamsFrom(lookup);
  const StageParams stage = stageParamsFrom(lookup);
  const RegistrationStageParams registration = registrationStageParamsFrom(lookup);
  const BrickTrackerParams tracker = trackerParamsFrom(lookup);
  const TrackedPoseParams tracked = trackedPoseParamsFrom(lookup);
  return {
      {"mode", toString(front_end.mode)},
      {"min_area_px", text(front_end.hsv.min_area_px)},
      {"crop_min_depth_m", text(front_end.cloud.min_depth_m)},
      {"crop_max_depth_m", text(front_end.cloud.max_depth_m)},
      {"outlier_removal", text(front_end.cloud.outlier_removal_enabled)},
      {"voxel_leaf_m", text(front_end.cloud.voxel_enabled ? front_end.cloud.voxel_leaf_m : 0.0)},
      {"mls", text(front_end.cloud.mls_enabled)},
      {"mls_search_radius_m", text(front_end.cloud.mls_search_radius_m)},
      {"dimension_tolerance_m", text(front_end.roi.dimensions.tolerance_m)},
      {"max_plane_rms_m", text(front_end.roi.max_plane_rms_m)},
      {"max_tilt_deg", text(front_end.roi.max_tilt_deg)},
      {"edge_min_step_m", text(front_end.roi.edges.min_step_m)},
      {"edge_min_groove_m", text(front_end.roi.edges.min_groove_m)},
      {"edge_min_line_contrast", text(front_end.roi.edges.min_line_contrast)},
      {"edge_seam_noise_factor", text(front_end.roi.edges.seam_noise_factor)},
      {"edge_max_overrun_m", text(front_end.roi.edges.max_overrun_m)},
      {"tiling_min_seam_strength", text(front_end.roi.tiling.min_seam_strength)},
      {"side_height_tolerance_m", text(front_end.roi.sides.height_tolerance_m)},
      {"side_height_tolerance_fraction", text(front_end.roi.sides.height_tolerance_fraction)},
      {"up_min_support_fraction", text(front_end.up.min_support_fraction)},
      {"colour_free_cell_px", text(front_end.colour_free.cell_px)},
      {"colour_free_estimate_noise", text(front_end.colour_free.estimate_noise)},
      {"colour_free_noise_at_1m_m", text(front_end.colour_free.noise_at_1m_m)},
      {"colour_free_max_noise_at_1m_m", text(front_end.colour_free.max_noise_at_1m_m)},
      {"colour_free_parallel", text(front_end.colour_free.parallel)},
      {"colour_free_skip_supporting_plane", text(front_end.skip_supporting_plane)},
      {"front_end_threads", text(front_end.worker_threads)},
      {"overlap", text(estimator.super4pcs.overlap)},
      {"delta_m", text(estimator.super4pcs.delta_m)},
      {"sample_size", text(estimator.super4pcs.sample_size)},
      {"max_time_s", text(estimator.super4pcs.max_time_s)},
      {"partial_face_max_time_s", text(estimator.partial_face_max_time_s)},
      {"correction_good_enough_ratio", text(estimator.correction_good_enough_ratio)},
      {"seed", std::to_string(estimator.super4pcs.seed)},
      {"refinement", toString(estimator.refinement)},
      {"correction_mode", toString(estimator.correction.mode)},
      {"icp_max_correspondence_m", text(estimator.icp.max_correspondence_distance_m)},
      {"icp_max_iterations", text(estimator.icp.max_iterations)},
      {"max_latency_ms", text(stage.max_latency_ms)},
      {"queue_size", text(stage.queue_size)},
      {"report_period_s", text(stage.report_period_s)},
      {"max_frame_registration_ms", text(registration.max_frame_registration_ms)},
      {"track_match_distance_m", text(tracker.match_distance_m)},
      {"track_match_angle_deg", text(tracker.match_angle_deg)},
      {"track_forget_after_s", text(tracker.forget_after_s)},
      {"pose_smoothing_weight", text(tracker.smoothing_weight)},
      {"track_poses", text(tracked.enabled)},
      {"moved_translation_m", text(tracked.moved_translation_m)},
      {"moved_rotation_deg", text(tracked.moved_rotation_deg)},
  };
}
}  // namespace brick_pose
