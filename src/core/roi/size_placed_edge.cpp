#include "brick_pose/roi/size_placed_edge.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "brick_pose/common/angles.h"

namespace brick_pose
{
namespace
{
/// A box may end along a line when at least this share of it shows a mark
/// (a line, groove, step, or what hides one): a box's end runs all along
/// it, and print (a label's edge, a barcode) marks a stretch or two of a
/// line's four. At half, the labels on the rig's pallet boxes kept 14 more
/// whole tops (of 160 at VGA) partial than at three quarters, and at three
/// quarters still no face of the rig or of mOSD is complete that is not a
/// whole top.
constexpr double kMinMarkedShare = 0.75;

/// A line across the face, parallel to the edge opposite `edge`, at
/// `extent_m` from it (measured toward `edge`), with its image direction
/// away from that opposite edge.
struct ProbeLine
{
  Eigen::Vector2d a_px, b_px, outward_px;
};

/// The face seen from the edge across from `edge`: the direction across
/// it (on the face's plane, toward `edge`), the face's own extent that way,
/// and the lines parallel to that edge at any extent.
class AcrossEdge
{
public:
  AcrossEdge(const BrickCandidate& face, int edge)
  {
    const auto& c = face.corners_m;
    // Edge k runs from corner k to k + 1; its opposite from k + 2 to k + 3,
    // whose ends k + 3 and k + 2 lie across from k and k + 1.
    from_a_m_ = c[(edge + 3) % 4];
    from_b_m_ = c[(edge + 2) % 4];
    const Eigen::Vector3d along = (from_b_m_ - from_a_m_).normalized();
    const Eigen::Vector3d sides = (c[edge] - from_a_m_) + (c[(edge + 1) % 4] - from_b_m_);
    across_ = (sides - along * along.dot(sides)).normalized();
    extent_m_ = 0.5 * ((c[edge] - from_a_m_).dot(across_) + (c[(edge + 1) % 4] - from_b_m_).dot(across_));
  }

  double extentM() const { return extent_m_; }

  ProbeLine at(const PinholeCamera& camera, double extent_m) const
  {
    const Eigen::Vector3d a = from_a_m_ + extent_m * across_, b = from_b_m_ + extent_m * across_;
    const Eigen::Vector2d a_px = camera.project(a), b_px = camera.project(b);
    const Eigen::Vector2d beyond_px = camera.project(0.5 * (a + b) + 0.01 * across_);
    return {a_px, b_px, beyond_px - 0.5 * (a_px + b_px)};
  }

private:
  Eigen::Vector3d from_a_m_, from_b_m_, across_;
  double extent_m_ = 0.0;
};

/// Whether something marks a line where a box `extent_m` across would end
/// (over kMinMarkedShare of any line from extent_m - reach_m to
/// extent_m + reach_m), seam_search_px apart: each line's seam search
/// reaches that far to either side, so every pixel between is searched
/// twice (more where the face is seen obliquely: its metres span fewer
/// pixels). Lines twice as far apart placed one more face at VGA and one
/// fewer at 720p on the pallet rows: where a mark lies between the lines
/// matters, and the denser reading is kept.
bool endMayBeMarked(const RgbdFrame& frame, const BrickCandidate& face, const AcrossEdge& across, double extent_m,
                    double reach_m, const EdgeEvidenceParams& params)
{
  const double depth_m = std::max(0.1, face.centroid_m.z());
  const double step_m = std::max(1e-3, std::max(1, params.seam_search_px) * depth_m / frame.camera.fx_px);
  for (double at_m = extent_m - reach_m; at_m <= extent_m + reach_m + 1e-9; at_m += step_m)
  {
    if (at_m <= 0.0) continue;
    const ProbeLine line = across.at(frame.camera, at_m);
    if (markedAlong(frame, face.plane, line.a_px, line.b_px, line.outward_px, kMinMarkedShare, params)) return true;
  }
  return false;
}
}  // namespace

bool meetAlongEdge(const BrickCandidate& face, int edge, const BrickCandidate& other, int other_edge,
                   double within_m)
{
  const Eigen::Vector3d a = face.corners_m[edge], b = face.corners_m[(edge + 1) % 4];
  const Eigen::Vector3d p = other.corners_m[other_edge], q = other.corners_m[(other_edge + 1) % 4];
  const double length_m = (b - a).norm();
  if (!(length_m > 0.0) || !((q - p).norm() > 0.0)) return false;
  const Eigen::Vector3d along = (b - a) / length_m;
  if (std::abs(along.dot((q - p).normalized())) < std::cos(10.0 * kDegToRad)) return false;
  const auto offLine = [&](const Eigen::Vector3d& point) {
    const Eigen::Vector3d from_a = point - a;
    return (from_a - along * along.dot(from_a)).norm();
  };
  if (offLine(p) > within_m || offLine(q) > within_m) return false;
  const double t_p = along.dot(p - a), t_q = along.dot(q - a);
  const double overlap_m = std::min(length_m, std::max(t_p, t_q)) - std::max(0.0, std::min(t_p, t_q));
  if (overlap_m < 0.8 * length_m) return false;
  // The centres lie on opposite sides of the line (across it, in the plane).
  const Eigen::Vector3d from_line = face.centroid_m - a - along * along.dot(face.centroid_m - a);
  return from_line.dot(other.centroid_m - a) < 0.0;
}

std::vector<double> catalogueExtentsM(const BrickCatalogue& catalogue)
{
  std::vector<double> extents;
  for (const BrickType& type : catalogue.types())
    for (const double extent_m : {type.length_m, type.width_m, type.height_m}) extents.push_back(extent_m);
  std::sort(extents.begin(), extents.end());
  std::vector<double> distinct;
  for (const double extent_m : extents)
    if (distinct.empty() || extent_m - distinct.back() > 1e-3) distinct.push_back(extent_m);
  return distinct;
}

SizePlacedEdge judgeSizePlacedEdge(const RgbdFrame& frame, const BrickCandidate& face, int edge,
                                   const std::vector<double>& extents_m, double tolerance_m,
                                   const EdgeEvidenceParams& params)
{
  SizePlacedEdge result;
  const EdgeKind opposite = face.edge_kinds[(edge + 2) % 4];
  if (!isRealEdge(opposite))
  {
    result.doubt = "and the edge across from it is no real edge either (" + toString(opposite) + ")";
    return result;
  }
  const AcrossEdge across(face, edge);
  const double own_m = across.extentM();
  for (const double extent_m : extents_m)
  {
    const double apart_m = std::abs(extent_m - own_m);
    if (apart_m <= tolerance_m) continue;
    if (!endMayBeMarked(frame, face, across, extent_m, std::min(tolerance_m, 0.5 * apart_m), params)) continue;
    std::ostringstream text;
    text.precision(3);
    text << "and a box " << extent_m << " m across from edge " << (edge + 2) % 4
         << " (a catalogue size) may end at a mark there";
    result.doubt = text.str();
    return result;
  }
  result.confirmed = true;
  return result;
}
}  // namespace brick_pose
