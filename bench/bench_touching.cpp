// Benchmark of the ROI stage on touching bricks and on real oblique scenes.
//
//   bench_touching [--frames N] [--seed S] [--modes hsv,region_growing]
//                  [--mosd DIR] [--measure-mosd]
//
// 1. Touching rows: seeded synthetic scenes of bricks of one type lying side
//    by side or end to end with no gap or a gap of 1-3 mm (single rows,
//    grids, two types in one layer), seen from 45-88 deg at 0.8-2 m, at
//    1280x720 and 640x480. Until the rig renders D4xx depth, the depth is
//    smoothed here as a stereo matching window would: each pixel becomes the
//    mean of its 7x7 neighbourhood with differences clipped at +-2 cm, so a
//    gap narrower than the window leaves only a faint crease. A candidate
//    is a true positive when most of its pixels are the top face of one
//    brick of its type that no earlier candidate took; recall counts top
//    faces at least 60% visible. A complete candidate is a false complete
//    when it is not a true positive, or its brick's top is less than 95%
//    visible, or a corner is more than 8 px off.
// 2. mOSD (real Kinect scenes, config/mosd_boxes.yaml): boxes and their top
//    faces come from the labels (see test/unit/mosd_scene.h). A whole
//    catalogue top is a labelled top whose measured size is a catalogue
//    top's within 1.5 cm; recall counts those found (a candidate with most
//    pixels on it, of a type of that top size). A complete candidate whose
//    pixels are not mostly one box's top is a false complete (a side face,
//    a strip of a hidden top).
// --measure-mosd prints every labelled box's top size and height (the
// source of config/mosd_boxes.yaml) and exits.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../test/unit/mosd_scene.h"
#include "brick_pose/common/statistics.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/pipeline/candidate_overlay.h"
#include "brick_pose/sim/fast_random.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

using namespace brick_pose;

namespace
{
struct Options
{
  int frames = 120;
  std::uint64_t seed = 1;
  std::vector<std::string> modes = {"hsv", "region_growing"};
  std::string mosd_dir = "test/data/mosd_learn";
  std::string mosd_catalogue = "config/mosd_boxes.yaml";
  bool measure_mosd = false;
  std::string overlay_dir;  // write mOSD overlays (segments, candidates, rejections) here
  int rig_frames = 0;        // also run bench_frontend's first N rig frames in hsv mode (debugging)
};

std::vector<std::string> splitList(const std::string& text)
{
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');)
    if (!item.empty()) items.push_back(item);
  return items;
}

Options parseOptions(int argc, char** argv)
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--frames" && has_value) options.frames = std::max(0, std::atoi(argv[++i]));
    else if (arg == "--seed" && has_value) options.seed = std::strtoull(argv[++i], nullptr, 10);
    else if (arg == "--modes" && has_value) options.modes = splitList(argv[++i]);
    else if (arg == "--mosd" && has_value) options.mosd_dir = argv[++i];
    else if (arg == "--mosd-catalogue" && has_value) options.mosd_catalogue = argv[++i];
    else if (arg == "--measure-mosd") options.measure_mosd = true;
    else if (arg == "--overlay" && has_value) options.overlay_dir = argv[++i];
    else if (arg == "--rig-frames" && has_value) options.rig_frames = std::max(0, std::atoi(argv[++i]));
    else
    {
      std::cerr << "usage: bench_touching [--frames N] [--seed S] [--modes hsv,region_growing] [--mosd DIR]\n"
                   "                      [--mosd-catalogue YAML] [--measure-mosd]\n";
      std::exit(arg == "--help" || arg == "-h" ? 0 : 2);
    }
  }
  return options;
}

