#include "brick_pose/registration/whole_view_registration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/number_text.h"
#include "brick_pose/common/statistics.h"
#include "brick_pose/registration/box_placement.h"
#include "brick_pose/registration/box_view_checks.h"
#include "brick_pose/registration/competitor_settling.h"
#include "brick_pose/registration/congruent_set_finder.h"
#include "brick_pose/registration/coplanar_base.h"
#include "brick_pose/registration/icp_polish.h"
#include "brick_pose/registration/model_symmetry.h"
#include "brick_pose/registration/normal_estimation.h"
#include "brick_pose/registration/point_to_plane_icp.h"
#include "brick_pose/registration/rigid_fit.h"
#include "brick_pose/registration/shell_pair_index.h"
#include "brick_pose/registration/strided_deadline.h"
#include "brick_pose/registration/uniform_sampling.h"
#include "brick_pose/registration/view_consistency.h"
#include "brick_pose/registration/visible_surface.h"

namespace brick_pose
{
namespace registration
{
namespace
{
constexpr int kMaxBaseDrawFailures = 8;
// Match radius over the scan sample's median spacing (as the LCP radius).
constexpr double kMatchRadiusPerSpacing = 1.3;
// A model point is seen within this many match radii of a scan point
// (ViewConsistencyParams::seen_radius_m). At one match radius (1.3 sample
// spacings) faces the camera saw whole, facing it at cos 0.97, came out only
// 0.74 seen (bench views 62 and 118 of seed 1), and the acceptance needs 0.75;
// at 1.5 (with the polish rule of kMaxScoreDropWithinHypothesis) seeds 1-4
// gave 100 / 99.5 / 99.0 / 99.0 % success and no false success, where 1.0
// gave 98.5 / 98.0 / 95.5 % on seeds 1-3 and one false success (a quarter
// turn of a box).
constexpr double kSeenRadiusPerMatchRadius = 1.5;
// Model points kept for the model-side checks and the symmetry probe.
constexpr int kModelProbeSize = 1000;
// Dense models are thinned to this many points for scoring.
constexpr int kMaxScoringModelPoints = 20000;
// Scan points of the cheap coverage test in the search.
constexpr int kSearchCoveragePoints = 200;
// A scan shows several faces when this fraction of its trusted normals is
// farther than kSpanAngleDeg from their mean; bases must then span faces.
constexpr double kSpanAngleDeg = 45.0;
constexpr double kMinSpanFraction = 0.1;
// Candidates below this scan coverage are not kept as hypotheses at all,
// nor those further than the window below the best one's (which cannot be a
// close second).
constexpr double kMinHypothesisCoverage = 0.3;
constexpr double kHypothesisCoverageWindow = 0.25;
// Two poses are one hypothesis when this close (modulo true symmetries). The
// offset is about the success tolerance (10 mm): a pose slid further along a
// face that ends out of view is a hypothesis of its own, and when it scores
// nearly as well the registration cannot claim that precision.
constexpr double kSameHypothesisDeg = 10.0;
constexpr double kSameHypothesisOffsetM = 0.012;
// Point-to-plane fit of each hypothesis: reach over the match radius.
constexpr double kHypothesisFitRadiusPerMatchRadius = 3.0;
constexpr int kHypothesisFitIterations = 8;
constexpr std::size_t kFitScanPoints = 300;
// The polished pose is kept unless its combined score drops by more, or by
// more than the second when it stayed within the hypothesis (polishKept).
constexpr double kMaxScoreDropByPolish = 0.03;
constexpr double kMaxScoreDropWithinHypothesis = 0.1;
// Competitors within the confidence margin polished to see where they settle,
// at most (each costs about one polish). A long face seen from an oblique
// angle gives slides of one pose along it as competitors, on both sides of
// the best (view 68 of the bench: -49, -20, 15 and 35 mm).
constexpr int kMaxSettledCompetitors = 4;
// A seen face moves the pose along its normal (snappedToSeenFaces) when this
// many scan points lie on it with normals within kSnapNormalDeg of its own,
// by at most kMaxSnapM (further is no polish residue but another pose).
constexpr double kSnapNormalDeg = 20.0;
constexpr int kMinSnapPoints = 20;
constexpr double kMaxSnapM = 0.03;
// Polishes of the same answer from different starts end this close together
// on a view that fixes the pose (bench: up to 3 mm; 9 mm and more on a long
// face whose end is out of view, once 12 mm off the truth).
constexpr double kSettledAgreementM = 0.006;
// Model faces turned towards the viewpoint by more than this take part in the
// polish: a grazing face has next to no scan points, and its boundary, unmatched
// in the scan, would only hide the fold edge the scan does show.
constexpr double kPolishVisibleCos = 0.2;
constexpr double kPolishReachPerPairTolerance = 2.5;
constexpr int kClockStride = 32;
// Scan points left out at each end of the scan's extent when an alternative
// orientation is placed on it (stray points that passed the normal checks).
constexpr int kExtentTrimPoints = 3;

// Scores and fractions in reasons read to three digits.
std::string formatScore(double value) { return numberText(value, 3); }

/// What the view search works on.
struct ViewInput
{
  PointSet model;  ///< unit normals; thinned for scoring
  PointSet model_sample;  ///< congruent sets come from these
  PointSet model_probe;  ///< model-side checks, symmetry probe
  PointSet scan;  ///< dense scan sample, normals towards the viewpoint
  std::vector<int> trusted;  ///< scan points whose normals are trusted
  std::vector<Eigen::Vector3d> trusted_points;  ///< their positions
  PointSet base_cloud;  ///< trusted scan points the bases are drawn from
  double match_radius_m = 0.0;
  double pair_tolerance_m = 0.0;
  double scan_diameter_m = 0.0;
  double model_diameter_m = 0.0;
  double model_spacing_m = 0.0;  ///< median nearest-neighbour spacing of `model`
  bool bases_span_faces = false;
};

PointSet withUnitNormals(PointSet cloud)
{
  for (Eigen::Vector3d& normal : cloud.normals)
    if (normal.squaredNorm() > 0.0)
      normal.normalize();
  return cloud;
}

PointSet prepareModel(const PointSet& source, std::mt19937_64& rng)
{
  PointSet model = source.subset(uniformSubsample(source.points, kMaxScoringModelPoints, rng));
  if (!model.hasNormals())
    model.normals = estimateOutwardNormals(
        model.points, kNormalRadiusPerSpacing * std::max(1e-6, neighbourSpacing(model.points, 0.5, rng)));
  return withUnitNormals(std::move(model));
}

/// Whether the trusted normals leave their mean by more than kSpanAngleDeg
/// often enough to say the scan shows more than one face.
bool showsSeveralFaces(const std::vector<Eigen::Vector3d>& normals)
{
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& n : normals)
    mean += n;
  if (!(mean.norm() > 0.0))
    return false;
  mean.normalize();
  const double max_cos = std::cos(kSpanAngleDeg * kDegToRad);
  int away = 0;
  for (const Eigen::Vector3d& n : normals)
    away += n.dot(mean) < max_cos ? 1 : 0;
  return away >= kMinSpanFraction * normals.size();
}

/// See ViewRegistrationParams::normal_radius_per_range.
double scanNormalRadius(const PointSet& scan, double spacing_m, const ViewRegistrationParams& view)
{
  std::vector<double> ranges;
  for (const Eigen::Vector3d& p : scan.points)
    ranges.push_back((p - view.viewpoint_m).norm());
  return std::max({1e-6, kNormalRadiusPerSpacing * spacing_m, view.normal_radius_per_range * percentile(ranges, 0.5)});
}

/// See ViewRegistrationParams::max_relative_surface_variation.
std::vector<int> trustedScanPoints(const PointSet& scan, const std::vector<double>& variation,
                                   const ViewRegistrationParams& view)
{
  std::vector<double> finite;
  for (std::size_t i = 0; i < scan.size(); ++i)
    if (scan.normals[i].squaredNorm() > 0.0)
      finite.push_back(variation[i]);
  const double max_variation = view.max_relative_surface_variation * percentile(finite, 0.5);
  std::vector<int> trusted;
  for (std::size_t i = 0; i < scan.size(); ++i)
  {
    if (scan.normals[i].squaredNorm() == 0.0 || variation[i] > max_variation)
      continue;
    const Eigen::Vector3d sight = (view.viewpoint_m - scan.points[i]).normalized();
    if (scan.normals[i].dot(sight) >= view.min_sight_cos)
      trusted.push_back(static_cast<int>(i));
  }
  return trusted;
}

ViewInput prepareInput(const PointSet& source, const PointSet& target, const Super4PCSParams& params,
                       std::mt19937_64& rng)
{
  const ViewRegistrationParams& view = params.view;
  ViewInput input;
  input.model = prepareModel(source, rng);
  input.model_probe = input.model.subset(uniformSubsample(input.model.points, kModelProbeSize, rng));

  input.scan = target.subset(uniformSubsample(target.points, view.scan_sample_size, rng));
  const double scan_spacing_m = neighbourSpacing(input.scan.points, 0.5, rng);
  const ViewNormals normals =
      estimateViewNormals(input.scan.points, scanNormalRadius(input.scan, scan_spacing_m, view), view.viewpoint_m);
  input.scan.normals = normals.normals;
  input.trusted = trustedScanPoints(input.scan, normals.surface_variation, view);
  const PointSet trusted_scan = input.scan.subset(input.trusted);
  input.trusted_points = trusted_scan.points;
  input.base_cloud = trusted_scan.subset(uniformSubsample(trusted_scan.points, params.sample_size, rng));
  input.bases_span_faces = showsSeveralFaces(input.base_cloud.normals);

  // The model sample as dense as the base cloud: a base point's counterpart
  // is then as close in the model sample as a face registration's would be.
  input.model_spacing_m = neighbourSpacing(input.model.points, 0.5, rng);
  const double model_spacing_m = input.model_spacing_m;
  const double base_spacing_m = neighbourSpacing(input.base_cloud.points, 0.5, rng);
  const double density_ratio = base_spacing_m > 0.0 ? model_spacing_m / base_spacing_m : 1.0;
  // Clamped as a double: a degenerate scan (all points within a few microns)
  // gives a ratio whose square does not fit an int.
  const double wanted_model_samples = static_cast<double>(input.model.size()) * density_ratio * density_ratio;
  const int model_sample_size = static_cast<int>(std::max(
      static_cast<double>(params.sample_size), std::min(wanted_model_samples, static_cast<double>(view.model_sample_size))));
  input.model_sample = input.model.subset(uniformSubsample(input.model.points, model_sample_size, rng));
  const double model_sample_spacing_m = neighbourSpacing(input.model_sample.points, 0.5, rng);
  input.match_radius_m = std::max({params.delta_m, kMatchRadiusPerSpacing * scan_spacing_m, model_spacing_m});
  // A scan point's counterpart among the model sample is up to about half
  // the model sample's spacing away.
  input.pair_tolerance_m = std::max(params.delta_m, 0.5 * model_sample_spacing_m);
  input.scan_diameter_m = approximateDiameter(input.base_cloud.points, rng);
  input.model_diameter_m = approximateDiameter(input.model_probe.points, rng);
  return input;
}

CongruenceTolerances tolerancesFor(const CoplanarBase& base, const ViewInput& input, const Super4PCSParams& params)
{
  CongruenceTolerances tolerances;
  tolerances.distance_m = input.pair_tolerance_m;
  tolerances.normal_rad = params.view.max_normal_difference_deg * kDegToRad;
  tolerances.angle_rad = params.max_angle_difference_deg > 0.0
                             ? params.max_angle_difference_deg * kDegToRad
                             : std::atan(2.0 * input.pair_tolerance_m / std::min(base.r1_m(), base.r2_m()));
  return tolerances;
}

/// The candidate (scan -> model) turns each base normal onto its model point's
/// (the model sample's normals are unit already).
bool normalsMapped(const Eigen::Isometry3d& scan_to_model, const CoplanarBase& base, const PointSet& model_sample,
                   const CongruentSet& set, double max_angle_rad)
{
  return baseNormalsMapped(
      scan_to_model, base, [&](int k) -> const Eigen::Vector3d& { return model_sample.normals[set[k]]; },
      max_angle_rad);
}

bool passesAcceptance(const ViewScore& score, const ViewRegistrationParams& view)
{
  return score.target_coverage >= view.min_target_coverage && score.model_coverage >= view.min_model_coverage &&
         score.free_space_violation <= view.max_free_space_violation;
}

/// The distinct hypotheses of the search, best target coverage first.
class HypothesisList
{
public:
  HypothesisList(int capacity, const ModelSymmetries& symmetries, double same_offset_m)
    : capacity_(std::max(1, capacity)), symmetries_(symmetries), same_offset_m_(same_offset_m)
  {
  }

