#include "brick_pose/segmentation/cell_clustering.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include <opencv2/core/utility.hpp>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/common/union_find.h"

namespace brick_pose
{
namespace
{

/// Standard deviation (rad) of a fitted normal: the noise over the spread of
/// the points along the plane's narrower axis, shrinking with their number.
double normalSigmaRad(const PlaneMoments& moments, const MomentPlane& plane, const DepthNoise& noise)
{
  return std::sqrt(noise.variance(moments) /
                   (noise.samples(moments.count) * std::max(plane.narrow_variance_m2, 1e-12)));
}

/// A node refits its plane when it has grown by this factor since the last
/// fit; in between, merges keep the normal and move the plane to the new
/// centroid. Most merges add a cell to a large node and hardly turn its
/// plane, and the eigen decomposition is the merge's main cost.
constexpr double kRefitGrowth = 1.1;

/// The plane of `moments` with the normal of `plane` (through their mean),
/// its MSE measured about that plane: an upper bound of the fitted one.
MomentPlane withNormal(const MomentPlane& plane, const PlaneMoments& moments)
{
  MomentPlane moved = plane;
  moved.count = moments.count;
  moved.centroid_m = moments.mean();
  moved.mse_m2 = std::max(0.0, plane.normal.dot(moments.covariance() * plane.normal));
  return moved;
}

enum class NodeState : std::uint8_t
{
  kNone,     // not a planar cell
  kActive,   // in the graph
  kMerged,   // absorbed into another node
  kPlane,    // retired as a plane (a neighbour may still absorb it)
  kRetired,  // retired, too small for a plane (a neighbour may still absorb it)
};

struct Node
{
  PlaneNode stats;
  double fitted_count = 0.0;  // points when the plane was last fitted
  // The node's neighbour list: a chain of links in NeighbourLinks (-1: empty).
  int first_link = -1, last_link = -1;
  int cells = 1;
  int version = 0;
  NodeState state = NodeState::kNone;
};

/// Every node's neighbour list in one pool of singly linked entries: a
/// merge appends the absorbed node's chain in constant time, and a frame
/// needs no allocation once the pool has grown to the grid (with a vector
/// per node, the lists of the nodes that happen to grow large differ from
/// frame to frame, and their reallocations cost more than the clustering).
struct NeighbourLinks
{
  std::vector<int> node;  // the neighbour (possibly merged since: resolve with findRoot)
  std::vector<int> next;  // following link of the chain, -1 at its end

