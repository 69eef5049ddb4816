#pragma once
// Named parameters of the pipeline stages (front end, registration,
// refinement), read through a ParamLookup: the nodelets feed them from
// rosparam, the tools from the command line.

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/param_parsing.h"
#include "brick_pose/pose/brick_pose_estimator.h"
#include "brick_pose/pipeline/front_end.h"

namespace brick_pose
{
/// `catalogue_path` (empty or unset: the built-in MBZIRC 2020 bricks).
BrickCatalogue catalogueFrom(const ParamLookup& lookup);

/// `mode` (hsv | region_growing | colour_free), `min_area_px`, `crop_min_depth_m`,
/// `crop_max_depth_m`, `outlier_removal`, `voxel_leaf_m` (0 disables),
/// `mls`, `mls_search_radius_m`, `dimension_tolerance_m`, `max_plane_rms_m`;
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
}  // namespace brick_pose