double loadAverage()
{
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

// ---------------------------------------------------------------- scenes

/// A layer of touching bricks on the ground and a camera looking at it.
sim::Scene touchingScene(const BrickCatalogue& catalogue, std::uint64_t seed, std::string& layout)
{
  sim::FastRandom random(seed);
  sim::Scene scene;
  const auto& types = catalogue.types();
  // Short types make the rows that fit in view; the long ones end to end
  // would leave the image.
  const BrickType& red = catalogue.at("red");
  const BrickType& green = catalogue.at("green");
  const int kind = static_cast<int>(random.uniform() * 4.0);
  const double gap_m = 0.001 * static_cast<int>(random.uniform() * 4.0);  // 0, 1, 2 or 3 mm
  auto place = [&](const BrickType& type, double x, double y, double yaw) {
    sim::PlacedBrick brick;
    brick.type = type;
    brick.world_T_brick = Eigen::Isometry3d::Identity();
    brick.world_T_brick.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    brick.world_T_brick.translation() = Eigen::Vector3d(x, y, type.height_m);
    scene.bricks.push_back(brick);
  };
  const double yaw = random.uniform(-M_PI, M_PI);
  const Eigen::Rotation2Dd turn(yaw);
  auto at = [&](double along, double across) { return turn * Eigen::Vector2d(along, across); };
  if (kind == 0)
  {
    // Side by side: 2-5 bricks of one type touching along their long edges.
    const BrickType& type = types[static_cast<std::size_t>(random.uniform() * std::min<std::size_t>(2, types.size()))];
    const int count = 2 + static_cast<int>(random.uniform() * 4.0);
    for (int k = 0; k < count; ++k)
    {
      const Eigen::Vector2d p = at(0.0, (k - 0.5 * (count - 1)) * (type.width_m + gap_m));
      place(type, p.x(), p.y(), yaw);
    }
    layout = "side by side x" + std::to_string(count);
  }
  else if (kind == 1)
  {
    // End to end: 2-3 red bricks touching at their short edges.
    const int count = 2 + static_cast<int>(random.uniform() * 2.0);
    for (int k = 0; k < count; ++k)
    {
      const Eigen::Vector2d p = at((k - 0.5 * (count - 1)) * (red.length_m + gap_m), 0.0);
      place(red, p.x(), p.y(), yaw);
    }
    layout = "end to end x" + std::to_string(count);
  }
  else if (kind == 2)
  {
    // A grid: 2 x 2 or 3 x 2 red bricks.
    const int rows = 2 + static_cast<int>(random.uniform() * 2.0);
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < 2; ++c)
      {
        const Eigen::Vector2d p =
            at((c - 0.5) * (red.length_m + gap_m), (r - 0.5 * (rows - 1)) * (red.width_m + gap_m));
        place(red, p.x(), p.y(), yaw);
      }
    layout = "grid " + std::to_string(rows) + "x2";
  }
  else
  {
    // Two types in one layer: a green beside two reds end to end.
    place(green, at(0.0, -0.5 * (green.width_m + gap_m)).x(), at(0.0, -0.5 * (green.width_m + gap_m)).y(), yaw);
    for (int c = 0; c < 2; ++c)
    {
      const Eigen::Vector2d p = at((c - 0.5) * (red.length_m + gap_m), 0.5 * (red.width_m + gap_m));
      place(red, p.x(), p.y(), yaw);
    }
    layout = "mixed green + 2 red";
  }
  const double distance_m = random.uniform(0.8, 2.0);
  const double elevation_deg = random.uniform(45.0, 88.0);
  const double azimuth_deg = random.uniform(0.0, 360.0);
  double top_z = 0.0;
  for (const auto& brick : scene.bricks) top_z = std::max(top_z, brick.world_T_brick.translation().z());
  scene.world_T_camera = sim::lookAt(Eigen::Vector3d(0.0, 0.0, top_z), distance_m, elevation_deg, azimuth_deg);
  layout += ", gap " + std::to_string(static_cast<int>(std::lround(gap_m * 1000.0))) + " mm";
  return scene;
}

