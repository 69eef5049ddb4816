#pragma once
// The find of a union-find over integer ids, shared by the segmenters that
// join pixel runs and plane cells into regions.

#include <vector>

namespace brick_pose
{
/// The root of `node` in the forest `parent` (a root is its own parent),
/// halving the path on the way so that later finds are shorter.
inline int findRoot(std::vector<int>& parent, int node)
{
  while (parent[node] != node)
  {
    parent[node] = parent[parent[node]];
    node = parent[node];
  }
  return node;
}
}  // namespace brick_pose