  /// Coverage a new candidate must exceed to be kept.
  double floor() const
  {
    if (list_.empty())
      return kMinHypothesisCoverage;
    const double window = std::max(kMinHypothesisCoverage, list_.front().target_coverage - kHypothesisCoverageWindow);
    return static_cast<int>(list_.size()) < capacity_ ? window : std::max(window, list_.back().target_coverage);
  }

  /// Keeps the candidate (merged with a hypothesis it repeats); returns its
  /// index in the list, or -1 when it was not kept.
  int offer(const Eigen::Isometry3d& pose, double coverage)
  {
    for (std::size_t i = 0; i < list_.size(); ++i)
      if (samePoseModuloSymmetry(list_[i].pose, pose, symmetries_, kSameHypothesisDeg, same_offset_m_))
      {
        if (coverage <= list_[i].target_coverage)
          return -1;
        list_[i] = Hypothesis{pose, coverage, {}, false};
        return sortFrom(static_cast<int>(i));
      }
    if (coverage <= floor())
      return -1;
    if (static_cast<int>(list_.size()) >= capacity_)
      list_.pop_back();
    list_.push_back(Hypothesis{pose, coverage, {}, false});
    return sortFrom(static_cast<int>(list_.size()) - 1);
  }

  Hypothesis& at(int index) { return list_[index]; }
  std::vector<Hypothesis>& all() { return list_; }

private:
  int sortFrom(int index)
  {
    while (index > 0 && list_[index - 1].target_coverage < list_[index].target_coverage)
    {
      std::swap(list_[index - 1], list_[index]);
      --index;
    }
    return index;
  }