/// A stereo matching window over the depth: 7x7 mean with differences
/// clipped at +-2 cm (see the header comment).
cv::Mat stereoWindowDepth(const cv::Mat& depth_mm)
{
  constexpr int kHalf = 3;
  constexpr double kClipMm = 20.0;
  cv::Mat smoothed = depth_mm.clone();
  for (int v = 0; v < depth_mm.rows; ++v)
    for (int u = 0; u < depth_mm.cols; ++u)
    {
      const double centre = depth_mm.at<std::uint16_t>(v, u);
      if (centre <= 0.0) continue;
      double sum = 0.0;
      int count = 0;
      for (int dv = -kHalf; dv <= kHalf; ++dv)
        for (int du = -kHalf; du <= kHalf; ++du)
        {
          const int uu = u + du, vv = v + dv;
          if (uu < 0 || vv < 0 || uu >= depth_mm.cols || vv >= depth_mm.rows) continue;
          const double other = depth_mm.at<std::uint16_t>(vv, uu);
          if (other <= 0.0) continue;
          sum += std::max(-kClipMm, std::min(kClipMm, other - centre));
          ++count;
        }
      smoothed.at<std::uint16_t>(v, u) = static_cast<std::uint16_t>(std::lround(centre + sum / std::max(1, count)));
    }
  return smoothed;
}

// ---------------------------------------------------------------- scoring

struct Stats
{
  int truths = 0, found = 0, candidates = 0, true_positives = 0, complete = 0, false_complete = 0;
  int whole_truths = 0, whole_found_complete = 0;
  std::vector<double> corner_error_px, total_ms;
  std::map<std::string, int> misses, false_completes, partial_whole;

  double recall() const { return truths ? static_cast<double>(found) / truths : 1.0; }
  double precision() const { return candidates ? static_cast<double>(true_positives) / candidates : 1.0; }
};

int topFaceInstance(const BrickCandidate& candidate, const sim::SyntheticFrame& frame, double& share)
{
  std::map<int, int> votes;
  const auto* instances = frame.instance_labels.ptr<std::uint16_t>(0);
  const auto* faces = frame.face_labels.ptr<std::uint8_t>(0);
  for (const int pixel : candidate.pixel_indices)
    if (faces[pixel] == static_cast<std::uint8_t>(sim::CuboidFace::kTop)) ++votes[instances[pixel]];
  int best = 0, best_votes = 0;
  for (const auto& [instance, count] : votes)
    if (count > best_votes)
    {
      best = instance;
      best_votes = count;
    }
  share = candidate.pixel_indices.empty() ? 0.0 : static_cast<double>(best_votes) / candidate.pixel_indices.size();
  return best;
}

double worstCornerErrorPx(const BrickCandidate& candidate, const sim::BrickTruth& truth, const PinholeCamera& camera)
{
  const auto corners_m = sim::topFaceCornersInCamera(truth);
  double worst = 0.0;
  for (const auto& corner_m : corners_m)
  {
    const Eigen::Vector2d p = camera.project(corner_m);
    double nearest = 1e9;
    for (const auto& c : candidate.corners_px) nearest = std::min(nearest, (c - p).norm());
    worst = std::max(worst, nearest);
  }
  return worst;
}

