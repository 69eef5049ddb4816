// The top-face check on real Kinect scenes (test/data/mosd_learn, boxes on
// a table seen obliquely, config/mosd_boxes.yaml): side faces and strips of
// hidden tops are never complete; whole catalogue tops are found complete.
#include <algorithm>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/segmentation/region_growing_segmenter.h"
#include "mosd_scene.h"

namespace brick_pose
{
namespace
{
const std::string kScenes = BRICK_POSE_SOURCE_DIR "/test/data/mosd_learn";

BrickCatalogue boxes() { return BrickCatalogue::fromYamlFile(BRICK_POSE_SOURCE_DIR "/config/mosd_boxes.yaml"); }

/// Share of the candidate's pixels on the top of its most frequent box, that
/// box, and the share of that top the candidate covers.
struct TopOverlap
{
  int box = 0;
  double share = 0.0;
  double coverage = 0.0;
};

TopOverlap overlap(const BrickCandidate& candidate, const test::MosdScene& scene, const test::MosdTruth& truth)
{
  std::map<int, int> votes;
  for (const int pixel : candidate.pixel_indices)
  {
    const int v = pixel / scene.frame.width_px(), u = pixel % scene.frame.width_px();
    if (truth.top.at<std::uint8_t>(v, u)) ++votes[truth.object.at<int>(v, u)];
  }
  TopOverlap result;
  int best_votes = 0;
  for (const auto& [box, count] : votes)
    if (count > best_votes)
    {
      result.box = box;
      best_votes = count;
    }
  result.share = candidate.pixel_indices.empty() ? 0.0 : static_cast<double>(best_votes) / candidate.pixel_indices.size();
  for (const test::MosdObject& object : truth.objects)
    if (object.id == result.box && object.top_pixels > 0)
      result.coverage = static_cast<double>(best_votes) / object.top_pixels;
  return result;
}

/// A complete candidate must be one box's whole top.
void expectNoFalseComplete(const FrontEndResult& result, const test::MosdScene& scene, const test::MosdTruth& truth)
{
  for (const BrickCandidate& candidate : result.candidates)
  {
    if (!candidate.complete) continue;
    const TopOverlap top = overlap(candidate, scene, truth);
    EXPECT_GE(top.share, 0.7) << scene.name << ": complete " << candidate.type_name << " is not a top face";
    EXPECT_GE(top.coverage, 0.7) << scene.name << ": complete " << candidate.type_name << " is a part of box "
                                 << top.box << "'s top";
  }
}

TEST(MosdTopFaces, TheScenesAndTheirLabelsLoad)
{
  const auto scene = test::loadMosdScene(kScenes, 0);
  ASSERT_TRUE(scene) << "test/data/mosd_learn/learn0_* missing";
  EXPECT_EQ(scene->frame.width_px(), 640);
  const test::MosdTruth truth = test::analyseMosdScene(*scene);
  ASSERT_EQ(truth.objects.size(), 2u);
  // The table's normal points up toward the camera; the boxes stand on it.
  EXPECT_LT(truth.up.z(), -0.4);
  for (const test::MosdObject& object : truth.objects)
  {
    EXPECT_GT(object.top_pixels, 1000);
    EXPECT_GT(object.height_m, 0.15);
    EXPECT_LT(object.top_tilt_deg, 10.0);
  }
}

TEST(MosdTopFaces, OnTheLabelledFacesSideFacesAreRejectedAndWholeTopsAreComplete)
{
  // The ROI stage alone: every planar face the labels show (each box's top,
  // its side faces, the table) as a colour-free segment.
  const BrickCatalogue catalogue = boxes();
  const FrontEnd front_end(catalogue);
  int whole_tops = 0, found_complete = 0, doubtful_type = 0, composed_doubt = 0, side_faces = 0;
  for (int index = 0; index < 25; ++index)
  {
    const auto scene = test::loadMosdScene(kScenes, index);
    ASSERT_TRUE(scene) << "learn" << index;
    const test::MosdTruth truth = test::analyseMosdScene(*scene);
    const std::vector<Segment> faces = test::labelledFaceSegments(*scene, truth);
    FrontEndResult result;
    front_end.filterSegments(scene->frame, faces, result);
    EXPECT_EQ(result.up.source, UpSource::kSupportPlane) << scene->name;
    expectNoFalseComplete(result, *scene, truth);
    for (const BrickCandidate& candidate : result.candidates)
    {
      EXPECT_EQ(candidate.complete, candidate.partial_reason.empty()) << scene->name;
      EXPECT_LT(candidate.tilt_from_up_deg, 30.0) << scene->name << ": a side face is a candidate";
    }
    for (const Rejection& rejection : result.rejections)
      side_faces += rejection.reason.find("not a top face") != std::string::npos ? 1 : 0;
    for (const test::MosdObject& object : truth.objects)
    {
      const BrickType* type = test::catalogueTopOf(object, catalogue);
      if (!type) continue;
      ++whole_tops;
      for (const BrickCandidate& candidate : result.candidates)
      {
        const TopOverlap top = overlap(candidate, *scene, truth);
        if (top.box != object.id || top.share < 0.7) continue;
        if (candidate.complete && candidate.type_name == type->name)
        {
          ++found_complete;
          break;
        }
        if (!candidate.type_doubt.empty())
        {
          ++doubtful_type;
          composed_doubt += candidate.type_doubt.find("tops touching") != std::string::npos ? 1 : 0;
          break;
        }
      }
    }
  }
  EXPECT_GE(side_faces, 40) << "the boxes' front and side faces are rejected as side faces";
  EXPECT_GE(whole_tops, 15);
  // Where no side is seen down to the table, some tops are as near another
  // box's face as their own: Kinect measures birchermuesli tops (0.128 x
  // 0.038 m) 1 cm wide, as near toppas (0.147 x 0.054 m, 0.212 vs 0.243 m
  // tall) in learn15, learn16 and learn20; toppas tops (learn2, learn13)
  // 1.3 cm wide, as near a tea box lying on a side (0.148 x 0.058 m, 7.8 cm
  // tall). Those are found, partial, "type uncertain". The toppas lying on a
  // side in learn8 is as much two birchermuesli tops touching, and its print
  // draws a line where they would meet: partial, its type in doubt (a lone
  // face of a size smaller tops make up is doubted where their seam shows,
  // since two boxes side by side on a stack end at steps too).
  EXPECT_GE(found_complete, 10) << "whole catalogue tops found complete, of their type";
  EXPECT_LE(composed_doubt, 1) << "whole tops doubted as smaller tops touching (learn8's toppas only)";
  EXPECT_EQ(found_complete + doubtful_type, whole_tops)
      << "every whole catalogue top is found complete, of its type, or partial with its type in doubt";
}

TEST(MosdTopFaces, ColourFreeSegmentationNeverCallsASideFaceComplete)
{
  const BrickCatalogue catalogue = boxes();
  FrontEndParams params;
  params.mode = SegmentationMode::kRegionGrowing;
  const FrontEnd front_end(catalogue, params);
  for (int index = 0; index < 25; index += 3)
  {
    const auto scene = test::loadMosdScene(kScenes, index);
    ASSERT_TRUE(scene);
    const test::MosdTruth truth = test::analyseMosdScene(*scene);
    const FrontEndResult result = front_end.process(scene->frame);
    expectNoFalseComplete(result, *scene, truth);
  }
}

TEST(MosdTopFaces, RegionGrowingFindsTheWholeTopsAtTheKinectsResolution)
{
  // Region growing thins the frame to blocks of one angle at every
  // resolution: 3 px at the Kinect's 525 px focal length. With the 6 px
  // blocks of 1280x720 its normals' window spanned a box's top and the side
  // beside it, and it found 11 of the 41 whole tops (bench_frontend).
  const BrickCatalogue catalogue = boxes();
  FrontEndParams params;
  params.mode = SegmentationMode::kRegionGrowing;
  const FrontEnd front_end(catalogue, params);
  EXPECT_EQ(RegionGrowingSegmenter(params.region_growing).strideFor(525.0, 640, 480), 3);
  int whole_tops = 0, found = 0;
  for (int index = 0; index < 25; ++index)
  {
    const auto scene = test::loadMosdScene(kScenes, index);
    ASSERT_TRUE(scene) << "learn" << index;
    const test::MosdTruth truth = test::analyseMosdScene(*scene);
    const FrontEndResult result = front_end.process(scene->frame);
    expectNoFalseComplete(result, *scene, truth);
    for (const test::MosdObject& object : truth.objects)
    {
      const BrickType* type = test::catalogueTopOf(object, catalogue);
      if (!type) continue;
      ++whole_tops;
      found += std::any_of(result.candidates.begin(), result.candidates.end(), [&](const BrickCandidate& candidate) {
        const TopOverlap top = overlap(candidate, *scene, truth);
        return top.box == object.id && top.share >= 0.7 && top.coverage >= 0.7;
      });
    }
  }
  EXPECT_GE(whole_tops, 15);
  EXPECT_GE(found, whole_tops - 2) << "whole catalogue tops found by region growing, of " << whole_tops;
}

TEST(MosdTopFaces, WithoutUpNoFaceIsComplete)
{
  // The ROI filter told nothing about up (no tf, no frame estimate) cannot
  // tell a top from a side face: whole tops come out partial, with the reason.
  const auto scene = test::loadMosdScene(kScenes, 1);
  ASSERT_TRUE(scene);
  const test::MosdTruth truth = test::analyseMosdScene(*scene);
  const RoiFilter filter(boxes(), RoiFilterParams(), FrontEndParams::defaultSegmentCloudParams());
  int candidates = 0, up_unknown = 0;
  for (const Segment& face : test::labelledFaceSegments(*scene, truth))
    for (const BrickCandidate& candidate : filter.filterSplitting(scene->frame, face).candidates)
    {
      ++candidates;
      EXPECT_FALSE(candidate.complete);
      EXPECT_FALSE(candidate.partial_reason.empty());
      // Pieces of a face larger than any box, tiled, stop at a cut first.
      up_unknown += candidate.partial_reason.find("up direction unknown") != std::string::npos ? 1 : 0;
    }
  EXPECT_GE(up_unknown, 2) << "the two tops (and side faces of a top's size) are still candidates, partial for "
                              "want of up; of "
                           << candidates;
}

}  // namespace
}  // namespace brick_pose