  void clear()
  {
    node.clear();
    next.clear();
  }
  void append(Node& owner, int neighbour)
  {
    const int link = static_cast<int>(node.size());
    node.push_back(neighbour);
    next.push_back(-1);
    if (owner.last_link < 0)
      owner.first_link = link;
    else
      next[owner.last_link] = link;
    owner.last_link = link;
  }
  /// Moves the chain of `from` to the end of the chain of `to`.
  void splice(Node& to, Node& from)
  {
    if (from.first_link < 0) return;
    if (to.last_link < 0)
      to.first_link = from.first_link;
    else
      next[to.last_link] = from.first_link;
    to.last_link = from.last_link;
    from.first_link = from.last_link = -1;
  }
};

/// Starts each 4-connected group of the active cells non-zero in `seeds`
/// as one node (rooted at its first cell), when every one of its cells
/// lies on the group's plane within the noise; returns how many cells
/// started so.
int mergeSeedGroups(const CellClustering& clustering, const CellGrid& grid, const std::vector<std::uint8_t>& seeds,
                    const DepthNoise& noise, std::vector<Node>& nodes, std::vector<int>& parent)
{
  const int cols = grid.cols(), rows = grid.rows(), count = grid.size();
  std::vector<std::uint8_t> visited(static_cast<std::size_t>(count), 0);
  std::vector<int> group, stack;
  int seeded = 0;
  for (int start = 0; start < count; ++start)
  {
    if (!seeds[start] || visited[start] || nodes[start].state != NodeState::kActive) continue;
    group.clear();
    stack.assign(1, start);
    visited[start] = 1;
    PlaneMoments moments;
    while (!stack.empty())
    {
      const int cell = stack.back();
      stack.pop_back();
      group.push_back(cell);
      moments += grid.moments(cell);
      const int col = cell % cols, row = cell / cols;
      for (const int next : {col > 0 ? cell - 1 : -1, col + 1 < cols ? cell + 1 : -1, row > 0 ? cell - cols : -1,
                             row + 1 < rows ? cell + cols : -1})
        if (next >= 0 && seeds[next] && !visited[next] && nodes[next].state == NodeState::kActive)
        {
          visited[next] = 1;
          stack.push_back(next);
        }
    }
    if (group.size() < 2) continue;
    const MomentPlane plane = fitMomentPlane(moments);
    if (!plane.valid) continue;
    const PlaneNode merged(moments, plane, noise);
    if (!std::all_of(group.begin(), group.end(),
                     [&](int cell) { return clustering.liesOn(merged, nodes[cell].stats, noise); }))
      continue;
    Node& root = nodes[start];
    root.stats = merged;
    root.fitted_count = moments.count;
    root.cells = static_cast<int>(group.size());
    for (const int cell : group)
      if (cell != start)
      {
        parent[cell] = start;
        nodes[cell].state = NodeState::kMerged;
      }
    seeded += root.cells;
  }
  return seeded;
}

struct HeapEntry
{
  double mse_m2;
  int node;
  int version;
  bool operator>(const HeapEntry& other) const { return mse_m2 > other.mse_m2; }
};
}  // namespace

void CellClusteringParams::validate() const
{
  const ParamCheck check("colour-free segmenter");
  check.require(min_cell_fill > 0.0 && min_cell_fill <= 1.0, "min_cell_fill", "must be in (0, 1]");
  check.require(cell_sigma_factor > 0.0, "cell_sigma_factor", "must be > 0");
  check.require(spread_sigma_factor > 0.0, "spread_sigma_factor", "must be > 0");
  check.require(offset_sigma_factor > 0.0, "offset_sigma_factor", "must be > 0");
  check.require(offset_floor_m >= 0.0, "offset_floor_m", "must be >= 0");
  check.require(merge_sigma_factor > 0.0, "merge_sigma_factor", "must be > 0");
  check.require(plane_floor_m >= 0.0, "plane_floor_m", "must be >= 0");
  check.require(min_angle_deg >= 0.0 && min_angle_deg < 90.0, "min_angle_deg", "must be in [0, 90)");
  check.require(angle_sigma_factor >= 0.0, "angle_sigma_factor", "must be >= 0");
  check.require(max_angle_deg > 0.0 && max_angle_deg < 90.0 && max_angle_deg >= min_angle_deg, "max_angle_deg",
          "must be in (0, 90) and >= min_angle_deg");
  check.require(min_plane_cells >= 1, "min_plane_cells", "must be >= 1");
  check.require(max_plane_normal_sigma_deg > 0.0, "max_plane_normal_sigma_deg", "must be > 0");
  check.require(max_incidence_deg > 0.0 && max_incidence_deg < 90.0, "max_incidence_deg", "must be in (0, 90)");
  check.require(step_sigma_factor > 0.0, "step_sigma_factor", "must be > 0");
  check.require(min_step_fraction >= 0.0, "min_step_fraction", "must be >= 0");
}

std::vector<MomentPlane> fitCellPlanes(const CellGrid& grid, double min_cell_fill, bool parallel)
{
  const double min_points = std::max(3.0, min_cell_fill * grid.cellPx() * grid.cellPx());
  std::vector<MomentPlane> planes(static_cast<std::size_t>(grid.size()));
  auto fitRange = [&](const cv::Range& cells) {
    for (int i = cells.start; i < cells.end; ++i)
      if (grid.moments(i).count >= min_points) planes[i] = fitMomentPlane(grid.moments(i));
  };
  // One eigen decomposition per cell: a third of the cell stage.
  if (parallel)
    cv::parallel_for_(cv::Range(0, grid.size()), fitRange, 4.0);
  else
    fitRange(cv::Range(0, grid.size()));
  return planes;
}

CellClustering::CellClustering(const CellClusteringParams& params) : params_(params) { params_.validate(); }

PlaneNode::PlaneNode(const PlaneMoments& point_moments, const MomentPlane& point_plane, const DepthNoise& noise)
  : moments(point_moments),
    plane(point_plane),
    mean(point_moments.mean()),
    covariance(point_moments.covariance()),
    noise_variance_m2(noise.variance(point_moments)),
    normal_sigma_rad(normalSigmaRad(point_moments, point_plane, noise))
{
}

bool CellClustering::planarCell(const CellGrid& grid, int cell, const MomentPlane& plane, const DepthNoise& noise) const
{
  const PlaneMoments& moments = grid.moments(cell);
  if (!plane.valid || plane.mse_m2 > params_.cell_sigma_factor * params_.cell_sigma_factor * noise.variance(moments))
    return false;
  const double distance_m = plane.centroid_m.norm();
  const double plane_offset_m = std::abs(plane.normal.dot(plane.centroid_m));  // distance of the plane from the camera
  if (plane_offset_m < std::cos(params_.max_incidence_deg * kDegToRad) * distance_m) return false;
  return !depthStep(grid, cell, plane, noise);
}

bool CellClustering::depthStep(const CellGrid& grid, int cell, const MomentPlane& plane, const DepthNoise& noise) const
{
  // Depth along the image changes by z^2 n_u / (f d) per pixel on a plane
  // at distance d from the camera.
  const double z = grid.moments(cell).mean().z();
  const double plane_offset_m = std::max(1e-6, std::abs(plane.normal.dot(plane.centroid_m)));
  const double step_allowance_m =
      std::max(params_.step_sigma_factor * std::sqrt(2.0) * noise.sigma(z), params_.min_step_fraction * z);
  const double step_u_m = z * z * std::abs(plane.normal.x()) / (grid.fx() * plane_offset_m);
  const double step_v_m = z * z * std::abs(plane.normal.y()) / (grid.fy() * plane_offset_m);
  return grid.maxStepU(cell) > step_u_m + step_allowance_m || grid.maxStepV(cell) > step_v_m + step_allowance_m;
}

bool CellClustering::withinNoise(const PlaneNode& large, const PlaneNode& small, const DepthNoise& noise,
                                 double& spread_m2, double& offset_m) const
{
  const Eigen::Vector3d& n = large.plane.normal;
  // Cheapest test first: most pairs that fail, fail the scatter test.
  spread_m2 = n.dot(small.covariance * n);
  const double plane_floor2 = params_.plane_floor_m * params_.plane_floor_m;
  if (spread_m2 > params_.spread_sigma_factor * params_.spread_sigma_factor * small.noise_variance_m2 + plane_floor2)
    return false;

  offset_m = large.plane.signedDistance(small.mean);
  const double lever2_m2 = (small.mean - large.plane.centroid_m).squaredNorm();
  const double offset_sigma_m = std::sqrt(small.noise_variance_m2 / noise.samples(small.moments.count) +
                                          large.noise_variance_m2 / noise.samples(large.moments.count) +
                                          large.normal_sigma_rad * large.normal_sigma_rad * lever2_m2);
  return std::abs(offset_m) <= params_.offset_sigma_factor * offset_sigma_m + params_.offset_floor_m;
}

bool CellClustering::liesOn(const PlaneNode& large, const PlaneNode& small, const DepthNoise& noise) const
{
  double spread_m2 = 0.0, offset_m = 0.0;
  return withinNoise(large, small, noise, spread_m2, offset_m);
}

bool CellClustering::compatible(const PlaneNode& a, const PlaneNode& b, const DepthNoise& noise,
                                double& merged_mse_m2) const
{
  const bool a_larger = a.moments.count >= b.moments.count;
  const PlaneNode& large = a_larger ? a : b;
  const PlaneNode& small = a_larger ? b : a;
  const Eigen::Vector3d& n = large.plane.normal;
  double spread_m2 = 0.0, offset_m = 0.0;
  if (!withinNoise(large, small, noise, spread_m2, offset_m)) return false;
  const double plane_floor2 = params_.plane_floor_m * params_.plane_floor_m;

  const double total = large.moments.count + small.moments.count;
  merged_mse_m2 =
      (large.moments.count * large.plane.mse_m2 + small.moments.count * (spread_m2 + offset_m * offset_m)) / total;
  const double merged_variance_m2 =
      (large.moments.count * large.noise_variance_m2 + small.moments.count * small.noise_variance_m2) / total;
  if (merged_mse_m2 > params_.merge_sigma_factor * params_.merge_sigma_factor * merged_variance_m2 + plane_floor2)
    return false;

  const double combined_sigma_rad = std::sqrt(large.normal_sigma_rad * large.normal_sigma_rad +
                                              small.normal_sigma_rad * small.normal_sigma_rad);
  return std::abs(n.dot(small.plane.normal)) >= std::cos(maxAngleRad(combined_sigma_rad));
}

double CellClustering::maxAngleRad(double normal_sigma_rad) const
{
  return std::min(params_.max_angle_deg * kDegToRad,
                  params_.min_angle_deg * kDegToRad + params_.angle_sigma_factor * normal_sigma_rad);
}

CellPlanes CellClustering::cluster(const CellGrid& grid, const std::vector<MomentPlane>& cell_planes,
                                   const DepthNoise& noise, const std::vector<std::uint8_t>& seeds, int* seeded) const
{
  if (!seeds.empty() && static_cast<int>(seeds.size()) != grid.size())
    throw InputError("cell clustering: seeds must be empty or one per cell");
  const int cols = grid.cols(), rows = grid.rows(), count = grid.size();
  // Working storage kept between frames (thread_local: the segmenter is
  // const and may run in several threads).
  thread_local std::vector<Node> nodes;
  thread_local std::vector<int> parent;
  thread_local std::vector<HeapEntry> heap;  // a min-heap on the MSE
  thread_local NeighbourLinks links;
  thread_local std::vector<int> neighbours;  // the current node's, resolved
  links.clear();
  if (static_cast<int>(nodes.size()) < count) nodes.resize(static_cast<std::size_t>(count));
  parent.resize(static_cast<std::size_t>(count));
  heap.clear();
  auto push = [&](const HeapEntry& entry) {
    heap.push_back(entry);
    std::push_heap(heap.begin(), heap.end(), std::greater<HeapEntry>());
  };
  for (int i = 0; i < count; ++i)
  {
    parent[i] = i;
    Node& node = nodes[i];
    node.first_link = node.last_link = -1;
    node.cells = 1;
    node.version = 0;
    node.state = NodeState::kNone;
    if (!planarCell(grid, i, cell_planes[i], noise)) continue;
    node.stats = PlaneNode(grid.moments(i), cell_planes[i], noise);
    node.fitted_count = node.stats.moments.count;
    node.state = NodeState::kActive;
  }
  const int seeded_cells = seeds.empty() ? 0 : mergeSeedGroups(*this, grid, seeds, noise, nodes, parent);
  if (seeded) *seeded = seeded_cells;
  // A seed group's node links to the neighbours of all its cells (before
  // any merge a merged node is a seed group's member).
  for (int i = 0; i < count; ++i)
  {
    if (nodes[i].state == NodeState::kNone) continue;
    const int owner = parent[i];
    const int col = i % cols, row = i / cols;
    auto link = [&](int other) {
      if (nodes[other].state != NodeState::kNone && parent[other] != owner) links.append(nodes[owner], other);
    };
    if (col > 0) link(i - 1);
    if (col + 1 < cols) link(i + 1);
    if (row > 0) link(i - cols);
    if (row + 1 < rows) link(i + cols);
    if (owner == i) push({nodes[i].stats.plane.mse_m2, i, 0});
  }

  thread_local std::vector<unsigned> seen;
  seen.assign(static_cast<std::size_t>(count), 0);
  unsigned stamp = 0;
  std::vector<std::pair<double, int>> candidates;
  const double max_plane_sigma_rad = params_.max_plane_normal_sigma_deg * kDegToRad;
  while (!heap.empty())
  {
    std::pop_heap(heap.begin(), heap.end(), std::greater<HeapEntry>());
    const HeapEntry entry = heap.back();
    heap.pop_back();
    Node& node = nodes[entry.node];
    if (node.state != NodeState::kActive || node.version != entry.version) continue;

    // Neighbour ids may name nodes merged since: resolve and deduplicate.
    // Retired neighbours stay: a node that found no partner when it was
    // taken (its neighbours then were small and noisy) joins a plane that
    // grows up to it later.
    // (Deduplicated with a stamp per node rather than by sorting: a large
    // plane's border holds hundreds of ids and it is taken many times.)
    // The chain is rewritten in place: duplicates unlinked, ids resolved.
    ++stamp;
    neighbours.clear();
    for (int link = node.first_link, previous = -1; link >= 0; link = links.next[link])
    {
      const int root = findRoot(parent, links.node[link]);
      if (root == entry.node || seen[root] == stamp)
      {
        if (previous < 0)
          node.first_link = links.next[link];
        else
          links.next[previous] = links.next[link];
        if (node.last_link == link) node.last_link = previous;
        continue;
      }
      seen[root] = stamp;
      links.node[link] = root;
      neighbours.push_back(root);
      previous = link;
    }

    // Every compatible neighbour is absorbed, best (smallest merged MSE)
    // first and each re-tested against the grown node: one pop per ring of
    // growth rather than one per cell keeps a large plane's repeated scans
    // of its border affordable.
    candidates.clear();
    for (const int neighbour : neighbours)
    {
      double merged_mse_m2 = 0.0;
      if (compatible(node.stats, nodes[neighbour].stats, noise, merged_mse_m2))
        candidates.emplace_back(merged_mse_m2, neighbour);
    }
    std::sort(candidates.begin(), candidates.end());
    int absorbed = 0;
    for (const auto& [first_mse_m2, neighbour] : candidates)
    {
      Node& other = nodes[neighbour];
      double merged_mse_m2 = first_mse_m2;
      if (absorbed > 0 && !compatible(node.stats, other.stats, noise, merged_mse_m2)) continue;
      const PlaneMoments merged = node.stats.moments + other.stats.moments;
      MomentPlane merged_plane;
      if (merged.count > kRefitGrowth * node.fitted_count)
      {
        merged_plane = refitMomentPlane(merged, node.stats.plane.normal);
        if (!merged_plane.valid) continue;  // cannot happen for two planar nodes; be safe anyway
        node.fitted_count = merged.count;
      }
      else
        merged_plane = withNormal(node.stats.plane, merged);
      parent[neighbour] = entry.node;
      other.state = NodeState::kMerged;
      node.stats = PlaneNode(merged, merged_plane, noise);
      node.cells += other.cells;
      links.splice(node, other);
      ++absorbed;
    }
    if (absorbed == 0)
    {
      // A plane needs enough cells and a normal that the noise does not
      // swamp (a strip of cells one cell wide seen from far away can tilt
      // freely about its long axis).
      const bool plane = node.cells >= params_.min_plane_cells && node.stats.normal_sigma_rad <= max_plane_sigma_rad;
      node.state = plane ? NodeState::kPlane : NodeState::kRetired;
      continue;
    }
    ++node.version;
    push({node.stats.plane.mse_m2, entry.node, node.version});
  }

  CellPlanes result;
  result.cell_labels.assign(static_cast<std::size_t>(count), -1);
  std::vector<int> plane_of_node(static_cast<std::size_t>(count), -1);
  for (int i = 0; i < count; ++i)
  {
    if (nodes[i].state == NodeState::kNone) continue;
    const int root = findRoot(parent, i);
    if (nodes[root].state != NodeState::kPlane) continue;
    if (plane_of_node[root] < 0)
    {
      plane_of_node[root] = static_cast<int>(result.planes.size());
      const MomentPlane fitted = fitMomentPlane(nodes[root].stats.moments);
      result.planes.push_back(fitted.valid ? fitted : nodes[root].stats.plane);
      result.moments.push_back(nodes[root].stats.moments);
      result.cell_counts.push_back(nodes[root].cells);
    }
    result.cell_labels[i] = plane_of_node[root];
  }
  groupContinuousPlanes(grid, noise, result);
  return result;
}

void CellClustering::groupContinuousPlanes(const CellGrid& grid, const DepthNoise& noise, CellPlanes& result) const
{
  const int plane_count = static_cast<int>(result.planes.size());
  std::vector<int> parent(static_cast<std::size_t>(plane_count));
  for (int i = 0; i < plane_count; ++i) parent[i] = i;

  // Seam cells of each pair of planes: cells of one plane at most two cells
  // from a cell of the other along a row or a column (a line of non-planar
  // cells may lie between two parts of one surface).
  struct SeamCell
  {
    int first, second, cell;  // plane pair (first < second) and a cell of either
    bool operator<(const SeamCell& o) const
    {
      return first != o.first ? first < o.first : second != o.second ? second < o.second : cell < o.cell;
    }
    bool operator==(const SeamCell& o) const { return first == o.first && second == o.second && cell == o.cell; }
  };
  std::vector<SeamCell> seam;
  const int cols = grid.cols(), rows = grid.rows();
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col)
    {
      const int a_cell = row * cols + col;
      const int a = result.cell_labels[a_cell];
      if (a < 0) continue;
      for (int step = 1; step <= 2; ++step)
        for (const int direction : {1, cols})
        {
          const bool inside = direction == 1 ? col + step < cols : row + step < rows;
          if (!inside) continue;
          const int b_cell = a_cell + step * direction;
          const int b = result.cell_labels[b_cell];
          if (b < 0 || b == a) continue;
          // Across a cell between them only when it holds depths and no
          // depth step: two coplanar faces with a gap are two regions.
          const int middle = a_cell + direction;
          if (step == 2 && (grid.moments(middle).count < 3.0 || depthStep(grid, middle, result.planes[a], noise)))
            continue;
          seam.push_back({std::min(a, b), std::max(a, b), a_cell});
          seam.push_back({std::min(a, b), std::max(a, b), b_cell});
        }
    }
  std::sort(seam.begin(), seam.end());
  seam.erase(std::unique(seam.begin(), seam.end()), seam.end());