void scoreSynthetic(const FrontEndResult& result, const sim::SyntheticFrame& frame, Stats& stats,
                    const std::string& layout)
{
  stats.total_ms.push_back(result.timings.total_ms);
  std::vector<bool> taken(frame.truth.size() + 1, false);
  for (const BrickCandidate& candidate : result.candidates)
  {
    ++stats.candidates;
    stats.complete += candidate.complete ? 1 : 0;
    double share = 0.0;
    const int instance = topFaceInstance(candidate, frame, share);
    const sim::BrickTruth* truth = instance > 0 ? &frame.truth[instance - 1] : nullptr;
    const bool true_positive = truth && share >= 0.5 && truth->type == candidate.type_name && !taken[instance];
    double corner_px = 1e9;
    if (true_positive)
    {
      taken[instance] = true;
      ++stats.true_positives;
      corner_px = worstCornerErrorPx(candidate, *truth, frame.camera);
      if (truth->visible_fraction >= 0.95) stats.corner_error_px.push_back(corner_px);
      if (truth->visible_fraction >= 0.95 && !candidate.complete)
      {
        std::string reason = candidate.partial_reason;
        for (char& c : reason)
          if (c >= '0' && c <= '9') c = '#';
        ++stats.partial_whole[reason.substr(0, 70)];
        if (std::getenv("BENCH_VERBOSE"))
          std::fprintf(stderr, "whole top partial (%s) %s %.3f x %.3f: %s\n", layout.c_str(), candidate.type_name.c_str(),
                       candidate.length_m, candidate.width_m, candidate.partial_reason.c_str());
      }
    }
    if (!candidate.complete) continue;
    std::string why;
    if (!true_positive) why = "not a true positive";
    else if (truth->visible_fraction < 0.95) why = "top not wholly visible";
    else if (corner_px > 8.0) why = "a corner more than 8 px off";
    if (!why.empty() && std::getenv("BENCH_VERBOSE"))
      std::fprintf(stderr, "  %s: corner %.1f px, truth visible %.2f, edges %s %s %s %s\n", layout.c_str(), corner_px,
                   truth ? truth->visible_fraction : 0.0, toString(candidate.edge_kinds[0]).c_str(),
                   toString(candidate.edge_kinds[1]).c_str(), toString(candidate.edge_kinds[2]).c_str(),
                   toString(candidate.edge_kinds[3]).c_str());
    if (!why.empty())
    {
      ++stats.false_complete;
      ++stats.false_completes[why];
      if (std::getenv("BENCH_VERBOSE"))
        std::fprintf(stderr, "false complete (%s) %s: %s %.3f x %.3f\n", layout.c_str(), why.c_str(),
                     candidate.type_name.c_str(), candidate.length_m, candidate.width_m);
    }
  }
  for (const sim::BrickTruth& truth : frame.truth)
  {
    if (truth.visible_fraction < 0.6) continue;
    ++stats.truths;
    if (truth.visible_fraction >= 0.95) ++stats.whole_truths;
    if (taken[truth.instance_id])
    {
      ++stats.found;
      for (const BrickCandidate& candidate : result.candidates)
      {
        double share = 0.0;
        if (candidate.complete && topFaceInstance(candidate, frame, share) == truth.instance_id && share >= 0.5 &&
            truth.visible_fraction >= 0.95)
          ++stats.whole_found_complete;
      }
      continue;
    }
    std::string reason = "no candidate";
    for (const Rejection& rejection : result.rejections)
    {
      const cv::Rect& box = rejection.bounding_box_px;
      int inside = 0;
      for (int v = box.y; v < box.br().y; v += 2)
        for (int u = box.x; u < box.br().x; u += 2)
          if (frame.instance_labels.at<std::uint16_t>(v, u) == truth.instance_id &&
              frame.face_labels.at<std::uint8_t>(v, u) == static_cast<std::uint8_t>(sim::CuboidFace::kTop))
            ++inside;
      if (inside * 4 > truth.visible_top_pixels / 3)
      {
        reason = rejection.reason.substr(0, rejection.reason.find_first_of("0123456789"));
        break;
      }
    }
    ++stats.misses[reason];
    if (std::getenv("BENCH_VERBOSE"))
      std::fprintf(stderr, "miss (%s) %s vis %.2f: %s\n", layout.c_str(), truth.type.c_str(), truth.visible_fraction,
                   reason.c_str());
  }
}

void printStats(const std::string& title, const Stats& stats)
{
  std::printf("\n== %s ==\n", title.c_str());
  std::printf("  recall          %6.4f  (%d / %d top faces >= 60%% visible)\n", stats.recall(), stats.found, stats.truths);
  std::printf("  precision       %6.4f  (%d / %d candidates)\n", stats.precision(), stats.true_positives, stats.candidates);
  std::printf("  complete        %d candidates; whole tops found complete %d / %d\n", stats.complete,
              stats.whole_found_complete, stats.whole_truths);
  std::printf("  false complete  %d\n", stats.false_complete);
  if (!stats.corner_error_px.empty())
    std::printf("  worst corner px median %.2f  p90 %.2f  (true positives, top >= 95%% visible)\n",
                percentile(stats.corner_error_px, 0.5), percentile(stats.corner_error_px, 0.9));
  if (!stats.total_ms.empty())
    std::printf("  front end ms    p50 %.2f  p95 %.2f\n", percentile(stats.total_ms, 0.5),
                percentile(stats.total_ms, 0.95));
  for (const auto& [reason, count] : stats.misses) std::printf("  missed: %-60s %d\n", reason.c_str(), count);
  for (const auto& [reason, count] : stats.false_completes)
    std::printf("  false complete: %-52s %d\n", reason.c_str(), count);
  for (const auto& [reason, count] : stats.partial_whole)
    std::printf("  whole top partial: %-70s %d\n", reason.c_str(), count);
}

