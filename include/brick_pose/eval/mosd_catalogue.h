#pragma once
// A catalogue for the mOSD boxes, measured from the scenes' ground truth:
// the boxes recur over the scenes (each standing upright or lying flat), so
// the tops measured in all scenes are grouped by size and each group becomes
// one catalogue type, its size the median of its measurements. A robot
// would be given these sizes; here they are measured once, written to
// test/data/mosd_learn/catalogue.yaml (bench_mosd_truth --write-catalogue)
// and read back by the benchmark and the tests.
//
// The HSV range of a type (for the hsv mode, which needs one) is fitted to
// its top pixels: the shortest hue interval holding hue_share of them and
// the [low, 1 - low] percentiles of saturation and value. The tops are
// printed in several colours, so these ranges are wide: that is what hsv
// segmentation of printed boxes has to work with.

#include <string>
#include <vector>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/eval/mosd_scene.h"
#include "brick_pose/eval/mosd_truth.h"

namespace brick_pose
{
namespace eval
{
struct MosdCatalogueParams
{
  /// Two measurements are one box when length, width and height differ by
  /// at most these.
  double max_length_difference_m = 0.015;
  double max_width_difference_m = 0.010;
  double max_height_difference_m = 0.015;
  double hue_share = 0.8;
  double saturation_value_low_percentile = 0.1;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// One box's top as measured in one scene.
struct MosdTopMeasurement
{
  std::string scene;
  int object = 0;
  double length_m = 0.0, width_m = 0.0, height_m = 0.0;
  bool whole = false;
  std::vector<int> top_pixels;  ///< v * width + u
};

/// A group of measurements of one box and the type made of it.
struct MosdBoxGroup
{
  std::vector<MosdTopMeasurement> members;
  BrickType type;
  double length_spread_m = 0.0, width_spread_m = 0.0, height_spread_m = 0.0;  ///< max - min
};

/// Every measured top of `truth` (boxes with a top).
std::vector<MosdTopMeasurement> topMeasurements(const MosdScene& scene, const MosdTruth& truth);

/// Groups measurements (greedy, in order, against each group's first
/// member) and makes a type of each; `scenes` (matched by name) give the
/// colour of the top pixels for the HSV fit.
std::vector<MosdBoxGroup> groupMosdBoxes(const std::vector<MosdTopMeasurement>& measurements,
                                         const std::vector<const MosdScene*>& scenes,
                                         const MosdCatalogueParams& params = MosdCatalogueParams());

/// The `bricks:` YAML of config/bricks.yaml's format.
std::string catalogueYaml(const std::vector<BrickType>& types, const std::string& header_comment);

/// test/data/mosd_learn/catalogue.yaml under `source_dir`.
std::string mosdCataloguePath(const std::string& source_dir);
}  // namespace eval
}  // namespace brick_pose