  int capacity_;
  const ModelSymmetries& symmetries_;
  double same_offset_m_;
  std::vector<Hypothesis> list_;
};

/// The pose slid along each box axis on which the scan is shorter than the
/// model, so that one end of the scan meets the model's end: a face whose end
/// is out of view (or grazing) leaves the position along it to the few
/// boundary points, and the 4-point pose may be off by more than the local
/// fits reach.
std::vector<Eigen::Isometry3d> slidAlternatives(const Eigen::Isometry3d& pose, const ViewInput& input,
                                                const ModelSymmetries& symmetries)
{
  std::vector<Eigen::Isometry3d> slid;
  if (!symmetries.box_like || input.trusted.empty())
    return slid;
  const Eigen::Isometry3d target_to_model = pose.inverse();
  Eigen::Vector3d lower = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d upper = -lower;
  for (int i : input.trusted)
  {
    const Eigen::Vector3d local =
        symmetries.axes.transpose() * (target_to_model * input.scan.points[i] - symmetries.centre_m);
    lower = lower.cwiseMin(local);
    upper = upper.cwiseMax(local);
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    const double half = symmetries.half_extents_m(axis);
    for (const double shift : {lower(axis) + half, upper(axis) - half})
    {
      if (std::abs(shift) <= input.match_radius_m)
        continue;
      Eigen::Isometry3d moved = pose;
      moved.translation() += pose.linear() * (shift * symmetries.axes.col(axis));
      slid.push_back(moved);
    }
  }
  return slid;
}

/// What the local fit of a hypothesis works on: the model sample (as dense
/// as the scan's bases; a plane needs no more) indexed for the fit's reach,
/// and about kFitScanPoints trusted scan points spread over the scan.
struct FitContext
{
  FitContext(const ViewInput& input, double radius_m)
    : model(input.model_sample), grid(input.model_sample.points, radius_m), radius_m(radius_m)
  {
    const std::size_t stride = std::max<std::size_t>(1, input.trusted.size() / kFitScanPoints);
    for (std::size_t k = 0; k < input.trusted.size(); k += stride)
      scan_points.push_back(input.trusted[k]);
  }

