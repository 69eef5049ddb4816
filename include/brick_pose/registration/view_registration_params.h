#pragma once
// Parameters of Super4PCS's whole-view mode (whole_view_registration.h): a
// model of a whole object (a cuboid's surface, with normals) registered onto
// one view of it, a scan from a known viewpoint that shows one to three faces.

#include <Eigen/Core>

namespace brick_pose
{
namespace registration
{
enum class ViewMode
{
  kOff,  ///< register as a face: LCP acceptance only (the pipeline's top faces)
  kOn,  ///< whole-view registration with the view acceptance
  kAuto  ///< kOn when the source is not flat (a model of several faces), else kOff
};

struct ViewRegistrationParams
{
  ViewMode mode = ViewMode::kOff;
  /// Where the scan was seen from, in the target frame: the camera centre
  /// (the origin for a cloud in the camera's optical frame).
  Eigen::Vector3d viewpoint_m = Eigen::Vector3d::Zero();
  /// Points kept (evenly spread) from the scan for normals and the checks.
  int scan_sample_size = 1500;
  /// Most points kept from the model for the congruent sets (it is sampled
  /// as densely as the scan's bases, up to this).
  int model_sample_size = 1500;
  /// Work budget: candidate poses verified (bases are bounded by
  /// Super4PCSParams::max_bases). Unlike the wall-clock budget it gives the
  /// same result for the same seed however loaded the machine is.
  int max_candidates = 4000;
  /// Distinct pose hypotheses kept from the search for the final comparison.
  int kept_hypotheses = 4;
  /// The scan's normals are fitted over a radius of at least this times the
  /// scan's median range (and 2.5 sample spacings): stereo depth noise is
  /// correlated over the matching window, a few pixels, and grows with the
  /// range, so a smaller neighbourhood fits the noise's bumps, not the face.
  double normal_radius_per_range = 0.025;
  /// Normals (the scan's estimated ones) agree within this.
  double max_normal_difference_deg = 30.0;
  /// See ViewConsistencyParams.
  double min_visible_cos = 0.3;
  double free_space_margin_m = 0.02;
  /// Scan points are trusted (used by the search and the checks) when their
  /// surface variation is at most this multiple of the scan's median (flat
  /// patches at the scan's noise level; edges and scatter are above it) and
  /// their normal faces the viewpoint with at least min_sight_cos: a surface
  /// seen at a grazing angle returns little true depth on a stereo camera,
  /// and the curtains of flying pixels behind an object's silhouette run
  /// along the lines of sight.
  double max_relative_surface_variation = 3.0;
  double min_sight_cos = 0.15;
  /// Acceptance: all must hold for success.
  double min_target_coverage = 0.8;
  double min_model_coverage = 0.75;
  double max_free_space_violation = 0.1;
  /// Margin of the best pose's combined view score over the best pose that
  /// is not the same up to a true symmetry of the model (the confidence).
  double min_confidence = 0.08;
  /// A new best candidate of the search whose quick target coverage reaches
  /// this is fitted and checked in full; the search stops when it passes the
  /// acceptance (a pose that covers the scan but fails the view checks does
  /// not stop it). The 4-point pose is only as good as the pair tolerance,
  /// so its quick coverage is lower than the fitted pose's.
  double stop_target_coverage = 0.7;

  /// Throws ConfigError naming the first unusable field.
  void validate() const;
};
}  // namespace registration
}  // namespace brick_pose
