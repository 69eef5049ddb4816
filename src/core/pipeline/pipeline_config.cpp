#include "brick_pose/pipeline/pipeline_config.h"

#include "brick_pose/common/errors.h"
#include "brick_pose/correction/correction_mode.h"

namespace brick_pose
{
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
  // voxel_leaf_m 0 switches the voxel grid off (and keeps a valid leaf size).
  double voxel_leaf_m = params.cloud.voxel_leaf_m;
  read.number("voxel_leaf_m", voxel_leaf_m);
  params.cloud.voxel_enabled = voxel_leaf_m > 0.0;
  if (params.cloud.voxel_enabled) params.cloud.voxel_leaf_m = voxel_leaf_m;
  read.flag("mls", params.cloud.mls_enabled);
  read.number("mls_search_radius_m", params.cloud.mls_search_radius_m);
  read.number("dimension_tolerance_m", params.roi.dimensions.tolerance_m);
  read.number("max_plane_rms_m", params.roi.max_plane_rms_m);
  params.hsv.validate();
  params.region_growing.validate();
  params.colour_free.validate();
  params.cloud.validate();
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
}  // namespace brick_pose
