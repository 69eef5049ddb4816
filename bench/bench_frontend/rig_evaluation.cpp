#include "bench_frontend/rig_evaluation.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "brick_pose/eval/match_overlay.h"
#include "brick_pose/eval/rig_truth.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/sim/synthetic_rig.h"
#include "common/run_environment.h"

namespace brick_pose
{
namespace frontend_bench
{
namespace
{
struct RenderedFrame
{
  sim::Scene scene;
  sim::SyntheticFrame synthetic;
  Eigen::Vector3d up_in_camera = Eigen::Vector3d::UnitZ();
  /// The ground the scene stands on (world z = 0) in the camera frame.
  Eigen::Vector4d ground_in_camera = Eigen::Vector4d::Zero();
};

RenderedFrame render(const sim::SceneGenerator& generator, const SceneClass& scene_class, const FrameSpec& spec,
                     const PinholeCamera& camera)
{
  RenderedFrame frame;
  frame.scene = generator.generate(spec.seed);
  frame.synthetic =
      sim::SyntheticRig(camera, sensorFor(scene_class, spec.lighting)).render(frame.scene, spec.seed);
  frame.up_in_camera = frame.scene.world_T_camera.linear().transpose() * Eigen::Vector3d::UnitZ();
  // A camera-frame point p is at world height up . p + (camera's height).
  frame.ground_in_camera << frame.up_in_camera, frame.scene.world_T_camera.translation().z();
  return frame;
}

/// The segments of a frame, each in a colour of its own over black, and
/// outlined: for reading by eye which faces a segment merged.
cv::Mat drawSegments(const std::vector<Segment>& segments, const cv::Size& size)
{
  cv::Mat picture(size, CV_8UC3, cv::Scalar::all(0));
  for (std::size_t s = 0; s < segments.size(); ++s)
  {
    // Well spread hues from a multiplicative hash of the index.
    const unsigned hash = static_cast<unsigned>(s + 1) * 2654435761u;
    const cv::Scalar colour(64 + (hash & 0x7F), 64 + ((hash >> 8) & 0x7F), 64 + ((hash >> 16) & 0x7F));
    const Segment& segment = segments[s];
    cv::Mat region = picture(segment.bounding_box_px);
    region.setTo(colour, segment.mask);
    std::vector<std::vector<cv::Point>> outlines;
    cv::findContours(segment.mask.clone(), outlines, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    cv::drawContours(region, outlines, -1, cv::Scalar::all(255), 1);
  }
  return picture;
}

RgbdFrame toRgbd(const RenderedFrame& frame, const PinholeCamera& camera, int index)
{
  FrameHeader header;
  header.stamp_ns = static_cast<std::int64_t>(index) * 33333333;
  header.frame_id = "camera_color_optical_frame";
  return makeRgbdFrame(frame.synthetic.rgb, frame.synthetic.depth_mm, camera, header);
}
/// Depth as grey, near light, over the frame's own range (2nd to 98th
/// percentile), holes red: steps and smoothing read by eye.
cv::Mat drawDepth(const cv::Mat& depth_m)
{
  std::vector<float> values;
  for (int v = 0; v < depth_m.rows; ++v)
    for (int u = 0; u < depth_m.cols; ++u)
      if (const float d = depth_m.at<float>(v, u); std::isfinite(d) && d > 0.0f) values.push_back(d);
  cv::Mat picture(depth_m.size(), CV_8UC3, cv::Scalar(0, 0, 255));
  if (values.empty()) return picture;
  std::sort(values.begin(), values.end());
  const float near_m = values[values.size() / 50], far_m = values[values.size() - 1 - values.size() / 50];
  const float scale = 255.0f / std::max(1e-3f, far_m - near_m);
  for (int v = 0; v < depth_m.rows; ++v)
    for (int u = 0; u < depth_m.cols; ++u)
      if (const float d = depth_m.at<float>(v, u); std::isfinite(d) && d > 0.0f)
      {
        const auto grey = static_cast<unsigned char>(std::clamp(255.0f - (d - near_m) * scale, 0.0f, 255.0f));
        picture.at<cv::Vec3b>(v, u) = cv::Vec3b(grey, grey, grey);
      }
  return picture;
}
}  // namespace

std::vector<BrickCatalogue> classCatalogues(const std::vector<SceneClass>& classes, const Options& options)
{
  const BrickCatalogue bricks = BrickCatalogue::mbzirc2020();
  std::optional<BrickCatalogue> boxes;
  std::vector<BrickCatalogue> catalogues;
  for (const SceneClass& scene_class : classes)
  {
    if (scene_class.catalogue == ClassCatalogue::kBricks)
    {
      catalogues.push_back(bricks);
      continue;
    }
    if (!boxes)
      boxes = BrickCatalogue::fromYamlFile(options.box_catalogue.empty()
                                               ? bench::sourceDirectory() + "/config/boxes.yaml"
                                               : options.box_catalogue);
    catalogues.push_back(*boxes);
  }
  return catalogues;
}

RigResults runRig(const std::vector<BrickCatalogue>& catalogues, const std::vector<SceneClass>& classes,
                  const std::vector<ModeSpec>& modes, const std::vector<Resolution>& resolutions,
                  const std::vector<FrameSpec>& plan, const Options& options)
{
  std::vector<std::unique_ptr<sim::SceneGenerator>> generators(classes.size());
  for (std::size_t c = 0; c < classes.size(); ++c)
    if (classes[c].kind)
      generators[c] = std::make_unique<sim::SceneGenerator>(catalogues[c], sceneParamsFor(classes[c]));
  const eval::MatchParams match_params;

  RigResults results;
  for (std::size_t c = 0; c < classes.size(); ++c)
    for (std::size_t m = 0; m < modes.size(); ++m)
    {
      const std::string reason = modeNotApplicable(modes[m], catalogues[c]);
      if (modes[m].mode && !reason.empty()) results.not_applicable[{c, m}] = reason;
    }
  for (std::size_t m = 0; m < modes.size(); ++m)
  {
    if (!modes[m].mode || !allowedBy(options.only_modes, modes[m].name)) continue;
    for (std::size_t r = 0; r < resolutions.size(); ++r)
    {
      if (!allowedBy(options.only_resolutions, resolutions[r].label)) continue;
      const PinholeCamera& camera = resolutions[r].camera;
      for (std::size_t i = 0; i < plan.size(); ++i)
      {
        const FrameSpec& spec = plan[i];
        if (results.not_applicable.count({spec.scene_class, m})) continue;
        if (!allowedBy(options.only_kinds, classes[spec.scene_class].rig_kind)) continue;
        if (options.only_frame >= 0 && static_cast<int>(i) != options.only_frame) continue;
        const RenderedFrame rendered = render(*generators[spec.scene_class], classes[spec.scene_class], spec, camera);
        const auto build_start = std::chrono::steady_clock::now();
        const RgbdFrame frame = toRgbd(rendered, camera, static_cast<int>(i));
        if (m == 0 && resolutions[r].legacy) results.frame_build_ms.push_back(millisecondsSince(build_start));
        // A front end per frame: the up direction is the frame's. Building
        // one is cheap next to processing a frame.
        const FrontEnd front_end(catalogues[spec.scene_class], frontEndParamsFor(modes[m], rendered.up_in_camera,
                                                                                   rendered.ground_in_camera,
                                                                                   options.measured_corners));
        const double cpu_start = bench::processCpuMs();
        const FrontEndResult result = front_end.process(frame);
        const double cpu_ms = bench::processCpuMs() - cpu_start;
        for (int extra = 0; extra < options.repeat; ++extra) front_end.process(frame);
        const eval::SceneTruth truth = eval::rigSceneTruth(rendered.synthetic, rendered.up_in_camera);
        const CellKey key{spec.scene_class, m, r};
        const std::string name = classes[spec.scene_class].rig_kind + " frame " + std::to_string(i) + " " +
                                 modes[m].name + " " + resolutions[r].label;
        CellStats frame_stats;
        recordFrame(result, cpu_ms, truth, camera, match_params, options.verbose, name, frame_stats);
        results.cells[key].merge(frame_stats);
        if (spec.legacy) results.legacy_cells[key].merge(frame_stats);
        // Pictures of a replayed cell only: the whole run would write thousands.
        if (!options.overlay_dir.empty() && !options.only_kinds.empty())
        {
          const eval::FrameMatch match = eval::matchCandidates(result.candidates, truth, camera, match_params);
          std::string file = name;
          std::replace(file.begin(), file.end(), ' ', '_');
          cv::imwrite(options.overlay_dir + "/" + file + ".png",
                      eval::drawMatchOverlay(frame.rgb, truth, result.candidates, match, camera));
          // The frame as the front end saw it, for reading seams by eye.
          cv::Mat bgr;
          cv::cvtColor(frame.rgb, bgr, cv::COLOR_RGB2BGR);
          cv::imwrite(options.overlay_dir + "/" + file + "_rgb.png", bgr);
          cv::imwrite(options.overlay_dir + "/" + file + "_segments.png",
                      drawSegments(front_end.segment(frame), frame.rgb.size()));
          cv::imwrite(options.overlay_dir + "/" + file + "_depth.png", drawDepth(frame.depth_m));
        }
      }
    }
  }
  return results;
}
}  // namespace frontend_bench
}  // namespace brick_pose
