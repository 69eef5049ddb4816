// Benchmark of the colour-free front end (segmentation to candidates) per
// resolution on seeded synthetic D415 frames, and of the colour-free
// segmentation on the real Kinect scenes of mOSD (test/data/mosd_learn).
//
//   bench_segmentation [--frames N] [--seed S] [--mode colour_free|region_growing]
//                      [--resolutions 1280x720,640x480] [--cell-px N] [--threads N]
//                      [--mosd DIR | --no-mosd] [--dump DIR]
//
// Rig frames cycle through single bricks and organised / unorganised piles
// (gapped: the rig has no touching scenes yet), normal / sunlight / low-light,
// 0.5-2 m, as bench_frontend does. 640x480 is the 1280x720 camera scaled by
// one half (fx 460) with the image made 480 rows tall. Gravity is known (as
// on a robot through tf), so side faces are not taken for tops.
//
// Per resolution it reports FrontEnd::process time (wall and process CPU,
// p50/p95), and
//  - recall: top faces >= 60% visible found as a candidate of the right type
//    (the definition of bench_frontend);
//  - whole-top recall: the same for top faces >= 95% visible;
//  - whole tops segmented: one segment covers >= 90% of the top and leaks
//    onto side faces or the ground by <= 5% of its area (other tops of the
//    same height may share the segment: the ROI stage splits touching
//    faces) - the segmentation alone;
//  - corner error of the candidates on whole tops (px).
// On mOSD (no face ground truth) it reports the segmentation time per frame,
// how much of the table one segment covers, how many segments lie on each box
// (>= 90% of their pixels on it) and how many segments mix objects.

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "brick_pose/common/statistics.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/segmentation/colour_free_segmenter.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"
#include "../test/unit/png_image.h"  // PNG through VTK: the build links no OpenCV imgcodecs

using namespace brick_pose;

namespace
{
/// The repository's mOSD copy, found from this file's path (the build
/// compiles it in place).
std::string defaultMosdDir()
{
#ifdef BRICK_POSE_SOURCE_DIR
  return std::string(BRICK_POSE_SOURCE_DIR) + "/test/data/mosd_learn";
#else
  const std::string source = __FILE__;
  const std::size_t bench = source.rfind("bench/");
  return (bench == std::string::npos ? std::string() : source.substr(0, bench)) + "test/data/mosd_learn";
#endif
}

struct Options
{
  int frames = 100;
  std::uint64_t seed = 1;
  std::string mode = "colour_free";
  std::vector<cv::Size> resolutions = {{1280, 720}, {640, 480}};
  int cell_px = 0;  // 0: the default
  int threads = -1;
  std::string mosd_dir = defaultMosdDir();
  std::string dump_dir;
};

[[noreturn]] void usage(int code)
{
  std::cerr << "usage: bench_segmentation [--frames N] [--seed S] [--mode colour_free|region_growing]\n"
               "                          [--resolutions WxH,WxH] [--cell-px N] [--threads N]\n"
               "                          [--mosd DIR | --no-mosd] [--dump DIR]\n";
  std::exit(code);
}

Options parseOptions(int argc, char** argv)
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") usage(0);
    if (arg == "--no-mosd")
    {
      options.mosd_dir.clear();
      continue;
    }
    if (i + 1 >= argc) usage(2);
    const std::string value = argv[++i];
    if (arg == "--frames") options.frames = std::max(0, std::atoi(value.c_str()));
    else if (arg == "--seed") options.seed = std::strtoull(value.c_str(), nullptr, 10);
    else if (arg == "--mode") options.mode = value;
    else if (arg == "--cell-px") options.cell_px = std::atoi(value.c_str());
    else if (arg == "--threads") options.threads = std::atoi(value.c_str());
    else if (arg == "--mosd") options.mosd_dir = value;
    else if (arg == "--dump") options.dump_dir = value;
    else if (arg == "--resolutions")
    {
      options.resolutions.clear();
      std::stringstream list(value);
      std::string item;
      while (std::getline(list, item, ','))
      {
        int w = 0, h = 0;
        if (std::sscanf(item.c_str(), "%dx%d", &w, &h) != 2 || w <= 0 || h <= 0) usage(2);
        options.resolutions.emplace_back(w, h);
      }
    }
    else usage(2);
  }
  return options;
}

