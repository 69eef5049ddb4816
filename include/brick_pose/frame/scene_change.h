#pragma once
// Whether anything in view changed since a keyframe (issue 14). A static
// pile seen by a static camera gives the same segments and candidates frame
// after frame; only the sensor noise differs. The front end can then reuse
// the keyframe's result instead of segmenting again.
//
// A frame is summarised block by block (SceneSignature): the mean depth of
// the block's valid pixels, the fraction that is valid, and the mean colour.
// A block changed when its mean depth moved by more than the stereo noise of
// a block mean at that depth allows, when its valid fraction moved, or when
// its colour moved. A block next to a depth step may move more, and one with
// holes of its own or next to a hole is judged by its valid fraction and
// colour only: their flying pixels and holes flicker. On the
// rig a whole top shifted 5 mm or turned 2 deg changes 10 to 900 blocks, a
// static scene's fresh noise at most a few (test_scene_change). A smaller
// change with nothing else moving (a brick creeping by a millimetre) can go
// unseen; the pipeline bounds that by measuring afresh every
// keyframe_max_age_s. When unsure it says "changed": the cost of a wrong
// "changed" is one full front end, of a wrong "unchanged" a stale pose.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "brick_pose/frame/rgbd_frame.h"

namespace brick_pose
{
struct SceneChangeParams
{
  /// Side of the square blocks a frame is summarised in, pixels.
  int block_px = 8;
  /// One pixel's depth noise at 1 m; stereo noise grows with depth squared.
  /// The D415's (subpixel 0.08 px, baseline 55 mm, f 920 px) is 1.6 mm.
  double depth_sigma_at_1m_m = 0.0016;
  /// A block's mean depth may move by this many pixel sigmas (at its depth),
  /// or by min_depth_change_m, whichever is larger. Stereo noise is
  /// correlated over the matching window, so a block mean is nearly as noisy
  /// as a pixel (the rig's static blocks: up to 3.6 sigmas).
  double depth_change_sigmas = 5.0;
  double min_depth_change_m = 0.002;
  /// A block next to a depth step holds the step's flying pixels, whose
  /// share flickers: its mean may move by this fraction of the step to its
  /// neighbour block.
  double step_fraction = 0.2;
  /// Mean colour change allowed per channel, grey levels (0..255); low light
  /// roughly triples the colour noise.
  double colour_change_levels = 8.0;
  /// Change allowed in a block's fraction of valid pixels (flickering holes).
  double valid_fraction_change = 0.35;
  /// Blocks with fewer valid pixels than this have no depth ...
  double min_valid_fraction = 0.5;
  /// ... and blocks with fewer than this, or next to a block without depth
  /// (a stereo shadow, a grazing surface), are compared by their valid
  /// fraction and colour only: their mean depth is over a flickering subset
  /// of flying pixels (a static oblique table view moved such blocks by up
  /// to 80 pixel sigmas).
  double full_valid_fraction = 0.9;
  /// The scene changed when more blocks than this changed. A brick moved by
  /// 2 mm or turned by a degree changes dozens along its edges; an arm or a
  /// hand in view, hundreds.
  int max_changed_blocks = 4;
  /// Up (from tf) may turn by this much before the scene counts as changed.
  double max_up_change_deg = 0.5;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// A frame summarised block by block.
class SceneSignature
{
public:
  SceneSignature() = default;
  /// Throws InputError for a frame without depth or colour of the same size.
  static SceneSignature of(const RgbdFrame& frame, const SceneChangeParams& params);

  bool empty() const { return blocks_.empty(); }
  int widthPx() const { return width_px_; }
  int heightPx() const { return height_px_; }

  struct Block
  {
    float mean_depth_m = 0.0f;  ///< of its valid pixels, 0 when none is
    float valid_fraction = 0.0f;
    float mean_rgb[3] = {0.0f, 0.0f, 0.0f};
  };
  const std::vector<Block>& blocks() const { return blocks_; }
  int blocksPerRow() const { return blocks_per_row_; }
  int blockPx() const { return block_px_; }
  const std::optional<Eigen::Vector3d>& up() const { return up_in_camera_; }

private:
  int width_px_ = 0;
  int height_px_ = 0;
  int block_px_ = 0;
  int blocks_per_row_ = 0;
  std::vector<Block> blocks_;
  std::optional<Eigen::Vector3d> up_in_camera_;
};

struct SceneChange
{
  bool changed = true;
  int changed_blocks = 0;
  /// The largest mean-depth change of a block with valid depth in both, metres.
  double max_depth_change_m = 0.0;
  /// Why it changed ("" when it did not): "no keyframe", "image size",
  /// "up direction", "14 blocks changed ...".
  std::string reason;
};

/// Compares `now` with `keyframe`. Block for block, so a camera that moved
/// changes nearly every block.
SceneChange compareScenes(const SceneSignature& keyframe, const SceneSignature& now, const SceneChangeParams& params);
}  // namespace brick_pose