// ---------------------------------------------------------------- mOSD

using test::catalogueTopOf;

struct MosdStats
{
  int whole_tops = 0, found = 0, found_complete = 0, candidates = 0, complete = 0, false_complete = 0;
  std::vector<double> total_ms;
  std::vector<std::string> notes;
};

void scoreMosd(const test::MosdScene& scene, const test::MosdTruth& truth, const BrickCatalogue& catalogue,
               const FrontEndResult& result, MosdStats& stats)
{
  stats.total_ms.push_back(result.timings.total_ms);
  std::map<int, const test::MosdObject*> objects;
  for (const auto& object : truth.objects) objects[object.id] = &object;
  std::map<int, bool> found, found_complete;
  for (const BrickCandidate& candidate : result.candidates)
  {
    ++stats.candidates;
    std::map<int, int> votes;
    for (const int pixel : candidate.pixel_indices)
    {
      const int v = pixel / scene.frame.width_px(), u = pixel % scene.frame.width_px();
      if (truth.top.at<std::uint8_t>(v, u)) ++votes[truth.object.at<int>(v, u)];
    }
    int best = 0, best_votes = 0;
    for (const auto& [id, count] : votes)
      if (count > best_votes)
      {
        best = id;
        best_votes = count;
      }
    const double share = candidate.pixel_indices.empty() ? 0.0 : static_cast<double>(best_votes) / candidate.pixel_indices.size();
    const test::MosdObject* object = best > 0 ? objects[best] : nullptr;
    const BrickType* top_type = object ? catalogueTopOf(*object, catalogue) : nullptr;
    const BrickType* claimed = catalogue.find(candidate.type_name);
    const bool same_top = top_type && claimed && std::abs(top_type->length_m - claimed->length_m) <= 0.015 &&
                          std::abs(top_type->width_m - claimed->width_m) <= 0.015;
    if (share >= 0.5 && same_top)
    {
      found[best] = true;
      found_complete[best] = found_complete[best] || candidate.complete;
    }
    if (!candidate.complete) continue;
    ++stats.complete;
    if (std::getenv("BENCH_VERBOSE"))
      std::fprintf(stderr, "%s complete %s %.3f x %.3f on box %d (share %.2f, its top %.3f x %.3f, height %.3f)\n",
                   scene.name.c_str(), candidate.type_name.c_str(), candidate.length_m, candidate.width_m, best, share,
                   object ? object->top_length_m : 0.0, object ? object->top_width_m : 0.0,
                   object ? object->height_m : 0.0);
    // Complete means the whole top: most of the candidate on one box's top,
    // and most of that top in the candidate.
    const double coverage = object && object->top_pixels > 0 ? static_cast<double>(best_votes) / object->top_pixels : 0.0;
    if (share < 0.7 || !object || coverage < 0.7)
    {
      ++stats.false_complete;
      std::ostringstream note;
      note.precision(3);
      note << scene.name << ": complete " << candidate.type_name << " " << candidate.length_m << " x " << candidate.width_m
           << " m is " << share << " on box " << best << "'s top and covers " << coverage << " of it";
      stats.notes.push_back(note.str());
    }
  }
  for (const auto& object : truth.objects)
  {
    if (!catalogueTopOf(object, catalogue)) continue;
    ++stats.whole_tops;
    if (found[object.id])
    {
      ++stats.found;
      stats.found_complete += found_complete[object.id] ? 1 : 0;
      continue;
    }
    std::ostringstream note;
    note.precision(3);
    note << scene.name << ": box " << object.id << " top " << object.top_length_m << " x " << object.top_width_m
         << " m not found";
    // The smallest rejection over most of its top, if any.
    const Rejection* nearest = nullptr;
    for (const Rejection& rejection : result.rejections)
    {
      int inside = 0;
      const cv::Rect& box = rejection.bounding_box_px;
      for (int v = box.y; v < box.br().y; ++v)
        for (int u = box.x; u < box.br().x; ++u)
          inside += truth.top.at<std::uint8_t>(v, u) && truth.object.at<int>(v, u) == object.id;
      if (inside * 2 > object.top_pixels && (!nearest || box.area() < nearest->bounding_box_px.area()))
        nearest = &rejection;
    }
    if (nearest) note << ": " << nearest->reason;
    for (const BrickCandidate& candidate : result.candidates)
      if (candidate.bounding_box_px.contains(cv::Point(static_cast<int>(candidate.centroid_px.x()),
                                                       static_cast<int>(candidate.centroid_px.y()))) &&
          truth.object.at<int>(static_cast<int>(candidate.centroid_px.y()), static_cast<int>(candidate.centroid_px.x())) ==
              object.id)
        note << " [candidate " << candidate.type_name << " " << candidate.length_m << " x " << candidate.width_m << "]";
    stats.notes.push_back(note.str());
  }
}

