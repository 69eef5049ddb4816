#include "brick_pose/frame/scene_change.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"

namespace brick_pose
{
void SceneChangeParams::validate() const
{
  const ParamCheck check("scene change");
  check.require(block_px >= 2 && block_px <= 64, "block_px", "must be in [2, 64]", block_px);
  check.require(depth_sigma_at_1m_m > 0.0, "depth_sigma_at_1m_m", "must be > 0", depth_sigma_at_1m_m);
  check.require(depth_change_sigmas > 0.0, "depth_change_sigmas", "must be > 0", depth_change_sigmas);
  check.require(min_depth_change_m > 0.0, "min_depth_change_m", "must be > 0", min_depth_change_m);
  check.inRange(step_fraction, 0.0, 1.0, "step_fraction");
  check.require(colour_change_levels > 0.0, "colour_change_levels", "must be > 0", colour_change_levels);
  check.inRange(valid_fraction_change, 0.0, 1.0, "valid_fraction_change");
  check.inRange(min_valid_fraction, 0.0, 1.0, "min_valid_fraction");
  check.inRange(full_valid_fraction, min_valid_fraction, 1.0, "full_valid_fraction");
  check.require(max_changed_blocks >= 0, "max_changed_blocks", "must be >= 0", max_changed_blocks);
  check.require(max_up_change_deg > 0.0, "max_up_change_deg", "must be > 0", max_up_change_deg);
}

namespace
{
/// Running sums of one block: integers for colour (64 x 255 x 3 fits), a
/// float for depth (64 values near one depth).
struct BlockSums
{
  float depth_m = 0.0f;
  int valid = 0;
  int pixels = 0;
  int rgb[3] = {0, 0, 0};
};

SceneSignature::Block blockOf(const BlockSums& sums)
{
  SceneSignature::Block block;
  if (sums.pixels == 0) return block;
  if (sums.valid > 0) block.mean_depth_m = sums.depth_m / static_cast<float>(sums.valid);
  block.valid_fraction = static_cast<float>(sums.valid) / static_cast<float>(sums.pixels);
  for (int c = 0; c < 3; ++c) block.mean_rgb[c] = static_cast<float>(sums.rgb[c]) / static_cast<float>(sums.pixels);
  return block;
}

/// Adds pixels [u_begin, u_end) of one row to `sums`.
void addRow(const float* depth, const unsigned char* rgb, int u_begin, int u_end, BlockSums& sums)
{
  sums.pixels += u_end - u_begin;
  for (int u = u_begin; u < u_end; ++u)
  {
    sums.rgb[0] += rgb[3 * u];
    sums.rgb[1] += rgb[3 * u + 1];
    sums.rgb[2] += rgb[3 * u + 2];
    // NaN (a hole) fails the comparison.
    if (depth[u] > 0.0f)
    {
      sums.depth_m += depth[u];
      ++sums.valid;
    }
  }
}
}  // namespace

SceneSignature SceneSignature::of(const RgbdFrame& frame, const SceneChangeParams& params)
{
  if (frame.depth_m.type() != CV_32FC1 || frame.rgb.type() != CV_8UC3 || frame.depth_m.size() != frame.rgb.size())
    throw InputError("scene signature: needs CV_32FC1 depth and CV_8UC3 colour of one size");
  SceneSignature signature;
  const int block_px = params.block_px;
  signature.width_px_ = frame.depth_m.cols;
  signature.height_px_ = frame.depth_m.rows;
  signature.block_px_ = block_px;
  signature.blocks_per_row_ = (signature.width_px_ + block_px - 1) / block_px;
  signature.up_in_camera_ = frame.up_in_camera;
  const int block_rows = (signature.height_px_ + block_px - 1) / block_px;
  signature.blocks_.reserve(static_cast<std::size_t>(block_rows * signature.blocks_per_row_));
  std::vector<BlockSums> row_sums(static_cast<std::size_t>(signature.blocks_per_row_));
  for (int block_row = 0; block_row < block_rows; ++block_row)
  {
    std::fill(row_sums.begin(), row_sums.end(), BlockSums());
    const int v_end = std::min(signature.height_px_, (block_row + 1) * block_px);
    for (int v = block_row * block_px; v < v_end; ++v)
    {
      const float* depth = frame.depth_m.ptr<float>(v);
      const unsigned char* rgb = frame.rgb.ptr<unsigned char>(v);
      for (int column = 0; column < signature.blocks_per_row_; ++column)
        addRow(depth, rgb, column * block_px, std::min(signature.width_px_, (column + 1) * block_px),
               row_sums[static_cast<std::size_t>(column)]);
    }
    for (const BlockSums& sums : row_sums) signature.blocks_.push_back(blockOf(sums));
  }
  return signature;
}

namespace
{
bool sameLayout(const SceneSignature& a, const SceneSignature& b)
{
  return a.widthPx() == b.widthPx() && a.heightPx() == b.heightPx() && a.blockPx() == b.blockPx() &&
         a.blocks().size() == b.blocks().size();
}

/// Up changed: known in one and not the other, or turned.
bool upChanged(const SceneSignature& keyframe, const SceneSignature& now, const SceneChangeParams& params)
{
  if (keyframe.up().has_value() != now.up().has_value()) return true;
  if (!keyframe.up()) return false;
  const double cos_angle = keyframe.up()->normalized().dot(now.up()->normalized());
  return cos_angle < std::cos(params.max_up_change_deg * kDegToRad);
}

bool hasDepth(const SceneSignature::Block& block, const SceneChangeParams& params)
{
  return block.valid_fraction >= params.min_valid_fraction;
}

/// Calls `visit` with each block of the 3x3 neighbourhood of block `index`
/// (itself included) inside the signature; stops early when `visit`
/// returns false.
template <typename Visit>
void forEachNeighbour(const SceneSignature& signature, std::size_t index, Visit visit)
{
  const int per_row = signature.blocksPerRow();
  const int rows = static_cast<int>(signature.blocks().size()) / per_row;
  const int row = static_cast<int>(index) / per_row, column = static_cast<int>(index) % per_row;
  for (int r = std::max(0, row - 1); r <= std::min(rows - 1, row + 1); ++r)
    for (int c = std::max(0, column - 1); c <= std::min(per_row - 1, column + 1); ++c)
      if (!visit(signature.blocks()[static_cast<std::size_t>(r * per_row + c)])) return;
}

/// Whether block `index`'s mean depth means anything from frame to frame:
/// not when it has holes of its own or lies next to a block without depth
/// (a stereo shadow, a grazing surface). Its mean is then over a flickering
/// subset of flying pixels between a near and a far surface; its valid
/// fraction and colour still count.
bool depthComparable(const SceneSignature& signature, std::size_t index, const SceneSignature::Block& now,
                     const SceneChangeParams& params)
{
  const SceneSignature::Block& block = signature.blocks()[index];
  if (std::min(block.valid_fraction, now.valid_fraction) < params.full_valid_fraction) return false;
  bool all_have_depth = true;
  forEachNeighbour(signature, index, [&](const SceneSignature::Block& neighbour) {
    all_have_depth = hasDepth(neighbour, params);
    return all_have_depth;
  });
  return all_have_depth;
}

/// How far block `index` of `signature` may move in mean depth without a
/// change: the stereo noise of its depth, or next to a depth step a
/// fraction of the step (the step's flying pixels flicker).
double allowedDepthChangeM(const SceneSignature& signature, std::size_t index, const SceneChangeParams& params)
{
  const double depth_m = signature.blocks()[index].mean_depth_m;
  const double sigma_m = params.depth_sigma_at_1m_m * depth_m * depth_m;
  double allowed_m = std::max(params.min_depth_change_m, params.depth_change_sigmas * sigma_m);
  forEachNeighbour(signature, index, [&](const SceneSignature::Block& neighbour) {
    allowed_m = std::max(allowed_m, params.step_fraction * std::abs(neighbour.mean_depth_m - depth_m));
    return true;
  });
  return allowed_m;
}
}  // namespace

SceneChange compareScenes(const SceneSignature& keyframe, const SceneSignature& now, const SceneChangeParams& params)
{
  SceneChange change;
  if (keyframe.empty())
  {
    change.reason = "no keyframe";
    return change;
  }
  if (!sameLayout(keyframe, now))
  {
    change.reason = "image size";
    return change;
  }
  if (upChanged(keyframe, now, params))
  {
    change.reason = "up direction";
    return change;
  }
  int depth_blocks = 0, fraction_blocks = 0, colour_blocks = 0;
  for (std::size_t i = 0; i < now.blocks().size(); ++i)
  {
    const SceneSignature::Block& before = keyframe.blocks()[i];
    const SceneSignature::Block& after = now.blocks()[i];
    bool changed = false;
    if (std::abs(after.valid_fraction - before.valid_fraction) > params.valid_fraction_change)
    {
      changed = true;
      ++fraction_blocks;
    }
    else if (depthComparable(keyframe, i, after, params))
    {
      const double moved_m = std::abs(static_cast<double>(after.mean_depth_m) - before.mean_depth_m);
      change.max_depth_change_m = std::max(change.max_depth_change_m, moved_m);
      if (moved_m > allowedDepthChangeM(keyframe, i, params))
      {
        changed = true;
        ++depth_blocks;
      }
    }
    if (!changed)
      for (int c = 0; c < 3; ++c)
        if (std::abs(after.mean_rgb[c] - before.mean_rgb[c]) > params.colour_change_levels)
        {
          changed = true;
          ++colour_blocks;
          break;
        }
    if (changed) ++change.changed_blocks;
  }
  change.changed = change.changed_blocks > params.max_changed_blocks;
  if (change.changed)
  {
    std::ostringstream reason;
    reason << change.changed_blocks << " blocks changed (" << depth_blocks << " depth, " << fraction_blocks
           << " valid fraction, " << colour_blocks << " colour)";
    change.reason = reason.str();
  }
  return change;
}
}  // namespace brick_pose