  const PointSet& model;
  PointGrid grid;
  double radius_m;
  std::vector<int> scan_points;
};

/// Gives a hypothesis its best local fit and its full view score.
Hypothesis fitAndScore(const Eigen::Isometry3d& pose, const FitContext& context, const ViewInput& input,
                       const ViewConsistency& consistency, const Super4PCSParams& params)
{
  PointToPlaneParams fit;
  fit.radius_m = context.radius_m;
  fit.max_normal_difference_deg = params.view.max_normal_difference_deg;
  fit.iterations = kHypothesisFitIterations;
  fit.min_step_m = 0.02 * params.delta_m;
  Hypothesis hypothesis;
  hypothesis.pose = refinePointToPlane(context.model, context.grid, input.scan, context.scan_points, pose, fit);
  hypothesis.view = consistency.evaluate(hypothesis.pose);
  hypothesis.view_evaluated = true;
  hypothesis.target_coverage = hypothesis.view.target_coverage;
  return hypothesis;
}

/// The pose turned into each other axis-aligned orientation of the model's
/// box (one per class modulo its true symmetries) and placed on the scan as
/// the camera sees a box (box_placement.h).
std::vector<Eigen::Isometry3d> placedAlternatives(const Eigen::Isometry3d& pose, const ViewInput& input,
                                                  const ModelSymmetries& symmetries, const Eigen::Vector3d& viewpoint_m)
{
  std::vector<Eigen::Isometry3d> placed;
  for (const Eigen::Isometry3d& alternative : symmetries.alternatives)
    placed.push_back(anchoredToScanExtent(pose * alternative, symmetries, input.trusted_points, viewpoint_m,
                                          kExtentTrimPoints));
  return placed;
}

/// The first of the placed alternatives of `leader` that passes the view
/// acceptance once fitted, if any.
std::optional<Hypothesis> acceptedAlternative(const Hypothesis& leader, const ViewInput& input,
                                              const ViewConsistency& consistency, const ModelSymmetries& symmetries,
                                              const FitContext& fit_context, const Super4PCSParams& params)
{
  for (const Eigen::Isometry3d& alternative : placedAlternatives(leader.pose, input, symmetries, params.view.viewpoint_m))
  {
    const Hypothesis fitted = fitAndScore(alternative, fit_context, input, consistency, params);
    if (passesAcceptance(fitted.view, params.view))
      return fitted;
  }
  return std::nullopt;
}

/// Draws bases from the scan and verifies their congruent sets in the model
/// until a pose passes the view acceptance with a high scan coverage, or the
/// work or time budget is spent.
std::string searchHypotheses(const ViewInput& input, const ViewConsistency& consistency, const FitContext& fit_context,
                             const ModelSymmetries& symmetries, const Super4PCSParams& params,
                             SteadyClock::time_point start, std::mt19937_64& rng, HypothesisList& hypotheses,
                             RegistrationResult& result)
{
  const ShellPairIndex pair_index(input.model_sample.points, input.pair_tolerance_m);
  const CongruentSetFinder finder(input.model_sample, pair_index);
  BaseSelectionLimits limits;
  limits.max_diameter_m = input.scan_diameter_m;
  limits.coplanar_tolerance_m = 0.5 * input.pair_tolerance_m;
  limits.min_normal_spread_rad = input.bases_span_faces ? kSpanAngleDeg * kDegToRad : 0.0;
  const double max_fit_rms_m = params.max_fit_rms_factor * input.pair_tolerance_m;
  const ViewRegistrationParams& view = params.view;

  std::string stop_reason;
  bool alternatives_tried = false;
  int base_draw_failures = 0;
  std::vector<Eigen::Vector3d> base_points(4);
  std::vector<Eigen::Vector3d> set_points(4);
  while (stop_reason.empty())
  {
    if (result.bases_tried >= params.max_bases)
      return "all " + std::to_string(params.max_bases) + " bases tried";
    if (secondsSince(start) >= params.max_time_s)
      return "time budget exhausted (wall clock: the result depends on the machine's load)";
    const std::optional<CoplanarBase> base = drawCoplanarBase(input.base_cloud, limits, rng);
    if (!base)
    {
      if (++base_draw_failures >= kMaxBaseDrawFailures)
      {
        if (limits.min_normal_spread_rad > 0.0)
        {
          limits.min_normal_spread_rad = 0.0;  // no spanning base: take any
          base_draw_failures = 0;
          continue;
        }
        return "no wide coplanar 4-point base found in the scan";
      }
      continue;
    }
    base_draw_failures = 0;
    ++result.bases_tried;
    const CongruenceTolerances tolerances = tolerancesFor(*base, input, params);
    for (int k = 0; k < 4; ++k)
      base_points[k] = base->points[k];

    StridedDeadline deadline(start, params.max_time_s, kClockStride);
    finder.find(*base, tolerances, [&](const CongruentSet& set) {
      if (deadline.passed())
      {
        stop_reason = "time budget exhausted (wall clock: the result depends on the machine's load)";
        return false;
      }
      for (int k = 0; k < 4; ++k)
        set_points[k] = input.model_sample.points[set[k]];
      const RigidFit fit = fitRigid(base_points, set_points);
      if (!fit.valid || fit.rms_m > max_fit_rms_m ||
          !normalsMapped(fit.transform, *base, input.model_sample, set, tolerances.normal_rad))
        return true;
      if (result.candidates_verified >= view.max_candidates)
      {
        stop_reason = "work budget of " + std::to_string(view.max_candidates) + " candidates spent";
        return false;
      }
      ++result.candidates_verified;
      const Eigen::Isometry3d pose = fit.transform.inverse();
      const double floor = hypotheses.floor();
      const double coverage = consistency.targetCoverage(pose, floor, kSearchCoveragePoints);
      if (coverage <= floor)
        return true;
      // Only a new leader is checked in full: the check costs as much as
      // hundreds of quick ones.
      const int kept = hypotheses.offer(pose, coverage);
      if (kept != 0 || coverage < view.stop_target_coverage)
        return true;
      Hypothesis& hypothesis = hypotheses.at(kept);
      const double quick_coverage = hypothesis.target_coverage;
      hypothesis = fitAndScore(pose, fit_context, input, consistency, params);
      hypothesis.target_coverage = std::max(quick_coverage, hypothesis.target_coverage);
      if (passesAcceptance(hypothesis.view, view))
      {
        stop_reason = "a pose passed the view checks";
        return false;
      }
      // A leader that covers the scan but fails the view checks is most
      // often the right surface in the wrong orientation (a brick's end face
      // matched as part of a side, which the search can match anywhere along
      // the side, using up its budget): its other orientations, placed on
      // the scan, are tried once, as the final comparison would.
      if (alternatives_tried || !symmetries.box_like)
        return true;
      alternatives_tried = true;
      const std::optional<Hypothesis> accepted =
          acceptedAlternative(hypothesis, input, consistency, symmetries, fit_context, params);
      if (!accepted)
        return true;
      const int index = hypotheses.offer(accepted->pose, accepted->target_coverage);
      if (index >= 0)
        hypotheses.at(index) = *accepted;
      stop_reason = "another orientation of the box passed the view checks";
      return false;
    });
  }
  return stop_reason;
}

/// The polish of the face mode with the model's surface turned towards the
/// viewpoint (visible_surface.h) as the source.
Eigen::Isometry3d polishOnVisibleFaces(const ViewInput& input, const Eigen::Isometry3d& pose,
                                       const ModelSymmetries& symmetries, const Super4PCSParams& params,
                                       SteadyClock::time_point start, std::mt19937_64& rng)
{
  // Half a model spacing takes in a face's edge points and none of the
  // neighbouring face's inner ones.
  const PointSet visible = visibleModelSurface(input.model, pose, symmetries, params.view.viewpoint_m,
                                               0.5 * input.model_spacing_m, kPolishVisibleCos);
  if (visible.size() < 4)
    return pose;
  // The scan without what faces away from the viewpoint (grazing strips and
  // flying-pixel curtains, which the polish's trimming does not always keep
  // out); edges stay, the boundary stage needs them.
  std::vector<int> kept;
  for (std::size_t i = 0; i < input.scan.size(); ++i)
  {
    const Eigen::Vector3d sight = (params.view.viewpoint_m - input.scan.points[i]).normalized();
    if (input.scan.normals[i].dot(sight) >= params.view.min_sight_cos)
      kept.push_back(static_cast<int>(i));
  }
  if (kept.size() < 4)
    return pose;
  PointSet polish_target = input.scan.subset(kept);
  polish_target.normals.clear();
  SearchScales scales;
  // The hypothesis fit leaves the in-plane pose of a single face as loose as
  // the 4-point pose (a few pair tolerances at its far ends): the polish must
  // reach that far.
  scales.pair_tolerance_m = kPolishReachPerPairTolerance * input.pair_tolerance_m;
  scales.lcp_radius_m = input.match_radius_m;
  scales.source_diameter_m = approximateDiameter(visible.points, rng);
  return polishWithIcp(visible, polish_target, pose, scales, params, start, rng);
}


/// The pose moved along each box axis so that the scan points lying on the
/// box face across that axis (their normal along it, their position inside
/// the face) sit on that face, at the median of their offsets. The polish
/// weighs a narrow end face by its few points against the thousands of a
/// long face, and a long face's points say nothing about the slide along
/// it: the end face, whenever it is seen, fixes that slide by itself.
Eigen::Isometry3d snappedToSeenFaces(const Eigen::Isometry3d& pose, const ViewInput& input,
                                     const ModelSymmetries& symmetries)
{
  if (!symmetries.box_like || !input.scan.hasNormals())
    return pose;
  const Eigen::Isometry3d target_to_model = pose.inverse();
  const Eigen::Matrix3d to_box = symmetries.axes.transpose();
  const double min_cos = std::cos(kSnapNormalDeg * kDegToRad);
  std::vector<double> offsets[3];
  for (int i : input.trusted)
  {
    const Eigen::Vector3d local = to_box * (target_to_model * input.scan.points[i] - symmetries.centre_m);
    const Eigen::Vector3d normal = to_box * (target_to_model.linear() * input.scan.normals[i]);
    for (int axis = 0; axis < 3; ++axis)
    {
      if (std::abs(normal(axis)) < min_cos)
        continue;
      bool inside = true;
      for (int other = 0; other < 3; ++other)
        inside = inside && (other == axis || std::abs(local(other)) <= symmetries.half_extents_m(other));
      if (!inside)
        continue;
      const double face = normal(axis) > 0.0 ? symmetries.half_extents_m(axis) : -symmetries.half_extents_m(axis);
      offsets[axis].push_back(local(axis) - face);
    }
  }
  Eigen::Vector3d shift_box = Eigen::Vector3d::Zero();
  for (int axis = 0; axis < 3; ++axis)
  {
    if (static_cast<int>(offsets[axis].size()) < kMinSnapPoints)
      continue;
    const double offset_m = percentile(offsets[axis], 0.5);
    if (std::abs(offset_m) <= kMaxSnapM)
      shift_box(axis) = offset_m;
  }
  Eigen::Isometry3d moved = pose;
  moved.translation() += pose.linear() * (symmetries.axes * shift_box);
  return moved;
}

/// The polished pose and its score, or the pose as it was when the polish
/// left the hypothesis and lost more than kMaxScoreDropByPolish of its score
/// (polishKept).
Hypothesis polished(const Hypothesis& hypothesis, const ViewInput& input, const ViewConsistency& consistency,
                    const ModelSymmetries& symmetries, const Super4PCSParams& params, SteadyClock::time_point start, std::mt19937_64& rng)
{
  if (params.refine_iterations <= 0)
    return hypothesis;
  Hypothesis result = hypothesis;
  result.pose = snappedToSeenFaces(polishOnVisibleFaces(input, hypothesis.pose, symmetries, params, start, rng), input, symmetries);
  result.view = consistency.evaluate(result.pose);
  result.view_evaluated = true;
  auto same = [&](const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return samePoseModuloSymmetry(a, b, symmetries, kSameHypothesisDeg, kSameHypothesisOffsetM);
  };
  if (!polishKept(hypothesis, result, same, kMaxScoreDropByPolish, kMaxScoreDropWithinHypothesis))
    return hypothesis;
  return result;
}

/// The best hypothesis polished against its competitors (competitor_settling.h).
Comparison compareHypotheses(const std::vector<Hypothesis>& scored, const ViewInput& input,
                             const ViewConsistency& consistency, const ModelSymmetries& symmetries,
                             const Super4PCSParams& params, SteadyClock::time_point start, std::mt19937_64& rng)
{
  CompetitorSettling settling;
  if (params.refine_iterations > 0)
    settling.polish = [&](const Hypothesis& hypothesis) {
      return polished(hypothesis, input, consistency, symmetries, params, start, rng);
    };
  settling.same = [&](const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return samePoseModuloSymmetry(a, b, symmetries, kSameHypothesisDeg, kSameHypothesisOffsetM);
  };
  settling.agree = [&](const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
    return samePoseModuloSymmetry(a, b, symmetries, kSameHypothesisDeg, kSettledAgreementM);
  };
  settling.min_confidence = params.view.min_confidence;
  settling.max_polishes = kMaxSettledCompetitors;
  return settleCompetitors(scored, settling);
}
}  // namespace

bool isMultiFaceModel(const PointSet& source)
{
  if (source.size() < 4)
    return false;
  if (source.hasNormals())
  {
    const Eigen::Vector3d first = source.normals.front().normalized();
    const double max_cos = std::cos(kSpanAngleDeg * kDegToRad);
    for (const Eigen::Vector3d& normal : source.normals)
      if (normal.normalized().dot(first) < max_cos)
        return true;
    return false;
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : source.points)
    mean += p;
  mean /= static_cast<double>(source.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : source.points)
    covariance += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance / static_cast<double>(source.size()));
  // Thicker than 5 % of its length: not one flat face.
  return std::sqrt(std::max(0.0, solver.eigenvalues()(0))) > 0.05 * std::sqrt(solver.eigenvalues()(2));
}