/// The scene with each segment outlined in its own colour, then the
/// candidates (green) and rejections (red) over it.
void writeOverlay(const std::string& directory, const std::string& name, const RgbdFrame& frame,
                  const std::vector<Segment>& segments, const FrontEndResult& result, const std::string& mode)
{
  cv::Mat image = drawCandidateOverlay(frame.rgb, result);
  for (std::size_t k = 0; k < segments.size(); ++k)
  {
    const cv::Scalar colour((53 * k) % 256, (101 * k + 80) % 256, (197 * k + 160) % 256);
    std::vector<std::vector<cv::Point>> outlines = allOutlines(segments[k].mask, segments[k].bounding_box_px.tl());
    cv::drawContours(image, outlines, -1, colour, 1);
  }
  for (const BrickCandidate& candidate : result.candidates)
    for (int k = 0; k < 4; ++k)
    {
      const Eigen::Vector2d middle = 0.5 * (candidate.corners_px[k] + candidate.corners_px[(k + 1) % 4]);
      cv::putText(image, toString(candidate.edge_kinds[k]).substr(0, 4), cv::Point(middle.x(), middle.y()),
                  cv::FONT_HERSHEY_PLAIN, 0.8, cv::Scalar(255, 255, 0), 1);
    }
  cv::Mat bgr;
  cv::cvtColor(image, bgr, cv::COLOR_RGB2BGR);
  cv::imwrite(directory + "/" + name + "_" + mode + ".png", bgr);
}