  for (std::size_t begin = 0; begin < seam.size();)
  {
    const int p = seam[begin].first, q = seam[begin].second;
    PlaneMoments p_side, q_side;
    std::size_t end = begin;
    for (; end < seam.size() && seam[end].first == p && seam[end].second == q; ++end)
      (result.cell_labels[seam[end].cell] == p ? p_side : q_side) += grid.moments(seam[end].cell);
    begin = end;
    const PlaneNode p_node(result.moments[p], result.planes[p], noise), q_node(result.moments[q], result.planes[q], noise);
    double merged_mse_m2 = 0.0;
    if (continuous(p_node, p_side, q_node, q_side, noise) || compatible(p_node, q_node, noise, merged_mse_m2))
      parent[findRoot(parent, q)] = findRoot(parent, p);
  }

  result.regions.assign(static_cast<std::size_t>(plane_count), -1);
  result.region_count = 0;
  std::vector<int> region_of_root(static_cast<std::size_t>(plane_count), -1);
  for (int i = 0; i < plane_count; ++i)
  {
    const int root = findRoot(parent, i);
    if (region_of_root[root] < 0) region_of_root[root] = result.region_count++;
    result.regions[i] = region_of_root[root];
  }
}

void CellClustering::joinTouchingRegions(const std::vector<PlaneSeam>& seams, int min_length, const DepthNoise& noise,
                                         CellPlanes& planes) const
{
  std::vector<int> parent(static_cast<std::size_t>(planes.region_count));
  for (int i = 0; i < planes.region_count; ++i) parent[i] = i;
  bool joined = false;
  for (const PlaneSeam& seam : seams)
  {
    const int p = seam.first, q = seam.second;
    if (seam.length < min_length || findRoot(parent, planes.regions[p]) == findRoot(parent, planes.regions[q])) continue;
    const PlaneNode p_node(planes.moments[p], planes.planes[p], noise), q_node(planes.moments[q], planes.planes[q], noise);
    double merged_mse_m2 = 0.0;
    if (continuous(p_node, seam.first_side, q_node, seam.second_side, noise) ||
        compatible(p_node, q_node, noise, merged_mse_m2))
    {
      parent[findRoot(parent, planes.regions[q])] = findRoot(parent, planes.regions[p]);
      joined = true;
    }
  }
  if (!joined) return;
  std::vector<int> renumbered(static_cast<std::size_t>(planes.region_count), -1);
  int count = 0;
  for (int& region : planes.regions)
  {
    const int root = findRoot(parent, region);
    if (renumbered[root] < 0) renumbered[root] = count++;
    region = renumbered[root];
  }
  planes.region_count = count;
}

