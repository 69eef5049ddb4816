#include "brick_pose/roi/side_faces.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "brick_pose/common/errors.h"
#include "brick_pose/common/rounding.h"

namespace brick_pose
{
namespace
{
enum class RunEnd
{
  kFoot,    // the surface the side stands on: the side ends there
  kHidden,  // a nearer surface, no depth or the image border: the side may go on
  kNone,    // no side surface below the edge at all
};

struct Run
{
  double height_m = 0.0;
  RunEnd end = RunEnd::kNone;
  bool on_support = false;  // the foot is the supporting plane
};

double median(std::vector<double> values)
{
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

/// Marches down the side plane from `top_m` (a point of the edge).
Run marchDown(const RgbdFrame& frame, const Eigen::Vector3d& top_m, const Eigen::Vector3d& down,
              const Eigen::Vector3d& outward, double max_height_m, const UpDirection& support,
              const SideFaceParams& params)
{
  // The side is followed where it is, not where the quad says: the mask's
  // edge may lie a few millimetres off the true edge (depth bleeding over
  // it), and a box may lean a little. The side's offset along `outward`
  // is tracked from the points found on it.
  double offset_m = 0.0;
  Run run;
  const double step_m = std::max(0.002, top_m.z() / frame.camera.fy_px);
  // The first few millimetres below the edge are mixed pixels.
  const double start_m = std::max(0.006, 3.0 * step_m);
  // Three surfaces off the side in a row end it; a stretch of missing depth
  // (a hole, a shadow) longer than a centimetre or two hides the rest.
  constexpr int kMaxMisses = 3;
  const int max_holes = std::max(5, static_cast<int>(std::ceil(0.02 / step_m)));
  int misses = 0, holes = 0;
  bool seen = false;
  for (double h = start_m; h <= max_height_m; h += step_m)
  {
    const Eigen::Vector3d on_side = top_m + h * down + offset_m * outward;
    if (on_side.z() <= 0.05) break;
    const Eigen::Vector2d p = frame.camera.project(on_side);
    const int u = roundToInt(p.x()), v = roundToInt(p.y());
    if (u < 0 || v < 0 || u >= frame.width_px() || v >= frame.height_px())
    {
      run.end = seen ? RunEnd::kHidden : RunEnd::kNone;
      return run;
    }
    const float z = frame.depthAt(u, v);
    if (std::isnan(z))
    {
      if (seen && ++holes > max_holes)
      {
        run.end = RunEnd::kHidden;
        return run;
      }
      continue;
    }
    holes = 0;
    // On the side: the pixel's surface is where the side plane is along its
    // ray. (Only near the plane is not enough: seen obliquely, the floor in
    // front of a side stays near its plane for centimetres past its foot.)
    // Locking on (the first hit) may take twice the tolerance.
    if (std::abs(z - on_side.z()) <= (seen ? 1.0 : 2.0) * params.plane_tolerance_m)
    {
      const Eigen::Vector3d point = frame.camera.backProject(u, v, z);
      offset_m += (seen ? 0.2 : 1.0) * (outward.dot(point - top_m) - offset_m);
      run.height_m = h;
      seen = true;
      misses = 0;
      continue;
    }
    // Before the side is found, only give up once well below the edge.
    if (!seen)
    {
      if (h > start_m + 3.0 * params.min_visible_m) return run;
      continue;
    }
    if (++misses < kMaxMisses) continue;
    // A nearer surface at the height where the side ended is what it stands
    // on; anything else (an occluder, a farther surface) leaves its foot unseen.
    const Eigen::Vector3d point = frame.camera.backProject(u, v, z);
    const double below_top_m = down.dot(point - top_m);
    const double level_tolerance_m = std::max(params.plane_tolerance_m, 4.0 * step_m);
    run.end = z < on_side.z() && std::abs(below_top_m - run.height_m) <= level_tolerance_m ? RunEnd::kFoot
                                                                                            : RunEnd::kHidden;
    run.on_support = run.end == RunEnd::kFoot && support.has_support_plane &&
                     std::abs(support.heightAboveSupport(point)) <= level_tolerance_m;
    return run;
  }
  // Still on the side at the end of the march: taller than searched.
  run.end = seen ? RunEnd::kFoot : RunEnd::kNone;
  return run;
}
}  // namespace

void SideFaceParams::validate() const
{
  const ParamCheck check("side faces");
  check.require(plane_tolerance_m > 0.0, "plane_tolerance_m", "must be > 0");
  check.require(search_factor > 1.0, "search_factor", "must be > 1");
  check.require(min_visible_m > 0.0, "min_visible_m", "must be > 0");
  check.require(height_tolerance_m >= 0.0, "height_tolerance_m", "must be >= 0");
  check.require(height_tolerance_fraction >= 0.0 && height_tolerance_fraction < 1.0, "height_tolerance_fraction",
          "must be in [0, 1)");
  check.require(columns >= 3, "columns", "must be >= 3");
}

SideFaceEvidence measureSideFace(const RgbdFrame& frame, const std::array<Eigen::Vector3d, 4>& corners_m,
                                 const Eigen::Vector3d& up, int edge, double max_height_m, const UpDirection& support,
                                 const SideFaceParams& params)
{
  SideFaceEvidence evidence;
  const Eigen::Vector3d& a = corners_m[edge % 4];
  const Eigen::Vector3d& b = corners_m[(edge + 1) % 4];
  const Eigen::Vector3d centre = 0.25 * (corners_m[0] + corners_m[1] + corners_m[2] + corners_m[3]);
  if (!((b - a).norm() > 1e-6) || !(max_height_m > 0.0)) return evidence;
  const Eigen::Vector3d down = -up.normalized();
  Eigen::Vector3d outward = (b - a).normalized().cross(up).normalized();
  if (outward.dot(a - centre) < 0.0) outward = -outward;
  // The camera must be on the outer side of the side plane to see it (a
  // grazing side shows no depth anyway).
  if (outward.dot(-a) / a.norm() < 0.05) return evidence;

  std::vector<double> feet, any;
  std::size_t grounded = 0;
  for (int column = 0; column < params.columns; ++column)
  {
    const double t = 0.2 + 0.6 * column / (params.columns - 1);
    const Run run =
        marchDown(frame, a + t * (b - a), down, outward, params.search_factor * max_height_m, support, params);
    if (run.end == RunEnd::kNone || run.height_m < params.min_visible_m) continue;
    any.push_back(run.height_m);
    if (run.end == RunEnd::kFoot) feet.push_back(run.height_m);
    grounded += run.on_support ? 1 : 0;
  }
  if (any.size() * 3 < static_cast<std::size_t>(params.columns)) return evidence;
  evidence.visible = true;
  evidence.visible_height_m = median(any);
  if (feet.size() * 3 >= static_cast<std::size_t>(params.columns))
  {
    evidence.foot_seen = true;
    evidence.foot_on_support = grounded * 2 > feet.size();
    evidence.visible_height_m = median(feet);
  }
  return evidence;
}

SideFaceVerdict judgeSideFace(const SideFaceEvidence& side, double height_m, const SideFaceParams& params)
{
  if (!side.visible) return SideFaceVerdict::kNotVisible;
  // Partly hidden: bricks stacked flush below could make any height.
  if (!side.foot_seen) return SideFaceVerdict::kCutShort;
  const double tolerance_m = std::max(params.height_tolerance_m, params.height_tolerance_fraction * height_m);
  for (int layers = 1; layers <= 3; ++layers)
    if (std::abs(side.visible_height_m - layers * height_m) <= tolerance_m) return SideFaceVerdict::kMatches;
  if (side.foot_on_support || side.visible_height_m > height_m + tolerance_m) return SideFaceVerdict::kMismatch;
  return SideFaceVerdict::kCutShort;
}

std::string toString(SideFaceVerdict verdict)
{
  switch (verdict)
  {
    case SideFaceVerdict::kCutShort: return "side partly hidden";
    case SideFaceVerdict::kMatches: return "side of the catalogue height";
    case SideFaceVerdict::kMismatch: return "side of another height";
    case SideFaceVerdict::kNotVisible:
    default: return "no side visible";
  }
}
}  // namespace brick_pose