int measureMosd(const Options& options)
{
  std::printf("scene   box  pixels  top px  top length x width [m]  tilt [deg]  height [m]  top above table [m]  "
              "occluded\n");
  for (int index = 0; index < 25; ++index)
  {
    const auto scene = test::loadMosdScene(options.mosd_dir, index);
    if (!scene) continue;
    const test::MosdTruth truth = test::analyseMosdScene(*scene);
    for (const auto& object : truth.objects)
      std::printf("%-7s %3d  %6d  %6d  %.3f x %.3f            %5.1f       %.3f       %.3f                %s\n",
                  scene->name.c_str(), object.id, object.pixels, object.top_pixels, object.top_length_m,
                  object.top_width_m, object.top_tilt_deg, object.height_m, object.top_above_table_m,
                  object.top_occluded ? "yes" : "no");
  }
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  const Options options = parseOptions(argc, argv);
  if (options.measure_mosd) return measureMosd(options);

  std::vector<SegmentationMode> modes;
  for (const std::string& name : options.modes) modes.push_back(parseSegmentationMode(name));

  // 1. Touching rows.
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  PinholeCamera vga;
  vga.width_px = 640;
  vga.height_px = 480;
  vga.fx_px = vga.fy_px = 615.0;
  vga.cx_px = 319.5;
  vga.cy_px = 239.5;
  const std::vector<std::pair<std::string, PinholeCamera>> cameras = {{"1280x720", PinholeCamera::d415Color1280x720()},
                                                                     {"640x480", vga}};
  std::map<std::string, Stats> touching;
  for (int i = 0; i < options.frames; ++i)
  {
    // BENCH_ONLY_FRAME=i: just that frame (with BRICK_POSE_DEBUG_* output).
    if (std::getenv("BENCH_ONLY_FRAME") && std::atoi(std::getenv("BENCH_ONLY_FRAME")) != i) continue;
    const std::uint64_t frame_seed = options.seed * 1000003ULL + static_cast<std::uint64_t>(i);
    std::string layout;
    const sim::Scene scene = touchingScene(catalogue, frame_seed, layout);
    const auto& [resolution, camera] = cameras[static_cast<std::size_t>(i % 2)];
    sim::SensorModel sensor;
    sim::SyntheticFrame synthetic = sim::SyntheticRig(camera, sensor).render(scene, frame_seed);
    const cv::Mat depth_mm = stereoWindowDepth(synthetic.depth_mm);
    FrameHeader header;
    header.stamp_ns = i;
    header.frame_id = "camera_color_optical_frame";
    const RgbdFrame frame = makeRgbdFrame(synthetic.rgb, depth_mm, camera, header);
    for (const SegmentationMode mode : modes)
    {
      FrontEndParams params;
      params.mode = mode;
      const FrontEnd front_end(catalogue, params);
      const FrontEndResult result = front_end.process(frame);
      Stats& all = touching[toString(mode) + " all"];
      const int bad_before = all.truths - all.found + all.false_complete;
      scoreSynthetic(result, synthetic, touching[toString(mode) + " " + resolution], layout);
      scoreSynthetic(result, synthetic, all, layout + ", frame " + std::to_string(i));
      if (!options.overlay_dir.empty() && all.truths - all.found + all.false_complete > bad_before)
        writeOverlay(options.overlay_dir, "touching" + std::to_string(i), frame, front_end.segment(frame), result,
                     toString(mode));
    }
  }

  // bench_frontend's rig frames (same seeds), hsv: misses and overlays.
  if (options.rig_frames > 0)
  {
    std::vector<sim::SceneGenerator> generators;
    for (const sim::SceneKind kind :
         {sim::SceneKind::kSingle, sim::SceneKind::kOrganisedPile, sim::SceneKind::kUnorganisedPile})
    {
      sim::SceneParams params;
      params.kind = kind;
      params.min_distance_m = 0.5;
      params.max_distance_m = 2.0;
      generators.emplace_back(catalogue, params);
    }
    const std::vector<sim::Lighting> lightings = {sim::Lighting::kNormal, sim::Lighting::kSunlight,
                                                  sim::Lighting::kLowLight};
    const PinholeCamera camera = PinholeCamera::d415Color1280x720();
    const FrontEnd front_end(catalogue, FrontEndParams());
    Stats rig;
    for (int i = 0; i < options.rig_frames; ++i)
    {
      const std::uint64_t frame_seed = 1 * 1000003ULL + static_cast<std::uint64_t>(i);
      const int kind_index = i % 4 == 3 ? 2 : (i % 4 == 2 ? 1 : 0);
      const sim::Scene scene = generators[static_cast<std::size_t>(kind_index)].generate(frame_seed);
      sim::SensorModel sensor;
      sensor.lighting = lightings[static_cast<std::size_t>((i / 4) % 3)];
      const sim::SyntheticFrame synthetic = sim::SyntheticRig(camera, sensor).render(scene, frame_seed);
      FrameHeader header;
      header.stamp_ns = i;
      const RgbdFrame frame = makeRgbdFrame(synthetic.rgb, synthetic.depth_mm, camera, header);
      const FrontEndResult result = front_end.process(frame);
      const int misses_before = rig.truths - rig.found;
      scoreSynthetic(result, synthetic, rig, "rig frame " + std::to_string(i));
      if (!options.overlay_dir.empty() && rig.truths - rig.found > misses_before)
      {
        cv::Mat bgr;
        cv::cvtColor(drawCandidateOverlay(frame.rgb, result), bgr, cv::COLOR_RGB2BGR);
        cv::imwrite(options.overlay_dir + "/rig" + std::to_string(i) + ".png", bgr);
      }
    }
    printStats("rig frames, hsv", rig);
  }

  // 2. mOSD.
  std::map<std::string, MosdStats> mosd;
  bool mosd_ran = false;
  try
  {
    const BrickCatalogue boxes = BrickCatalogue::fromYamlFile(options.mosd_catalogue);
    for (int index = 0; index < 25; ++index)
    {
      const auto scene = test::loadMosdScene(options.mosd_dir, index);
      if (!scene) continue;
      mosd_ran = true;
      const test::MosdTruth truth = test::analyseMosdScene(*scene);
      {
        // The ROI stage alone, on the faces the labels show.
        const FrontEnd front_end(boxes, FrontEndParams());
        FrontEndResult result;
        const std::vector<Segment> faces = test::labelledFaceSegments(*scene, truth);
        front_end.filterSegments(scene->frame, faces, result);
        scoreMosd(*scene, truth, boxes, result, mosd["labelled faces"]);
        if (!options.overlay_dir.empty())
          writeOverlay(options.overlay_dir, scene->name, scene->frame, faces, result, "labelled");
      }
      for (const SegmentationMode mode : modes)
      {
        FrontEndParams params;
        params.mode = mode;
        const FrontEnd front_end(boxes, params);
        const FrontEndResult result = front_end.process(scene->frame);
        scoreMosd(*scene, truth, boxes, result, mosd[toString(mode)]);
        if (!options.overlay_dir.empty())
          writeOverlay(options.overlay_dir, scene->name, scene->frame, front_end.segment(scene->frame), result,
                       toString(mode));
      }
    }
  }
  catch (const std::exception& error)
  {
    std::printf("mOSD skipped: %s\n", error.what());
  }

  std::printf("bench_touching: %d touching-row frames, seed %llu, load average (1 min) %.2f on 2 cores\n", options.frames,
              static_cast<unsigned long long>(options.seed), loadAverage());
  for (const auto& [name, stats] : touching) printStats("touching rows, " + name, stats);
  std::ostringstream json;
  json.precision(6);
  json << "{\"frames\": " << options.frames << ", \"seed\": " << options.seed;
  for (const SegmentationMode mode : modes)
  {
    const Stats& stats = touching[toString(mode) + " all"];
    json << ", \"" << toString(mode) << "_touching_recall\": " << stats.recall() << ", \"" << toString(mode)
         << "_touching_false_complete\": " << stats.false_complete;
  }
  std::vector<std::string> mosd_runs = {"labelled faces"};
  for (const SegmentationMode mode : modes) mosd_runs.push_back(toString(mode));
  if (mosd_ran)
    for (const std::string& run : mosd_runs)
    {
      const MosdStats& stats = mosd[run];
      std::printf("\n== mOSD learn0-24, %s ==\n", run.c_str());
      std::printf("  whole catalogue tops found  %d / %d  (complete %d)\n", stats.found, stats.whole_tops,
                  stats.found_complete);
      std::printf("  candidates %d, complete %d, false complete %d\n", stats.candidates, stats.complete,
                  stats.false_complete);
      if (!stats.total_ms.empty())
        std::printf("  front end ms p50 %.1f  p95 %.1f\n", percentile(stats.total_ms, 0.5),
                    percentile(stats.total_ms, 0.95));
      for (const std::string& note : stats.notes) std::printf("  %s\n", note.c_str());
      std::string key = run;
      std::replace(key.begin(), key.end(), ' ', '_');
      json << ", \"" << key << "_mosd_recall\": "
           << (stats.whole_tops ? static_cast<double>(stats.found) / stats.whole_tops : 1.0) << ", \"" << key
           << "_mosd_false_complete\": " << stats.false_complete;
    }
  json << ", \"load_average_1min\": " << loadAverage() << "}";
  std::printf("%s\n", json.str().c_str());
  return 0;
}
