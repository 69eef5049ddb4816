#pragma once
// Command line of bench_registration.

#include <cstdint>

namespace bench_registration
{
struct Options
{
  int frames = 200;  ///< face cases
  int views = 200;  ///< whole-cuboid view cases (0 = none)
  int first_view = 0;  ///< index of the first view case (to rerun one case)
  std::uint64_t seed = 1;
  int pcl_time_s = 1;
  /// Faces cut by the image border or occluded are ambiguous along the cut
  /// for any registration that sees only the segment; by default only faces
  /// seen whole take part.
  double min_visible_fraction = 0.95;
  bool verbose = false;  ///< one line per case and method on stderr
  bool only_ours = false;  ///< skip the PCL baselines (quick tuning runs)
  bool only_views = false;  ///< skip the face cases
  /// Super4PCS without its local refinement, as the pipeline runs it before
  /// the pose correction (shows what the search alone delivers).
  bool no_refine = false;
  /// PCL FPCS and KFPCS at several settings (bases, overlap) on the first
  /// sweep_frames faces, to find where they come closest to our success
  /// (0 disables); each PCL call may take up to sweep_time_s.
  int sweep_frames = 50;
  int sweep_time_s = 10;
};

/// Throws brick_pose::ConfigError for a bad argument; exits after --help.
Options parseOptions(int argc, char** argv);
}  // namespace bench_registration
