#pragma once
// Touching cuboids of one colour at one height (a row of bricks, a pallet
// layer of boxes) merge into one planar segment: real depth is smooth across
// the seams between them, and HSV sees one colour. This cuts such a segment
// into bricks by hypothesising how the catalogue's rectangles tile it.
//
// The segment is rasterised on its own plane (cells of a few millimetres,
// axes along its least-area quad, or along its outline's straight stretches
// where the two disagree: see outline_axis.h). Tiles are placed one at a time, each
// anchored at a corner of the region still untiled (the quad's corners
// first, then the corners earlier tiles leave), in every catalogue size and
// both orientations. A tile's far edges are moved, within the dimension
// tolerance, to the line the image supports best: a seam (a groove in depth
// or a dark line in colour, averaged along the whole line so that a
// millimetre-deep crease under several millimetres of noise still shows,
// and compared with the lines beside it, so that a noisier region of the
// face does not pass for a seam) or
// the region's own boundary. The tile whose edges the image supports best
// is kept, and the search goes on until nothing more fits. Corner anchoring
// tiles rows, grids and the pinwheel patterns of pallets alike.

#include <array>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/roi/brick_candidate.h"
#include "brick_pose/roi/edge_evidence.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
struct FaceTilingParams
{
  /// Raster cell on the plane (m); coarser for very large segments so that
  /// there are at most max_cells cells.
  double cell_m = 0.004;
  int max_cells = 120000;
  /// Seam evidence: dips are measured between points this many pixels to
  /// either side of a line.
  int seam_arm_px = 3;
  /// A line is a seen seam when its mean dip is at least this many standard
  /// errors (and above EdgeEvidenceParams' absolute minimums).
  double min_seam_strength = 4.0;
  /// At least this share of a tile's cells inside the image must be cells
  /// of the segment not yet tiled...
  double min_coverage = 0.8;
  /// ... and at most this share other surfaces or other tiles.
  double max_foreign_fraction = 0.12;
  /// A tile may reach beyond the segment (the image border or an occluder
  /// cutting the brick) but must show at least this fraction of its area.
  double min_visible_fraction = 0.4;
  /// Largest number of tiles per segment.
  int max_tiles = 48;
  /// A cut seen (min_seam_strength) but too short to be confirmed alone is
  /// confirmed when the cuts continuing it on the same line, each seen on
  /// its own, are confirmed read together: one seam runs past several
  /// bricks of a grid. Only on plain faces (the ROI filter sets it per
  /// face): on a printed one, lines run along rows of print and tape.
  bool confirm_along_lines = false;
  /// Threads reading a face's seam evidence (one per direction of its
  /// grid; the front end sets its own worker_threads).
  int worker_threads = 1;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// One brick of a tiling: its type, its rectangle on the plane and the
/// segment of its pixels.
struct FaceTile
{
  std::string type_name;
  /// Rectangle corners on the plane (camera frame, m).
  std::array<Eigen::Vector3d, 4> corners_m;
  /// Edges (corner k to k + 1) that cut through the segment (the others
  /// follow its boundary), and whether a seam was seen along each cut.
  std::array<bool, 4> cut{{false, false, false, false}};
  std::array<bool, 4> seam_seen{{false, false, false, false}};
  /// The tile's pixels; empty in tileFaceEach()'s tilings until
  /// cutTileSegments().
  Segment segment;
};

struct FaceTiling
{
  std::vector<FaceTile> tiles;
  /// Cells of the segment no tile took (fraction of the segment's cells).
  double untiled_fraction = 0.0;
  /// Cuts made, how many of them followed a seen seam (a groove in depth
  /// or a line in colour), and how many a groove in depth (print on a box
  /// draws lines; only a gap between two boxes dents the depth).
  int cuts = 0;
  int seen_cuts = 0;
  int grooved_cuts = 0;
  /// The weakest dark (or bright) line along a cut, in grey levels
  /// (infinity without cuts).
  double weakest_cut_line = std::numeric_limits<double>::infinity();
};

/// Which way a tiling may lay its rectangles, relative to the axis of the
/// face's grid (its quad's, or its outline's: see face_tiling.cpp).
enum class TileOrientation
{
  kEither,          ///< each rectangle either way (the greedy tiler picks)
  kLongAlongAxis,   ///< every rectangle's length along the axis
  kLongAcrossAxis,  ///< every rectangle's length across it
};

/// Tiles `segment` (measured as `measured`: plane and least-area quad) with
/// rectangles of `types` (length x width, either orientation) whose edges
/// may be off by `tolerance_m`. Empty tiles when no two rectangles fit.
FaceTiling tileFace(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                    const std::vector<const BrickType*>& types, double tolerance_m, const FaceTilingParams& params,
                    const EdgeEvidenceParams& evidence_params);

/// The same face tiled with each of `type_sets` in turn, each once per
/// entry of `orientations` (sharing the raster and the seam evidence, which
/// do not depend on the types), skipping the sets `wanted` refuses given
/// the tilings made so far; the tilings made, in order (set by set, each
/// set's orientations in order). Their tiles' segments are left empty: most
/// tilings are compared and dropped, and cutTileSegments() cuts the one kept.
std::vector<FaceTiling> tileFaceEach(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                                     const std::vector<std::vector<const BrickType*>>& type_sets, double tolerance_m,
                                     const FaceTilingParams& params, const EdgeEvidenceParams& evidence_params,
                                     const std::function<bool(std::size_t set, const std::vector<FaceTiling>& made)>& wanted,
                                     const std::vector<TileOrientation>& orientations = {TileOrientation::kEither});

/// Fills each tile's segment: the pixels of `segment` (the face tiled)
/// inside the tile's image.
void cutTileSegments(const RgbdFrame& frame, const Segment& segment, FaceTiling& tiling);
}  // namespace brick_pose
