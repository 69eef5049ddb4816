#include "bench_frontend/cell_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace brick_pose
{
namespace frontend_bench
{
namespace
{
/// A missed top that a candidate lies on without being it: the candidate's
/// own line ("not a top found") says what it is.
constexpr const char* kUnderACandidate = "a candidate lies on it but is not it (see its line)";
/// A missed top found with a wrong type that names its own among the other
/// types it may be: a rejection lying over it is not why it was missed.
constexpr const char* kTypeLeftOpen = "found, its type left open (see its candidate's line)";

/// Legacy tops >= this visible give dimension and corner errors.
constexpr double kMeasuredMinVisibleFraction = 0.95;

void append(std::vector<double>& to, const std::vector<double>& from) { to.insert(to.end(), from.begin(), from.end()); }

/// The rejection that names a missed top (its reason up to its first
/// number, as the earlier benchmark named misses): of those whose box holds
/// a third of the top, the one whose box is most of that top (the tile cut
/// from a split segment, not the whole segment or a neighbour's part).
/// A top found with its type left open is named so, and one whose pixels
/// a candidate holds half of is under that candidate (a box merged with its
/// neighbour: a rejected side face beside it has a box over it too).
std::string missReason(const FrontEndResult& result, const eval::SceneTruth& truth, const eval::TopMatch& match,
                       bool verbose, const std::string& frame_name)
{
  const int face = match.face;
  const bool whole = match.whole_in_view;
  const eval::FaceTruth& top = truth.faces[static_cast<std::size_t>(face)];
  // How much of the top a box holds (sampled every other pixel), and
  // whether that is a third of the top.
  auto holds = [&](const cv::Rect& box, double& share) {
    int inside = 0, samples = 0;
    for (int v = box.y; v < box.br().y; v += 2)
      for (int u = box.x; u < box.br().x; u += 2, ++samples)
        if (truth.face_index.at<int>(v, u) == face) ++inside;
    share = samples > 0 ? static_cast<double>(inside) / samples : 0.0;
    return inside * 4 > top.visible_px / 3;
  };
  // Half the top's pixels in a candidate's own.
  auto pixelsHeldBy = [&](const BrickCandidate& c) {
    const cv::Rect box = c.bounding_box_px & cv::Rect(0, 0, truth.face_index.cols, truth.face_index.rows);
    if (c.mask.empty() || box != c.bounding_box_px) return false;
    int inside = 0;
    for (int v = 0; v < box.height; ++v)
    {
      const unsigned char* mask_row = c.mask.ptr<unsigned char>(v);
      const int* face_row = truth.face_index.ptr<int>(box.y + v) + box.x;
      for (int u = 0; u < box.width; ++u) inside += mask_row[u] && face_row[u] == face ? 1 : 0;
    }
    return inside * 2 >= top.visible_px;
  };
  const bool held_by_a_candidate = std::any_of(result.candidates.begin(), result.candidates.end(), pixelsHeldBy);
  const Rejection* named = nullptr;
  double named_share = 0.0;
  for (const Rejection& rejection : result.rejections)
    if (double share = 0.0; holds(rejection.bounding_box_px, share) && share > named_share)
    {
      named = &rejection;
      named_share = share;
    }
  // Looked for only where no rejection names the miss.
  auto underACandidate = [&]() {
    return std::any_of(result.candidates.begin(), result.candidates.end(), [&](const BrickCandidate& c) {
      double share = 0.0;
      return holds(c.bounding_box_px, share);
    });
  };
  const std::string reason = match.found_type_left_open ? kTypeLeftOpen
                             : held_by_a_candidate      ? kUnderACandidate
                             : named                    ? named->reason
                             : underACandidate()        ? kUnderACandidate
                                                        : "no segment";
  if (verbose)
  {
    // Where the named rejection lies, to find it in an overlay.
    const std::string where = named && reason == named->reason
                                  ? " [rejected box " + std::to_string(named->bounding_box_px.x) + "," +
                                        std::to_string(named->bounding_box_px.y) + " " +
                                        std::to_string(named->bounding_box_px.width) + "x" +
                                        std::to_string(named->bounding_box_px.height) + " px]"
                                  : std::string();
    std::fprintf(stderr, "%s: miss %s%s vis %.2f: %s%s\n", frame_name.c_str(), whole ? "whole " : "", top.type.c_str(),
                 top.visible_fraction, reason.c_str(), where.c_str());
  }
  return reason.substr(0, reason.find_first_of("0123456789"));
}

/// How far each edge of `candidate` (its midpoint) lies outside the
/// truth's edge it stands for (m, negative inside): edges 0 and 2 are the
/// long ones, a width apart; 1 and 3 a length.
std::array<double, 4> edgeOffsetsM(const BrickCandidate& candidate, const eval::TopFaceGeometry& truth)
{
  const Eigen::Vector3d normal = truth.normal.normalized();
  const Eigen::Vector3d along = (truth.long_axis - truth.long_axis.dot(normal) * normal).normalized();
  const Eigen::Vector3d across = normal.cross(along);
  std::array<double, 4> offsets_m{};
  for (int k = 0; k < 4; ++k)
  {
    const Eigen::Vector3d middle =
        0.5 * (candidate.corners_m[k] + candidate.corners_m[(k + 1) % 4]) - truth.centre_m;
    offsets_m[k] = k % 2 == 0 ? std::abs(middle.dot(across)) - 0.5 * truth.width_m
                              : std::abs(middle.dot(along)) - 0.5 * truth.length_m;
  }
  return offsets_m;
}

/// Why a candidate is not one of the earlier benchmark's true positives
/// (its names: "wrong type (X for Y)", "second candidate on a top").
std::string falsePositiveReason(const BrickCandidate& candidate, const eval::CandidateMatch& match,
                                const eval::SceneTruth& truth)
{
  if (match.face < 0) return eval::toString(match.outcome);
  const eval::FaceTruth& face = truth.faces[static_cast<std::size_t>(match.face)];
  if (match.outcome == eval::CandidateOutcome::kWrongType)
    return "wrong type (" + candidate.type_name + " for " + face.type + ")";
  // On a top of its type but not first on it (whatever its coverage).
  return face.role == eval::FaceRole::kTop ? "second candidate on a top" : eval::toString(match.outcome);
}

void recordLegacyErrors(const BrickCandidate& candidate, const eval::FaceTruth& face, const PinholeCamera& camera,
                        CellStats& stats)
{
  const eval::TopFaceGeometry& truth = face.geometry;
  stats.quad_dim_error_mm.push_back(1000.0 * std::abs(candidate.length_m - truth.length_m));
  stats.quad_dim_error_mm.push_back(1000.0 * std::abs(candidate.width_m - truth.width_m));
  stats.obb_dim_error_mm.push_back(1000.0 * std::abs(candidate.obb.extents_m.x() - truth.length_m));
  stats.obb_dim_error_mm.push_back(1000.0 * std::abs(candidate.obb.extents_m.y() - truth.width_m));
  std::array<Eigen::Vector2d, 4> corners_px;
  for (int k = 0; k < 4; ++k) corners_px[k] = camera.project(truth.corners_m[k]);
  for (const double error : eval::cornerErrorsPx(candidate.corners_px, corners_px))
    stats.corner_error_px.push_back(error);
}
}  // namespace

void CellStats::merge(const CellStats& other)
{
  tally.merge(other.tally);
  append(total_ms, other.total_ms);
  append(segmentation_ms, other.segmentation_ms);
  append(cloud_ms, other.cloud_ms);
  append(roi_ms, other.roi_ms);
  append(cpu_ms, other.cpu_ms);
  append(quad_dim_error_mm, other.quad_dim_error_mm);
  append(obb_dim_error_mm, other.obb_dim_error_mm);
  append(corner_error_px, other.corner_error_px);
  append(complete_centre_mm, other.complete_centre_mm);
  for (const auto& [kind, offsets] : other.complete_edge_offset_mm) append(complete_edge_offset_mm[kind], offsets);
  for (const auto& [reason, count] : other.miss_reasons) miss_reasons[reason] += count;
  for (const auto& [reason, count] : other.false_positive_reasons) false_positive_reasons[reason] += count;
}

void recordFrame(const FrontEndResult& result, double cpu_ms, const eval::SceneTruth& truth,
                 const PinholeCamera& camera, const eval::MatchParams& match_params, bool verbose,
                 const std::string& frame_name, CellStats& stats)
{
  stats.total_ms.push_back(result.timings.total_ms);
  stats.segmentation_ms.push_back(result.timings.segmentation_ms);
  stats.cloud_ms.push_back(result.timings.cloud.total());
  stats.roi_ms.push_back(result.timings.roi_ms);
  stats.cpu_ms.push_back(cpu_ms);
  if (verbose)
    std::fprintf(stderr, "%s: time ms total %.2f segmentation %.2f cloud %.2f roi %.2f cpu %.2f\n", frame_name.c_str(),
                 result.timings.total_ms, result.timings.segmentation_ms, result.timings.cloud.total(),
                 result.timings.roi_ms, cpu_ms);

  const eval::FrameMatch match = eval::matchCandidates(result.candidates, truth, camera, match_params);
  stats.tally.add(match, match_params.legacy_min_visible_fraction);
  for (std::size_t c = 0; c < match.candidates.size(); ++c)
  {
    const eval::CandidateMatch& candidate_match = match.candidates[c];
    const BrickCandidate& candidate = result.candidates[c];
    if (verbose && candidate_match.false_complete)
    {
      const eval::FaceTruth* face =
          candidate_match.face >= 0 ? &truth.faces[static_cast<std::size_t>(candidate_match.face)] : nullptr;
      std::fprintf(stderr, "%s: false complete %s %.3f x %.3f m, %d px, fill %.2f: %s (share %.2f, coverage %.2f%s%s)\n",
                   frame_name.c_str(), candidate.type_name.c_str(), candidate.length_m, candidate.width_m,
                   candidate.area_px, candidate.fill_ratio, eval::toString(candidate_match.outcome),
                   candidate_match.face_share, candidate_match.coverage, face ? ", truth: " : "",
                   face ? (face->not_whole_reason.empty() ? eval::toString(face->role) : face->not_whole_reason.c_str())
                        : "");
    }
    if (!candidate_match.legacy_true_positive)
    {
      const std::string reason = falsePositiveReason(candidate, candidate_match, truth);
      // What covers a top without being it (a tile over two bricks, half of
      // one): its miss has no rejection to name.
      if (verbose)
        std::fprintf(stderr, "%s: not a top found: %s %.3f x %.3f m%s: %s (share %.2f, coverage %.2f)%s%s\n",
                     frame_name.c_str(), candidate.type_name.c_str(), candidate.length_m, candidate.width_m,
                     candidate.complete ? ", complete" : "", reason.c_str(), candidate_match.face_share,
                     candidate_match.coverage, candidate.partial_reason.empty() ? "" : "; partial: ",
                     candidate.partial_reason.c_str());
      ++stats.false_positive_reasons[reason];
      continue;
    }
    const eval::FaceTruth& face = truth.faces[static_cast<std::size_t>(candidate_match.face)];
    // A whole top found but not pickable: why it stays in doubt.
    if (verbose && !candidate.complete && candidate_match.outcome == eval::CandidateOutcome::kWholeTop)
      std::fprintf(stderr, "%s: whole top found partial: %s: %s\n", frame_name.c_str(), candidate.type_name.c_str(),
                   candidate.partial_reason.c_str());
    if (candidate.complete && candidate_match.outcome == eval::CandidateOutcome::kWholeTop &&
        candidate_match.has_errors)
    {
      stats.complete_centre_mm.push_back(candidate_match.errors.centre_mm);
      const std::array<double, 4> offsets_m = edgeOffsetsM(candidate, face.geometry);
      for (int k = 0; k < 4; ++k)
        stats.complete_edge_offset_mm[toString(candidate.edge_kinds[k])].push_back(1000.0 * offsets_m[k]);
    }
    if (face.has_geometry && face.visible_fraction >= kMeasuredMinVisibleFraction)
      recordLegacyErrors(candidate, face, camera, stats);
  }
  for (const eval::TopMatch& top : match.tops)
  {
    if (top.visible_fraction >= match_params.legacy_min_visible_fraction && !top.legacy_found)
      ++stats.miss_reasons[missReason(result, truth, top, verbose, frame_name)];
    // A whole top a legacy true positive lies on without holding enough of
    // it (a tile over two bricks, half of one): what lies on it is named,
    // as no other line names a legacy true positive.
    else if (verbose && top.whole_in_view && !top.found)
    {
      std::fprintf(stderr, "%s: miss whole %s vis %.2f: %s\n", frame_name.c_str(),
                   truth.faces[static_cast<std::size_t>(top.face)].type.c_str(), top.visible_fraction,
                   kUnderACandidate);
      for (std::size_t c = 0; c < match.candidates.size(); ++c)
        if (match.candidates[c].face == top.face)
          std::fprintf(stderr, "  on it: %s %.3f x %.3f m: %s (share %.2f, coverage %.2f)%s%s\n",
                       result.candidates[c].type_name.c_str(), result.candidates[c].length_m,
                       result.candidates[c].width_m, eval::toString(match.candidates[c].outcome),
                       match.candidates[c].face_share, match.candidates[c].coverage,
                       result.candidates[c].partial_reason.empty() ? "" : "; partial: ",
                       result.candidates[c].partial_reason.c_str());
    }
  }
}
}  // namespace frontend_bench
}  // namespace brick_pose