bool CellClustering::continuous(const PlaneNode& p, const PlaneMoments& p_seam, const PlaneNode& q,
                                const PlaneMoments& q_seam, const DepthNoise& noise) const
{
  if (p_seam.count < 3.0 || q_seam.count < 3.0) return false;
  const double cos_angle = std::min(1.0, std::abs(p.plane.normal.dot(q.plane.normal)));
  if (cos_angle < std::cos(maxAngleRad(std::hypot(p.normal_sigma_rad, q.normal_sigma_rad)))) return false;
  // Along the mean normal, the two sides of the seam must be at one height:
  // within the uncertainty of their means, plus what the kink between the
  // two planes allows over the distance between them.
  const Eigen::Vector3d& n_p = p.plane.normal;
  const Eigen::Vector3d& n_q = q.plane.normal;
  const Eigen::Vector3d mean_normal = (n_p + (n_p.dot(n_q) < 0.0 ? -n_q : n_q)).normalized();
  const Eigen::Vector3d between = p_seam.mean() - q_seam.mean();
  const double step_m = std::abs(mean_normal.dot(between));
  const double sine = std::sqrt(std::max(0.0, 1.0 - cos_angle * cos_angle));
  const double tolerance_m =
      params_.offset_sigma_factor * std::sqrt(noise.variance(p_seam) / noise.samples(p_seam.count) +
                                              noise.variance(q_seam) / noise.samples(q_seam.count)) +
      sine * between.norm() + params_.offset_floor_m;
  return step_m <= tolerance_m;
}
}  // namespace brick_pose