double processCpuMs()
{
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return 1e3 * static_cast<double>(now.tv_sec) + 1e-6 * static_cast<double>(now.tv_nsec);
}

double loadAverage()
{
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

/// The D415 at 1280x720, or scaled to the width and cut/padded to the height.
PinholeCamera cameraFor(cv::Size size)
{
  PinholeCamera camera = PinholeCamera::d415Color1280x720().scaled(size.width / 1280.0);
  camera.cy_px += 0.5 * (size.height - camera.height_px);
  camera.height_px = size.height;
  return camera;
}

FrontEndParams frontEndParams(const Options& options, const Eigen::Vector3d& up)
{
  FrontEndParams params;
  params.mode = parseSegmentationMode(options.mode);
  if (options.cell_px > 0) params.colour_free.cell_px = options.cell_px;
  params.roi.up_direction = up;
  return params;
}

std::vector<Segment> segmentOnly(const Options& options, const RgbdFrame& frame, ColourFreeTimings* timings)
{
  ColourFreeParams params;
  if (options.cell_px > 0) params.cell_px = options.cell_px;
  return ColourFreeSegmenter(params).segment(frame, cv::Mat(), timings);
}

/// Mean over corners of the distance to the truth corners, for the best
/// cyclic correspondence (either direction).
std::vector<double> cornerErrorsPx(const BrickCandidate& candidate, const std::array<Eigen::Vector2d, 4>& truth)
{
  std::vector<double> best;
  double best_sum = 1e18;
  for (int direction : {1, -1})
    for (int shift = 0; shift < 4; ++shift)
    {
      std::vector<double> errors;
      double sum = 0.0;
      for (int k = 0; k < 4; ++k)
      {
        const int t = ((shift + direction * k) % 4 + 4) % 4;
        errors.push_back((candidate.corners_px[k] - truth[t]).norm());
        sum += errors.back();
      }
      if (sum < best_sum)
      {
        best_sum = sum;
        best = errors;
      }
    }
  return best;
}

struct RigStats
{
  int truths = 0, found = 0;              // >= 60 % visible
  int whole = 0, whole_found = 0;         // >= 95 % visible
  int whole_segmented = 0;                // one segment covers >= 90 %, leaks <= 5 %
  int candidates = 0, true_positives = 0;
  std::vector<double> total_ms, cpu_ms, segmentation_ms, roi_ms;
  std::vector<double> cells_ms, clustering_ms, refinement_ms, segments_ms, noise_mm;
  std::vector<double> corner_error_px, segment_coverage, segment_leak;
  std::map<std::string, int> misses;
  int frame = 0;  // index of the frame being evaluated
};

/// Top-face pixels of every instance (full-image masks).
std::map<int, cv::Mat> topFaceMasks(const sim::SyntheticFrame& frame)
{
  std::map<int, cv::Mat> masks;
  for (const sim::BrickTruth& truth : frame.truth)
  {
    cv::Mat is_instance, is_top;
    cv::compare(frame.instance_labels, truth.instance_id, is_instance, cv::CMP_EQ);
    cv::compare(frame.face_labels, static_cast<int>(sim::CuboidFace::kTop), is_top, cv::CMP_EQ);
    masks[truth.instance_id] = is_instance & is_top;
  }
  return masks;
}

/// How well the best segment for a top face fits it: the share of the top
/// it covers and its pixels off any top face (side faces, ground), as a
/// share of the top. Other bricks' tops may be in the segment: touching
/// tops of one height form one planar region, which the ROI stage splits.
struct TopFit
{
  double coverage = 0.0;
  double leak = 0.0;
  double iou = 0.0;
};

TopFit bestFit(const std::vector<Segment>& segments, const cv::Mat& truth_mask, const cv::Mat& all_tops)
{
  const cv::Rect truth_box = cv::boundingRect(truth_mask);
  const double truth_area = cv::countNonZero(truth_mask);
  TopFit best;
  for (const Segment& segment : segments)
  {
    if ((segment.bounding_box_px & truth_box).area() == 0) continue;
    const double shared = cv::countNonZero(segment.mask & truth_mask(segment.bounding_box_px));
    if (shared <= best.coverage * truth_area) continue;
    best.coverage = shared / truth_area;
    best.leak = (segment.area_px - cv::countNonZero(segment.mask & all_tops(segment.bounding_box_px))) / truth_area;
    best.iou = shared / (segment.area_px + truth_area - shared);
  }
  return best;
}

void evaluateRig(const FrontEndResult& result, const std::vector<Segment>& segments, const sim::SyntheticFrame& frame,
                 const PinholeCamera& camera, RigStats& stats)
{
  const auto* instances = frame.instance_labels.ptr<std::uint16_t>(0);
  const auto* faces = frame.face_labels.ptr<std::uint8_t>(0);
  std::vector<bool> taken(frame.truth.size() + 1, false);
  for (const BrickCandidate& candidate : result.candidates)
  {
    ++stats.candidates;
    std::map<int, int> votes;
    for (const int pixel : candidate.pixel_indices)
      if (faces[pixel] == static_cast<std::uint8_t>(sim::CuboidFace::kTop)) ++votes[instances[pixel]];
    int instance = 0, best_votes = 0;
    for (const auto& [id, count] : votes)
      if (count > best_votes)
      {
        instance = id;
        best_votes = count;
      }
    const double share = candidate.pixel_indices.empty() ? 0.0 : double(best_votes) / candidate.pixel_indices.size();
    if (instance == 0 || share < 0.5 || taken[instance] || frame.truth[instance - 1].type != candidate.type_name)
      continue;
    taken[instance] = true;
    ++stats.true_positives;
    const sim::BrickTruth& truth = frame.truth[instance - 1];
    if (truth.visible_fraction < 0.95) continue;
    std::array<Eigen::Vector2d, 4> corners_px;
    const auto corners_m = sim::topFaceCornersInCamera(truth);
    for (int k = 0; k < 4; ++k) corners_px[k] = camera.project(corners_m[k]);
    for (const double e : cornerErrorsPx(candidate, corners_px)) stats.corner_error_px.push_back(e);
  }
  const std::map<int, cv::Mat> top_masks = topFaceMasks(frame);
  cv::Mat all_tops;
  cv::compare(frame.face_labels, static_cast<int>(sim::CuboidFace::kTop), all_tops, cv::CMP_EQ);
  for (const sim::BrickTruth& truth : frame.truth)
  {
    if (truth.visible_fraction < 0.6) continue;
    ++stats.truths;
    if (taken[truth.instance_id]) ++stats.found;
    if (truth.visible_fraction < 0.95) continue;
    ++stats.whole;
    if (taken[truth.instance_id]) ++stats.whole_found;
    const TopFit fit = bestFit(segments, top_masks.at(truth.instance_id), all_tops);
    const double iou = fit.iou;
    stats.segment_coverage.push_back(fit.coverage);
    stats.segment_leak.push_back(fit.leak);
    if (fit.coverage >= 0.9 && fit.leak <= 0.05) ++stats.whole_segmented;
    else if (std::getenv("BENCH_VERBOSE"))
      std::fprintf(stderr, "poor segment frame %d instance %d %s z %.2f: covers %.3f leaks %.3f (found %d)\n", stats.frame,
                   truth.instance_id, truth.type.c_str(), truth.camera_T_brick.translation().z(), fit.coverage, fit.leak,
                   taken[truth.instance_id] ? 1 : 0);
    if (taken[truth.instance_id]) continue;
    std::string reason = fit.coverage >= 0.9 && fit.leak <= 0.05
                             ? "segmented, rejected: "
                             : "poorly segmented (iou " + std::to_string(iou).substr(0, 4) + "): ";
    for (const Rejection& rejection : result.rejections)
    {
      const cv::Rect overlap = rejection.bounding_box_px & cv::boundingRect(top_masks.at(truth.instance_id));
      if (overlap.area() * 2 > rejection.bounding_box_px.area() / 2)
      {
        reason += rejection.reason.substr(0, rejection.reason.find_first_of("0123456789"));
        break;
      }
    }
    if (std::getenv("BENCH_VERBOSE"))
      std::fprintf(stderr, "miss frame %d instance %d %s vis %.2f z %.2f: %s\n", stats.frame, truth.instance_id,
                   truth.type.c_str(), truth.visible_fraction, truth.camera_T_brick.translation().z(), reason.c_str());
    ++stats.misses[reason.substr(0, 60)];
  }
}

/// A false-colour picture of segments over the grey image, for inspection.
void dumpSegments(const std::string& path, const cv::Mat& rgb, const std::vector<Segment>& segments)
{
  cv::Mat grey, picture;
  cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
  cv::cvtColor(grey, picture, cv::COLOR_GRAY2RGB);
  picture *= 0.5;
  cv::RNG rng(7);
  for (const Segment& segment : segments)
  {
    const cv::Scalar colour(rng.uniform(60, 255), rng.uniform(60, 255), rng.uniform(60, 255));
    cv::Mat region = picture(segment.bounding_box_px);
    region.setTo(colour, segment.mask);
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(segment.mask.clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE,
                     segment.bounding_box_px.tl());
    cv::drawContours(picture, contours, -1, cv::Scalar(0, 0, 0), 1);
  }
  test::writePng(path, picture);
}

void printRig(const Options& options, cv::Size size, const RigStats& s)
{
  auto ratio = [](int a, int b) { return b ? double(a) / b : 1.0; };
  std::printf("\n== %s %dx%d (%d frames) ==\n", options.mode.c_str(), size.width, size.height, options.frames);
  std::printf("  recall (>= 60%% visible)   %.4f  (%d / %d)\n", ratio(s.found, s.truths), s.found, s.truths);
  std::printf("  whole-top recall (>= 95%%) %.4f  (%d / %d)\n", ratio(s.whole_found, s.whole), s.whole_found, s.whole);
  std::printf("  precision                 %.4f  (%d / %d candidates)\n", ratio(s.true_positives, s.candidates),
              s.true_positives, s.candidates);
  if (options.mode == "colour_free")
  {
    std::printf("  whole tops segmented (one segment covers >= 90%%, leaks <= 5%%) %.4f  (%d / %d)\n",
                ratio(s.whole_segmented, s.whole), s.whole_segmented, s.whole);
    std::printf("    coverage median %.4f p10 %.4f; leak onto side faces / ground median %.4f p90 %.4f\n",
                percentile(s.segment_coverage, 0.5), percentile(s.segment_coverage, 0.1), percentile(s.segment_leak, 0.5),
                percentile(s.segment_leak, 0.9));
  }
  std::printf("  corner error px (whole tops)  median %.3f  p90 %.3f  (n = %zu)\n", percentile(s.corner_error_px, 0.5),
              percentile(s.corner_error_px, 0.9), s.corner_error_px.size());
  std::printf("  front end ms  wall p50 %.2f p95 %.2f   cpu (all threads) p50 %.2f p95 %.2f\n",
              percentile(s.total_ms, 0.5), percentile(s.total_ms, 0.95), percentile(s.cpu_ms, 0.5),
              percentile(s.cpu_ms, 0.95));
  std::printf("  stages ms p50 segmentation %.2f  roi+cloud %.2f\n", percentile(s.segmentation_ms, 0.5),
              percentile(s.roi_ms, 0.5));
  if (options.mode == "colour_free")
    std::printf("  segmenter stages, cpu ms of the calling thread, p50: cells %.2f clustering %.2f refinement %.2f "
                "segments %.2f; noise at 1 m p50 %.2f mm\n",
                percentile(s.cells_ms, 0.5), percentile(s.clustering_ms, 0.5), percentile(s.refinement_ms, 0.5),
                percentile(s.segments_ms, 0.5), percentile(s.noise_mm, 0.5));
  for (const auto& [reason, count] : s.misses) std::printf("  missed whole top: %-60s %d\n", reason.c_str(), count);
}

RigStats runRig(const Options& options, cv::Size size)
{
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  const PinholeCamera camera = cameraFor(size);
  std::vector<sim::SceneGenerator> generators;
  for (const sim::SceneKind kind : {sim::SceneKind::kSingle, sim::SceneKind::kOrganisedPile, sim::SceneKind::kUnorganisedPile})
  {
    sim::SceneParams params;
    params.kind = kind;
    params.min_distance_m = 0.5;
    params.max_distance_m = 2.0;
    generators.emplace_back(catalogue, params);
  }
  const std::vector<sim::Lighting> lightings = {sim::Lighting::kNormal, sim::Lighting::kSunlight, sim::Lighting::kLowLight};
  RigStats stats;
  for (int i = 0; i < options.frames; ++i)
  {
    const std::uint64_t frame_seed = options.seed * 1000003ULL + static_cast<std::uint64_t>(i);
    const int kind_index = i % 4 == 3 ? 2 : (i % 4 == 2 ? 1 : 0);
    const sim::Scene scene = generators[kind_index].generate(frame_seed);
    sim::SensorModel sensor;
    sensor.lighting = lightings[(i / 4) % 3];
    const sim::SyntheticFrame synthetic = sim::SyntheticRig(camera, sensor).render(scene, frame_seed);
    FrameHeader header;
    header.stamp_ns = static_cast<std::int64_t>(i) * 33333333;
    const RgbdFrame frame = makeRgbdFrame(synthetic.rgb, synthetic.depth_mm, camera, header);
    const Eigen::Vector3d up = scene.world_T_camera.linear().transpose() * Eigen::Vector3d::UnitZ();
    const FrontEnd front_end(catalogue, frontEndParams(options, up));

    const double cpu_start = processCpuMs();
    const FrontEndResult result = front_end.process(frame);
    stats.cpu_ms.push_back(processCpuMs() - cpu_start);
    stats.total_ms.push_back(result.timings.total_ms);
    stats.segmentation_ms.push_back(result.timings.segmentation_ms);
    stats.roi_ms.push_back(result.timings.total_ms - result.timings.segmentation_ms);

    std::vector<Segment> segments;
    if (options.mode == "colour_free")
    {
      ColourFreeTimings timings;
      segments = segmentOnly(options, frame, &timings);
      stats.cells_ms.push_back(timings.cells_cpu_ms);
      stats.clustering_ms.push_back(timings.clustering_cpu_ms);
      stats.refinement_ms.push_back(timings.refinement_cpu_ms);
      stats.segments_ms.push_back(timings.segments_cpu_ms);
      stats.noise_mm.push_back(1e3 * timings.noise_at_1m_m);
    }
    else
      segments = front_end.segment(frame);
    stats.frame = i;
    evaluateRig(result, segments, synthetic, camera, stats);
    if (!options.dump_dir.empty() && (i < 24 || std::getenv("BENCH_DUMP_ALL")))
      dumpSegments(options.dump_dir + "/rig_" + std::to_string(size.width) + "_" + std::to_string(i) + ".png",
                   synthetic.rgb, segments);
  }
  return stats;
}

/// Intrinsics of a mOSD scene from its camera.json.
PinholeCamera readMosdCamera(const std::string& path)
{
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  const std::string json = text.str();
  auto number = [&](const std::string& key) {
    const std::size_t at = json.find("\"" + key + "\"");
    if (at == std::string::npos) throw std::runtime_error(path + ": no " + key);
    return std::strtod(json.c_str() + json.find(':', at) + 1, nullptr);
  };
  PinholeCamera camera;
  camera.width_px = static_cast<int>(number("width"));
  camera.height_px = static_cast<int>(number("height"));
  camera.fx_px = number("fx");
  camera.fy_px = number("fy");
  camera.cx_px = number("cx");
  camera.cy_px = number("cy");
  return camera;
}

void runMosd(const Options& options)
{
  std::vector<double> wall_ms, cpu_ms, front_end_ms, table_cover, noise_mm;
  int segments_total = 0, mixed = 0, on_boxes = 0, boxes = 0, boxes_with_two_faces = 0, table_one = 0, scenes = 0;
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  for (int n = 0; n < 25; ++n)
  {
    const std::string stem = options.mosd_dir + "/learn" + std::to_string(n) + "_";
    const cv::Mat rgb = test::readPng(stem + "color.png");
    const cv::Mat depth = test::readPng(stem + "depth.png");
    const cv::Mat labels = test::readPng(stem + "labels.png");
    if (rgb.empty() || depth.empty() || labels.empty()) continue;
    ++scenes;
    const RgbdFrame frame = makeRgbdFrame(rgb, depth, readMosdCamera(stem + "camera.json"), {});

    ColourFreeTimings timings;
    const double cpu_start = processCpuMs();
    const auto start = std::chrono::steady_clock::now();
    const std::vector<Segment> segments = segmentOnly(options, frame, &timings);
    wall_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    cpu_ms.push_back(processCpuMs() - cpu_start);
    noise_mm.push_back(1e3 * timings.noise_at_1m_m);
    // The whole front end too (nothing there is a catalogue brick: its time only).
    FrontEndParams params = frontEndParams(options, Eigen::Vector3d::Zero());
    front_end_ms.push_back(FrontEnd(catalogue, params).process(frame).timings.total_ms);

    // Object of a label: 0 none, 1 the table, 2.. the boxes (20-29 -> 2, 30-39 -> 3, ...).
    auto objectOf = [](int label) { return label == 0 ? 0 : (label < 10 ? 1 : label / 10); };
    std::map<int, int> object_pixels;
    for (int i = 0; i < labels.rows * labels.cols; ++i) ++object_pixels[objectOf(labels.at<std::uint16_t>(i))];
    std::map<int, int> faces_on_object;
    double best_table = 0.0;
    for (const Segment& segment : segments)
    {
      ++segments_total;
      std::map<int, int> votes;
      for (const int pixel : segment.pixel_indices) ++votes[objectOf(labels.at<std::uint16_t>(pixel))];
      int object = 0, count = 0;
      for (const auto& [id, c] : votes)
        if (c > count)
        {
          object = id;
          count = c;
        }
      const double purity = segment.pixel_indices.empty() ? 0.0 : double(count) / segment.pixel_indices.size();
      if (purity < 0.9)
      {
        ++mixed;
        continue;
      }
      if (object == 1) best_table = std::max(best_table, double(count) / object_pixels[1]);
      if (object >= 2)
      {
        ++faces_on_object[object];
        ++on_boxes;
      }
    }
    table_cover.push_back(best_table);
    if (best_table >= 0.8) ++table_one;
    for (const auto& [object, pixels] : object_pixels)
    {
      if (object < 2 || pixels < 2000) continue;
      ++boxes;
      if (faces_on_object[object] >= 2) ++boxes_with_two_faces;
    }
    if (!options.dump_dir.empty())
      dumpSegments(options.dump_dir + "/mosd_learn" + std::to_string(n) + ".png", rgb, segments);
  }
  if (scenes == 0)
  {
    std::printf("\n== mOSD: no scenes found in %s ==\n", options.mosd_dir.c_str());
    return;
  }
  std::printf("\n== mOSD learn, %d real Kinect scenes 640x480 (colour-free segmentation) ==\n", scenes);
  std::printf("  segmentation ms  wall p50 %.2f p95 %.2f max %.2f   cpu p50 %.2f\n", percentile(wall_ms, 0.5),
              percentile(wall_ms, 0.95), percentile(wall_ms, 1.0), percentile(cpu_ms, 0.5));
  std::printf("  front end (segmentation to candidates) ms  p50 %.2f p95 %.2f\n", percentile(front_end_ms, 0.5),
              percentile(front_end_ms, 0.95));
  std::printf("  noise at 1 m p50 %.2f mm\n", percentile(noise_mm, 0.5));
  std::printf("  table: one segment covers >= 80%% of it in %d / %d scenes (cover median %.3f, min %.3f)\n", table_one,
              scenes, percentile(table_cover, 0.5), percentile(table_cover, 0.0));
  std::printf("  segments %d: %d on one box, %d mixing objects (< 90%% on one)\n", segments_total, on_boxes, mixed);
  std::printf("  boxes (>= 2000 px) with >= 2 face segments: %d / %d\n", boxes_with_two_faces, boxes);
}
}  // namespace

