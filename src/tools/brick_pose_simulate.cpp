// brick_pose_simulate: writes frames of the synthetic D415 to a rosbag with
// realsense2_camera's topics (align_depth:=true), the ground truth and tf.
//
//   brick_pose_simulate --output scene.bag [--frames 30] [--rate 15]
//                       [--camera-ns /camera] [--new-scene-every 0]
//                       [--scene unorganised_pile --seed 4 --lighting sunlight ...]
//
// Every rig parameter of the SyntheticCamera nodelet is accepted as --NAME VALUE.

#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <string>

#include <rosbag/bag.h>
#include <tf2_msgs/TFMessage.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/sim_ros/synthetic_frame_messages.h"
#include "brick_pose/sim/rig_config.h"

namespace
{
using brick_pose::ConfigError;

struct CommandLineParams
{
  std::string output;
  int frames = 30;
  double rate_hz = 15.0;
  std::string camera_ns = "/camera";
  int new_scene_every = 0;  // 0: one scene for the whole bag
  std::string frame_id = "camera_color_optical_frame";
  std::map<std::string, std::string> rig_parameters;
};

void printUsage()
{
  std::cout << "usage: brick_pose_simulate --output FILE.bag [options]\n\n"
               "  --output FILE        bag to write (required)\n"
               "  --frames N           frames to write (default 30)\n"
               "  --rate HZ            frame rate of the stamps (default 15)\n"
               "  --camera-ns NS       camera namespace of the topics (default /camera)\n"
               "  --new-scene-every K  new seeded scene every K frames (default 0: never)\n"
               "  --frame-id ID        optical frame (default camera_color_optical_frame)\n\n"
               "rig parameters (as for the SyntheticCamera nodelet):\n";
  for (const auto& [name, meaning] : brick_pose::sim::rigParameterHelp())
    std::printf("  --%-24s %s\n", name.c_str(), meaning.c_str());
}

CommandLineParams parseArguments(int argc, char** argv)
{
  CommandLineParams options;
  for (int i = 1; i < argc; ++i)
  {
    const std::string flag = argv[i];
    if (flag.rfind("--", 0) != 0) throw ConfigError("unexpected argument '" + flag + "' (options start with --)");
    if (i + 1 >= argc) throw ConfigError("option '" + flag + "' needs a value");
    const std::string name = flag.substr(2), value = argv[++i];
    if (name == "output")
      options.output = value;
    else if (name == "frames")
      options.frames = static_cast<int>(brick_pose::parseInteger("frames", value));
    else if (name == "rate")
      options.rate_hz = brick_pose::parseDouble("rate", value);
    else if (name == "camera-ns")
      options.camera_ns = value;
    else if (name == "new-scene-every")
      options.new_scene_every = static_cast<int>(brick_pose::parseInteger("new-scene-every", value));
    else if (name == "frame-id")
      options.frame_id = value;
    else
    {
      bool known = false;
      for (const auto& entry : brick_pose::sim::rigParameterHelp())
        known |= entry.first == name;
      if (!known) throw ConfigError("unknown option '--" + name + "' (see --help)");
      options.rig_parameters[name] = value;
    }
  }
  if (options.output.empty()) throw ConfigError("--output is required");
  if (options.frames < 1) throw ConfigError("--frames must be >= 1");
  if (!(options.rate_hz > 0.0)) throw ConfigError("--rate must be > 0");
  if (options.new_scene_every < 0) throw ConfigError("--new-scene-every must be >= 0");
  if (!options.camera_ns.empty() && options.camera_ns.back() == '/') options.camera_ns.pop_back();
  return options;
}

void writeFrame(rosbag::Bag& bag, const CommandLineParams& options, const brick_pose::SyntheticFrameMessages& messages)
{
  const ros::Time stamp = messages.color->header.stamp;
  const std::string& ns = options.camera_ns;
  bag.write(ns + "/" + brick_pose::CameraTopics::kColorImage, stamp, messages.color);
  bag.write(ns + "/" + brick_pose::CameraTopics::kColorInfo, stamp, messages.color_info);
  bag.write(ns + "/" + brick_pose::CameraTopics::kDepthImage, stamp, messages.depth);
  bag.write(ns + "/" + brick_pose::CameraTopics::kDepthInfo, stamp, messages.depth_info);
  bag.write(ns + "/synthetic_camera/ground_truth", stamp, messages.truth);
  tf2_msgs::TFMessage tf;
  tf.transforms = messages.truth_frames;
  bag.write("/tf", stamp, tf);
}

int run(const CommandLineParams& options)
{
  const brick_pose::sim::RigConfig config = brick_pose::sim::rigConfigFrom([&](const std::string& name) {
    const auto found = options.rig_parameters.find(name);
    return found == options.rig_parameters.end() ? std::nullopt : std::optional<std::string>(found->second);
  });
  const brick_pose::sim::SyntheticRig rig(config.camera, config.sensor);
  const brick_pose::sim::SceneGenerator generator(config.catalogue, config.scene);

  rosbag::Bag bag(options.output, rosbag::bagmode::Write);
  const ros::Time start(1700000000, 0);
  tf2_msgs::TFMessage static_tf;
  static_tf.transforms.push_back(brick_pose::cameraLinkToOptical(start, "camera_link", options.frame_id));
  bag.write("/tf_static", start, static_tf);

  std::uint64_t scene_seed = config.seed;
  brick_pose::sim::Scene scene = generator.generate(scene_seed);
  const auto wall_start = std::chrono::steady_clock::now();
  for (int frame = 0; frame < options.frames; ++frame)
  {
    if (options.new_scene_every > 0 && frame > 0 && frame % options.new_scene_every == 0)
      scene = generator.generate(++scene_seed);
    const ros::Time stamp = start + ros::Duration(frame / options.rate_hz);
    const auto rendered = rig.render(scene, scene_seed * 1000003ULL + frame);
    writeFrame(bag, options, brick_pose::toMessages(rendered, stamp, options.frame_id));
    std::fprintf(stderr, "\rframe %d/%d", frame + 1, options.frames);
  }
  bag.close();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  std::fprintf(stderr, "\nwrote %d frames to %s in %.1f s\n", options.frames, options.output.c_str(), seconds);
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help" || std::string(argv[i]) == "-h")
    {
      printUsage();
      return 0;
    }
  try
  {
    return run(parseArguments(argc, argv));
  }
  catch (const ConfigError& e)
  {
    std::cerr << "brick_pose_simulate: " << e.what() << "\n";
    return 2;
  }
  catch (const std::exception& e)
  {
    std::cerr << "brick_pose_simulate: error: " << e.what() << "\n";
    return 1;
  }
}
