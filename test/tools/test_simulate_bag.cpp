// brick_pose_simulate writes a bag that rosbag reads back with realsense2_camera's
// topics, the right types and one message per frame on each.

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <string>

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Image.h>

namespace
{
struct CommandResult
{
  int exit_code;
  std::string output;
};

CommandResult runCommand(const std::string& command)
{
  CommandResult result{-1, ""};
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  while (fgets(buffer, sizeof(buffer), pipe) != nullptr)
    result.output += buffer;
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string bagPath(const std::string& name)
{
  return std::string(::testing::TempDir()) + "brick_pose_" + name + ".bag";
}
}  // namespace

TEST(SimulateTool, BagHasRealsenseTopicsTypesAndCounts)
{
  const std::string bag_file = bagPath("simulate");
  const CommandResult written = runCommand(std::string(SIMULATE_TOOL) + " --output " + bag_file +
                                           " --frames 4 --scene unorganised_pile --seed 3 --lighting sunlight");
  ASSERT_EQ(written.exit_code, 0) << written.output;

  const CommandResult info = runCommand("rosbag info --yaml " + bag_file);
  ASSERT_EQ(info.exit_code, 0) << "rosbag info failed:\n" << info.output;
  for (const char* topic : {"/camera/color/image_raw", "/camera/color/camera_info",
                            "/camera/aligned_depth_to_color/image_raw", "/camera/aligned_depth_to_color/camera_info",
                            "/camera/synthetic_camera/ground_truth", "/tf", "/tf_static"})
    EXPECT_NE(info.output.find(topic), std::string::npos) << topic << " missing from:\n" << info.output;
  EXPECT_NE(info.output.find("sensor_msgs/Image"), std::string::npos);
  EXPECT_NE(info.output.find("sensor_msgs/CameraInfo"), std::string::npos);
  EXPECT_NE(info.output.find("brick_pose/BrickTruthArray"), std::string::npos);

  rosbag::Bag bag(bag_file, rosbag::bagmode::Read);
  std::map<std::string, int> counts;
  std::map<std::string, std::string> types;
  rosbag::View view(bag);
  for (const rosbag::MessageInstance& message : view)
  {
    ++counts[message.getTopic()];
    types[message.getTopic()] = message.getDataType();
  }
  EXPECT_EQ(counts["/camera/color/image_raw"], 4);
  EXPECT_EQ(counts["/camera/aligned_depth_to_color/image_raw"], 4);
  EXPECT_EQ(counts["/camera/color/camera_info"], 4);
  EXPECT_EQ(counts["/camera/aligned_depth_to_color/camera_info"], 4);
  EXPECT_EQ(counts["/camera/synthetic_camera/ground_truth"], 4);
  EXPECT_EQ(counts["/tf_static"], 1);
  EXPECT_EQ(types["/camera/aligned_depth_to_color/image_raw"], "sensor_msgs/Image");

  // The depth really is 16UC1 millimetres at 1280x720.
  rosbag::View depth_view(bag, rosbag::TopicQuery("/camera/aligned_depth_to_color/image_raw"));
  const auto depth = depth_view.begin()->instantiate<sensor_msgs::Image>();
  ASSERT_NE(depth, nullptr);
  EXPECT_EQ(depth->encoding, "16UC1");
  EXPECT_EQ(depth->width, 1280u);
  EXPECT_EQ(depth->height, 720u);
  EXPECT_EQ(depth->header.frame_id, "camera_color_optical_frame");
  bag.close();
  std::remove(bag_file.c_str());
}

TEST(SimulateTool, BadOptionsAreNamedAndRejected)
{
  const std::string tool = std::string(SIMULATE_TOOL) + " --output " + bagPath("bad");
  const CommandResult unknown_type = runCommand(tool + " --types purple");
  EXPECT_EQ(unknown_type.exit_code, 2);
  EXPECT_NE(unknown_type.output.find("purple"), std::string::npos) << unknown_type.output;

  const CommandResult zero_focal = runCommand(tool + " --fx 0");
  EXPECT_EQ(zero_focal.exit_code, 2);
  EXPECT_NE(zero_focal.output.find("fx"), std::string::npos) << zero_focal.output;

  const CommandResult negative_rate = runCommand(tool + " --rate -5");
  EXPECT_EQ(negative_rate.exit_code, 2);
  EXPECT_NE(negative_rate.output.find("rate"), std::string::npos) << negative_rate.output;

  const CommandResult not_a_number = runCommand(tool + " --min_distance_m near");
  EXPECT_EQ(not_a_number.exit_code, 2);
  EXPECT_NE(not_a_number.output.find("min_distance_m"), std::string::npos) << not_a_number.output;
}