RegistrationResult alignWholeView(const PointSet& source, const PointSet& target, const Super4PCSParams& params)
{
  const SteadyClock::time_point start = SteadyClock::now();
  std::mt19937_64 rng(params.seed);
  const ViewRegistrationParams& view = params.view;
  const ViewInput input = prepareInput(source, target, params, rng);
  RegistrationResult result;
  result.view_checked = true;
  if (input.base_cloud.size() < 4)
  {
    result.reason = "fewer than 4 scan points with trustworthy normals";
    result.elapsed_s = secondsSince(start);
    return result;
  }

  ViewConsistencyParams check;
  check.viewpoint_m = view.viewpoint_m;
  check.match_radius_m = input.match_radius_m;
  check.seen_radius_m = kSeenRadiusPerMatchRadius * input.match_radius_m;
  check.max_normal_difference_deg = view.max_normal_difference_deg;
  check.min_visible_cos = view.min_visible_cos;
  check.free_space_margin_m = view.free_space_margin_m;
  const ViewConsistency consistency(input.model, input.model_probe, input.scan, input.trusted, check);
  const ModelSymmetries symmetries =
      findModelSymmetries(input.model, consistency.modelGrid(), input.model_probe, input.match_radius_m);

  const double search_cpu_start_s = threadCpuSeconds();
  HypothesisList hypotheses(view.kept_hypotheses, symmetries, kSameHypothesisOffsetM);
  const FitContext fit_context(input, kHypothesisFitRadiusPerMatchRadius * input.match_radius_m);
  result.reason = searchHypotheses(input, consistency, fit_context, symmetries, params, start, rng, hypotheses, result);
  result.search_cpu_s = threadCpuSeconds() - search_cpu_start_s;
  if (hypotheses.all().empty())
  {
    result.reason += "; no pose covers " + formatScore(kMinHypothesisCoverage) + " of the scan";
    result.elapsed_s = secondsSince(start);
    return result;
  }

  const double refine_cpu_start_s = threadCpuSeconds();
  // Every hypothesis of the search, and every near-symmetric alternative of
  // the best (centred as the best, and placed on the scan as the camera sees
  // a box: box_placement.h), fitted and scored alike.
  std::vector<Hypothesis> scored;
  for (const Hypothesis& hypothesis : hypotheses.all())
    scored.push_back(fitAndScore(hypothesis.pose, fit_context, input, consistency, params));
  auto by_score = [](const Hypothesis& a, const Hypothesis& b) { return a.view.combined() > b.view.combined(); };
  std::stable_sort(scored.begin(), scored.end(), by_score);
  const Eigen::Isometry3d leader = scored.front().pose;
  std::vector<Eigen::Isometry3d> alternatives = slidAlternatives(leader, input, symmetries);
  for (const Eigen::Isometry3d& alternative : symmetries.alternatives)
    alternatives.push_back(leader * alternative);
  for (const Eigen::Isometry3d& placed : placedAlternatives(leader, input, symmetries, view.viewpoint_m))
    alternatives.push_back(placed);
  for (const Eigen::Isometry3d& alternative : alternatives)
    scored.push_back(fitAndScore(alternative, fit_context, input, consistency, params));
  // The alternatives' own slides: a near-symmetric pose of a box whose
  // dimensions differ sits best against one end of the scan.
  std::stable_sort(scored.begin(), scored.end(), by_score);
  for (const Eigen::Isometry3d& alternative : slidAlternatives(scored.front().pose, input, symmetries))
    scored.push_back(fitAndScore(alternative, fit_context, input, consistency, params));
  std::stable_sort(scored.begin(), scored.end(), by_score);
  const Comparison comparison = compareHypotheses(scored, input, consistency, symmetries, params, start, rng);
  const Hypothesis& best = comparison.best;
  const double second_best = comparison.second_best;
  result.refine_cpu_s = threadCpuSeconds() - refine_cpu_start_s;

  result.source_to_target = best.pose;
  result.view = best.view;
  result.lcp_score = best.view.target_coverage;
  result.second_best_score = second_best;
  result.confidence = std::max(0.0, best.view.combined() - second_best);
  result.true_symmetries = static_cast<int>(symmetries.symmetries.size());

  std::vector<std::string> doubts;
  if (best.view.target_coverage < view.min_target_coverage)
    doubts.push_back("the pose explains only " + formatScore(best.view.target_coverage) + " of the scan (needs " +
                     formatScore(view.min_target_coverage) + ")");
  if (best.view.model_coverage < view.min_model_coverage)
    doubts.push_back("the scan shows only " + formatScore(best.view.model_coverage) +
                     " of the model faces the pose turns towards the camera (needs " +
                     formatScore(view.min_model_coverage) + ")");
  if (best.view.free_space_violation > view.max_free_space_violation)
    doubts.push_back("the pose puts " + formatScore(best.view.free_space_violation) +
                     " of its visible surface in front of what the camera saw (allowed " +
                     formatScore(view.max_free_space_violation) + ")");
  if (symmetries.box_like)
  {
    ModelBox box;
    box.centre_m = symmetries.centre_m;
    box.axes = symmetries.axes;
    box.half_extents_m = symmetries.half_extents_m;
    BoxViewCheckParams box_check;
    box_check.viewpoint_m = view.viewpoint_m;
    const BoxViewCheck measured = checkBoxView(best.pose, box, input.scan, input.trusted, box_check);
    doubts.insert(doubts.end(), measured.doubts.begin(), measured.doubts.end());
  }
  if (comparison.loosely_settled)
    doubts.push_back("polishes from nearby starts end more than " + formatScore(1e3 * kSettledAgreementM) +
                     " mm apart (the view leaves the position loose)");
  if (result.confidence < view.min_confidence)
    doubts.push_back("another pose scores nearly as well (margin " + formatScore(result.confidence) + ", needs " +
                     formatScore(view.min_confidence) + ")");
  result.success = doubts.empty();
  for (const std::string& doubt : doubts)
    result.reason += "; not sure: " + doubt;
  result.elapsed_s = secondsSince(start);
  return result;
}
}  // namespace registration
}  // namespace brick_pose
