#pragma once
// What bench_pose records per matched brick and per run.

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "bench_pose/methods.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/sensor_model.h"

namespace brick_pose
{
namespace pose_bench
{
/// Bricks whose top face is less visible than this do not count.
constexpr double kMinVisibleFraction = 0.6;

struct MethodOutcome
{
  bool success = false;
  std::string failure;
  double rotation_error_deg = std::nan("");
  double translation_error_mm = std::nan("");
  double refinement_us = std::nan("");
};

/// How far the front end's measurements (what the correction sees) are from
/// the truth: these bound what any correction from them can achieve.
struct MeasurementError
{
  double t1_t2_direction_deg = std::nan("");  ///< T1->T2 vs the true long axis, modulo 180.
  double normal_deg = std::nan("");           ///< Plane normal vs the true face normal.
  double midpoint_in_plane_mm = std::nan("");  ///< T1/T2 midpoint vs true centre, along the face.
  double plane_offset_mm = std::nan("");       ///< Fitted plane vs true centre, along the normal.
  double length_error_mm = std::nan("");       ///< Measured minus catalogue length (< 0: an end is hidden).
  double width_error_mm = std::nan("");        ///< Measured minus catalogue width.
  double fill_ratio = std::nan("");            ///< Of the segment's outline in its quad.
  /// Mean of the segment's points vs the true centre, along the face: the
  /// alternative to the T1/T2 midpoint for the in-plane position.
  double point_centroid_in_plane_mm = std::nan("");
  /// T1/T2 midpoint minus true centre in camera x and y (bias detection).
  double midpoint_camera_x_mm = std::nan("");
  double midpoint_camera_y_mm = std::nan("");
  /// Area centroid of the segment's depth pixels, their rays cut with the
  /// fitted plane, vs the true centre along the face (a candidate
  /// replacement for the quad's centre; see maskAreaCentroid()).
  double mask_area_centroid_in_plane_mm = std::nan("");
};

struct BrickRecord
{
  int frame = 0;
  sim::SceneKind kind = sim::SceneKind::kSingle;
  sim::Lighting lighting = sim::Lighting::kNormal;
  std::string type;
  int instance = 0;
  double distance_m = 0.0;
  double visible_fraction = 0.0;
  bool complete = false;
  bool counted = false;
  std::string exclusion;  ///< Why it does not count; empty when counted.
  bool registered = false;
  double super4pcs_ms = std::nan("");
  double lcp_score = std::nan("");
  MeasurementError measurement;
  std::array<MethodOutcome, kMethodCount> outcomes;
};

struct BenchResults
{
  std::vector<BrickRecord> bricks;
  std::map<std::string, int> unmatched_candidates;  ///< Candidates with no truth brick, by reason.
  int frames = 0;
  int candidates = 0;
  std::vector<double> latency_ms;  ///< Single-brick frames, end to end.
  std::vector<double> latency_frontend_ms;
  std::vector<double> latency_registration_ms;
};
}  // namespace pose_bench
}  // namespace brick_pose
