// Registration benchmark: our Super4PCS against PCL 1.13's FPCS, KFPCS and
// ICP-from-identity, on segmented brick top faces from the synthetic D415
// (face cases, bench_registration/face_*.cpp), and in whole-view mode against
// FPCS and KFPCS on views of whole cuboids showing one to three faces (view
// cases, bench_registration/view_*.cpp).
//
//   bench_registration [--frames N] [--views N] [--seed S] [--pcl-time S]
//                      [--min-visible F] [--verbose] [--only-ours] [--only-views]
//                      [--no-refine] [--sweep-frames N] [--sweep-time S]
//
// Each frame is a seeded single-brick scene (any catalogue type, camera
// 0.5-2 m away) rendered by sim::SyntheticRig with its D415 noise model. The
// segment is the top-face pixels of the brick in the rig's instance and face
// label images, back-projected from the *noisy* depth (holes skipped, flying
// pixels at the edges kept), then evenly downsampled to at most 2000 points.
// Faces less than 95 % visible (--min-visible) or with fewer than 1000 points
// are skipped (and counted): a face cut by the image border or occluded is
// ambiguous along the cut for any method that sees only the segment. Every method registers the brick's top-face model (1 cm
// grid, normals +z) onto the same segment; the segment has no normals.
//
// Success: rotation error < 5 deg and translation error < 10 mm, with the
// estimate first canonicalised (brick z towards the camera, which a face
// without normals cannot tell) and the error taken modulo the half turn about
// the face normal. Prints a markdown table and, on its own line, one JSON
// object.
//
// The PCL baselines first run at the shared settings (overlap 0.95,
// PCL's own base count, about 12). That is not a fair setting for them, so on
// the first --sweep-frames faces they also run with more bases and at a lower
// overlap; the table notes and the JSON (*_matched_*) report the fastest
// setting that reaches our success on those faces, or else the closest one.
// Super4PCS's CPU time is also split into setup, search and refinement.

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <unistd.h>

#include "bench_registration/face_bench.h"
#include "bench_registration/options.h"
#include "bench_registration/view_bench.h"

int main(int argc, char** argv)
{
  using namespace bench_registration;
  Options options;
  try
  {
    options = parseOptions(argc, argv);
  }
  catch (const std::exception& e)
  {
    std::cerr << "bench_registration: " << e.what() << "\n";
    return 2;
  }
  std::string json;
  try
  {
    if (!options.only_views)
      json = runFaceBench(options);
    if (options.views > 0)
      json += (json.empty() ? "" : ", ") + runViewBench(options);
  }
  catch (const std::exception& e)
  {
    std::cerr << "bench_registration: " << e.what() << "\n";
    return 1;
  }
  // Wall times (and Super4PCS's wall-clock budget) depend on what else runs.
  double load[3] = {0.0, 0.0, 0.0};
  if (getloadavg(load, 3) == 3)
    std::printf("\nLoad average at the end: %.2f %.2f %.2f on %ld cores; CPU times are per thread.\n", load[0],
                load[1], load[2], sysconf(_SC_NPROCESSORS_ONLN));
  std::printf("\n{%s}\n", json.c_str());
  return 0;
}
