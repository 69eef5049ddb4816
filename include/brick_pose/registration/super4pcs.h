#pragma once
// Super 4PCS global registration (Mellado, Aiger, Mitra, "Super 4PCS: Fast
// Global Pointcloud Registration via Smart Indexing", SGP 2014).
//
// Repeatedly draws a wide coplanar 4-point base from the source, finds every
// congruent 4-point set of the target through the smart pair index, fits a
// rigid transform to each and keeps the one with the largest common pointset
// (LCP). Stops when the LCP is good enough, when max_bases bases were tried or
// when the time budget is spent. The best candidate is finally polished in
// two stages: a coarse symmetric hybrid ICP on small samples
// (symmetric_icp.h), then a boundary ICP (boundary_icp.h) that takes the
// position and rotation within the surface from the boundaries of both
// clouds. The LCP is flat near the optimum on flat faces, so the raw 4-point
// pose is only accurate to about the pair tolerance, and along a long face to
// far less. The time budget covers the polish too.

#include <cstdint>

#include "brick_pose/registration/point_set.h"
#include "brick_pose/registration/registration_result.h"
#include "brick_pose/registration/view_registration_params.h"

namespace brick_pose
{
namespace registration
{
/// Defaults suit a brick-face model (source) against a segmented brick face
/// from a D415 at 0.5-2 m (target): 1-3k points, 1-3 mm depth noise.
struct Super4PCSParams
{
  /// Expected fraction (0..1] of the source seen in the target. Bounds the
  /// base diameter (overlap * source diameter) and scales the stop score.
  double overlap = 0.95;
  /// Accuracy in metres: pair length / crossing point tolerance and LCP
  /// radius. Both are raised to half the sample spacing when the samples are
  /// sparser than that, since a base point's counterpart can be that far off.
  double delta_m = 0.004;
  /// Points kept (evenly spread) from each cloud for bases and pairs.
  int sample_size = 200;
  /// Source points on which the LCP is evaluated.
  int lcp_sample_size = 200;
  /// Normal pair filter tolerance (used only when both clouds have normals).
  double max_normal_difference_deg = 20.0;
  /// Tolerance on the angle between the two diagonals; 0 = derived from
  /// delta and the diagonal lengths.
  double max_angle_difference_deg = 0.0;
  /// Hard budget for the whole call (search and ICP polish), in seconds of
  /// wall-clock time: on a loaded machine the polish may be cut short.
  double max_time_s = 0.1;
  /// Upper bound on the bases drawn.
  int max_bases = 200;
  /// Stop once LCP >= good_enough_ratio * overlap.
  double good_enough_ratio = 0.85;
  /// The result counts as a success when LCP >= min_success_ratio * overlap.
  double min_success_ratio = 0.5;
  /// A 4-point fit with an RMS above max_fit_rms_factor * delta is rejected.
  double max_fit_rms_factor = 1.5;
  /// Iterations of the coarse refinement stage, symmetric hybrid ICP on the
  /// best candidate (0 disables the refinement, both stages).
  int refine_iterations = 8;
  /// Points kept (evenly spread) from the target and from the source for the
  /// coarse stage. The source sample also gives the boundary stage its
  /// point-to-plane pairs. Small: the coarse stage only has to bring the
  /// pose within reach of the boundary stage.
  int refine_sample_size = 200;
  int refine_source_sample_size = 200;
  /// Iterations of the boundary stage (0 disables it), and the points kept
  /// from the target and from the source to find their boundaries: dense,
  /// because the in-surface position of a face is only as well known as its
  /// boundary is sampled (a clean source, a model, keeps its exact edges).
  int fine_refine_iterations = 10;
  int fine_refine_sample_size = 2000;
  int fine_refine_source_sample_size = 4000;
  /// Same seed and inputs => same result (unless the time budget cuts in).
  std::uint64_t seed = 1;
  /// Whole-object views (whole_view_registration.h); off by default: the
  /// face registration of the pipeline.
  ViewRegistrationParams view;

  /// Throws ConfigError naming the first unusable field.
  void validate() const;
};

class Super4PCS
{
public:
  explicit Super4PCS(const Super4PCSParams& params = Super4PCSParams());

  const Super4PCSParams& params() const { return params_; }

  /// Registers source onto target. Throws InputError for clouds that cannot
  /// be registered (see validateRegistrationInput); an unsuccessful search is
  /// reported in the result (success = false, reason), not thrown.
  RegistrationResult align(const PointSet& source, const PointSet& target) const;

private:
  Super4PCSParams params_;
};

/// Convenience overloads converting PCL clouds.
RegistrationResult alignSuper4PCS(const pcl::PointCloud<pcl::PointXYZ>& source,
                                  const pcl::PointCloud<pcl::PointXYZ>& target, const Super4PCSParams& params);
RegistrationResult alignSuper4PCS(const pcl::PointCloud<pcl::PointNormal>& source,
                                  const pcl::PointCloud<pcl::PointNormal>& target, const Super4PCSParams& params);
}  // namespace registration
}  // namespace brick_pose
