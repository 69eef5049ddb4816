#pragma once
// A printed box draws lines anywhere on its top, so a line in the colour
// image alone does not show where a box ends: on a pallet layer of touching
// boxes, the edges between them are such lines, and every box there was
// partial. The catalogue adds what the line lacks. Where the face's
// opposite edge is a real one (a step, a crease, a groove), the box that
// starts there ends at one of the catalogue's extents across it. When the
// line lies at one of them and nothing marks any other (no line, groove,
// step, border or occluder along three quarters of where a box of another
// size would end), the line is that box's end. Print could fool this only
// by drawing a line all across the face at a catalogue extent, on a face of
// a type's size, while the true end shows a mark along a quarter of its
// length at most: the colour-free front end's premise everywhere else is
// that a seam shows.

#include <string>
#include <vector>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/roi/brick_candidate.h"
#include "brick_pose/roi/edge_evidence.h"

namespace brick_pose
{
/// Every extent (m) a catalogue box's top may have along either of its
/// axes, in any pose (lying on a side or an end too): each type's length,
/// width and height, ascending, those within 1 mm of another dropped.
std::vector<double> catalogueExtentsM(const BrickCatalogue& catalogue);

/// What placed (or failed to place) a colour line as the face's end.
struct SizePlacedEdge
{
  bool confirmed = false;
  /// Why not, for the face's partial reason; empty when confirmed.
  std::string doubt;
};

/// Whether `face`'s edge `edge` (a colour line) is where the box ends: its
/// opposite edge is real (isRealEdge, printed), and for every extent of
/// `extents_m` farther than `tolerance_m` from the face's own across that
/// edge, the lines parallel to the opposite edge at that extent (within
/// the tolerance, or half the way to the face's own) are each unmarked
/// along more than a quarter of their length (markedAlong).
SizePlacedEdge judgeSizePlacedEdge(const RgbdFrame& frame, const BrickCandidate& face, int edge,
                                   const std::vector<double>& extents_m, double tolerance_m,
                                   const EdgeEvidenceParams& params);
/// Whether `face`'s edge `edge` and `other`'s edge `other_edge` are one line
/// the two faces meet along, from either side: parallel within 10 degrees,
/// each end of the other's edge within `within_m` of the face's edge's line,
/// covering at least 80 % of it, the faces' centres on opposite sides.
/// Where a line was placed as one box's end (kSizePlacedLine), the box
/// across it begins there: a real edge for that face too.
bool meetAlongEdge(const BrickCandidate& face, int edge, const BrickCandidate& other, int other_edge,
                   double within_m);
}  // namespace brick_pose
