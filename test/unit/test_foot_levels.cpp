// The levels a face may stand on, read around its outline, and the type
// whose footing they show named among types a face's size and height leave
// tied (bench_frontend's frames, as the benchmark runs them).
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "brick_pose/eval/candidate_matching.h"
#include "brick_pose/eval/rig_truth.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/roi/foot_levels.h"

#include "bench_frame.h"

namespace brick_pose
{
namespace
{
bool anyWithin(const std::vector<double>& levels_m, double low_m, double high_m)
{
  return std::any_of(levels_m.begin(), levels_m.end(),
                     [&](double level_m) { return level_m > low_m && level_m < high_m; });
}

TEST(FootLevels, AFacesOwnSideSeenObliquelyIsNoLevel)
{
  // Table view 196 at 1280x720: a box_small on a box_flat, its top 0.22 m
  // up, seen obliquely. Its side hangs below its near edges across the ring
  // read around its foot, and the pixels there, and those mixed across the
  // depth jump at its far edge, lie at every height from the ledge to the
  // top, densest at about 0.145 m: read as a level, it was where a box_flat
  // would stand, and named the box box_flat.
  const BrickCatalogue boxes = BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/boxes.yaml");
  const test::BenchFrameRun run = test::runBenchFrame(boxes, test::kTableBoxesClass, 196, "1280x720");
  const RgbdFrame frame = makeRgbdFrame(run.rendered.rgb, run.rendered.depth_mm, run.rendered.camera,
                                        FrameHeader{1, "camera"});
  const BrickCandidate* top = nullptr;
  for (const BrickCandidate& candidate : run.result.candidates)
    if (std::abs(run.result.up.heightAboveSupport(candidate.centroid_m) - 0.22) < 0.02) top = &candidate;
  ASSERT_NE(top, nullptr) << "the stacked box's top was not found";

  // The side's pixels are a tenth of the lower ones read around this mask
  // (the benchmark's, a little tighter, had a fifth: a level then): the
  // share a level needs is lowered for both readings, so that the test
  // shows what keeps the side out, not the share.
  FootLevelParams level_only;
  level_only.min_share = 0.1;
  FootLevelParams any_surface = level_only;  // every lower pixel counts, as it did
  any_surface.max_level_tilt_deg = 90.0;
  any_surface.max_bend_m = std::numeric_limits<double>::infinity();
  const auto levels = [&](const FootLevelParams& params) {
    return levelsAroundFoot(frame, top->mask, top->bounding_box_px, top->plane, run.result.up, 0.02, params);
  };
  EXPECT_TRUE(anyWithin(levels(any_surface), 0.10, 0.20)) << "the side no longer reads as a level: the test shows nothing";
  EXPECT_FALSE(anyWithin(levels(level_only), 0.10, 0.20));
}

TEST(FootLevels, ABoxWhoseFootingShowsBesideItIsNamedItsTypeAndStaysInDoubt)
{
  // Pallet stack 158 at 1280x720: box_flat tops on box_small ones, 0.22 m
  // up, where a box_small on a box_flat would be as high. A lower box's
  // top seen beside them at 0.15 m names them box_flat; a neighbour just
  // that high could show the same, so box_small stays open and the face
  // partial.
  const BrickCatalogue boxes = BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/boxes.yaml");
  const test::BenchFrameRun run = test::runBenchFrame(boxes, test::kPalletStackClass, 158, "1280x720");
  const eval::SceneTruth truth = eval::rigSceneTruth(run.rendered, run.up_in_camera);
  const eval::FrameMatch match = eval::matchCandidates(run.result.candidates, truth, run.rendered.camera);
  int flat_tops_named = 0;
  for (std::size_t c = 0; c < match.candidates.size(); ++c)
  {
    const eval::CandidateMatch& candidate_match = match.candidates[c];
    EXPECT_FALSE(candidate_match.false_complete);
    if (candidate_match.outcome != eval::CandidateOutcome::kWholeTop) continue;
    const BrickCandidate& candidate = run.result.candidates[c];
    if (candidate.type_name != "box_flat") continue;
    if (std::abs(run.result.up.heightAboveSupport(candidate.centroid_m) - 0.22) > 0.02) continue;
    ++flat_tops_named;
    EXPECT_FALSE(candidate.complete);
    EXPECT_NE(std::find(candidate.other_possible_types.begin(), candidate.other_possible_types.end(), "box_small"),
              candidate.other_possible_types.end());
  }
  // All four were named box_small (the catalogue's order) before.
  EXPECT_GE(flat_tops_named, 2);
}
}  // namespace
}  // namespace brick_pose