int main(int argc, char** argv)
{
  const Options options = parseOptions(argc, argv);
  if (options.threads >= 0) cv::setNumThreads(options.threads);
  std::printf("bench_segmentation: mode %s, seed %llu, OpenCV threads %d\n", options.mode.c_str(),
              static_cast<unsigned long long>(options.seed), cv::getNumThreads());
  std::ostringstream json;
  json << "{\"mode\": \"" << options.mode << "\", \"frames\": " << options.frames;
  if (options.frames > 0)
    for (const cv::Size& size : options.resolutions)
    {
      const RigStats stats = runRig(options, size);
      printRig(options, size, stats);
      const std::string key = std::to_string(size.width) + "x" + std::to_string(size.height);
      json << ", \"p50_ms_" << key << "\": " << percentile(stats.total_ms, 0.5) << ", \"p95_ms_" << key
           << "\": " << percentile(stats.total_ms, 0.95) << ", \"whole_top_recall_" << key
           << "\": " << (stats.whole ? double(stats.whole_found) / stats.whole : 1.0);
    }
  if (!options.mosd_dir.empty() && options.mode == "colour_free") runMosd(options);
  std::printf("load average (1 min) at the end: %.2f on 2 cores\n", loadAverage());
  json << ", \"load_average_1min\": " << loadAverage() << "}";
  std::printf("%s\n", json.str().c_str());
  return 0;
}
