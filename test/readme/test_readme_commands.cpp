// The README's commands, run exactly as the README writes them: each line is
// read from README.md, not copied here, so a README that documents a command
// which does not work fails this test.
//
//  - the bag commands, on a 1 s bag written by brick_pose_simulate: looped,
//    it gives detections on at least 3 passes in 10 s; played once, the
//    pipeline stays up and the service still answers 5 s after the bag ended;
//  - the demo command (scripts/demo.sh with the README's arguments);
//  - the box pallet on the synthetic D415 with its ground as support_frame.
//
// A roscore on a port of its own serves the launched pipeline and this
// test's ROS client.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <ros/ros.h>

#include "brick_pose/BrickDetectionArray.h"
#include "brick_pose/GetBrickPose.h"

namespace
{
// The repository (README.md, scripts/) and the workspace it was built in.
const std::string kRepositoryDir = BRICK_POSE_REPOSITORY_DIR;
const std::string kMasterPort = "11471";
const std::string kRosEnv = "export PATH=/usr/bin:/bin:$PATH; source " DEVEL_SETUP_BASH
                            " >/dev/null 2>&1; export ROS_MASTER_URI=http://127.0.0.1:" + kMasterPort +
                            " ROS_HOSTNAME=127.0.0.1; ";

/// A shell command running in a process group of its own, interrupted
/// (SIGINT, as Ctrl-C) and reaped when it goes out of scope.
class Background
{
public:
  Background(const std::string& command, const std::string& log_path)
  {
    pid_ = fork();
    if (pid_ == 0)
    {
      setpgid(0, 0);
      const std::string line = command + " >" + log_path + " 2>&1";
      execl("/bin/bash", "bash", "-c", line.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
  }
  ~Background()
  {
    if (pid_ <= 0) return;
    kill(-pid_, SIGINT);
    for (int i = 0; i < 100 && running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(100));
    if (running()) kill(-pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  bool running() const { return waitpid(pid_, nullptr, WNOHANG) == 0; }

private:
  pid_t pid_ = -1;
};

std::string readFile(const std::string& path)
{
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

/// The README's line that starts (after indentation) with `prefix`, without
/// a trailing comment; fails the test when there is none.
std::string readmeLine(const std::string& prefix, const std::string& must_contain = "")
{
  std::istringstream readme(readFile(kRepositoryDir + "/README.md"));
  std::string line;
  while (std::getline(readme, line))
  {
    const auto start = line.find_first_not_of(' ');
    if (start == std::string::npos || line.compare(start, prefix.size(), prefix) != 0) continue;
    std::string command = line.substr(start);
    command = command.substr(0, command.find('#'));
    command = command.substr(0, command.find_last_not_of(' ') + 1);
    if (command.find(must_contain) != std::string::npos) return command;
  }
  ADD_FAILURE() << "README.md has no line starting with '" << prefix << "' containing '" << must_contain << "'";
  return "false";
}

struct Received
{
  double wall_s;
  double stamp_s;
  std::size_t bricks;
};

/// Detections as this test's client receives them.
class DetectionLog
{
public:
  explicit DetectionLog(ros::NodeHandle& node)
  {
    subscriber_ = node.subscribe("/brick_pose/detections", 50, &DetectionLog::onDetections, this);
  }
  std::vector<Received> snapshot() const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_;
  }

private:
  void onDetections(const brick_pose::BrickDetectionArrayConstPtr& message)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    received_.push_back({ros::WallTime::now().toSec(), message->header.stamp.toSec(), message->detections.size()});
  }
  mutable std::mutex mutex_;
  std::vector<Received> received_;
  ros::Subscriber subscriber_;
};

/// Waits up to `timeout_s` for `done`, polling.
template <typename Predicate>
bool waitFor(double timeout_s, Predicate done)
{
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end)
  {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return done();
}

/// Passes of a looped bag with at least one brick: a new pass starts where
/// the stamps go back.
int passesWithBricks(const std::vector<Received>& received)
{
  int passes = 0;
  bool counted = false;
  for (std::size_t i = 0; i < received.size(); ++i)
  {
    if (i > 0 && received[i].stamp_s < received[i - 1].stamp_s) counted = false;
    if (!counted && received[i].bricks > 0)
    {
      ++passes;
      counted = true;
    }
  }
  return passes;
}

class ReadmeCommands : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    bag_dir_ = std::string(::testing::TempDir()) + "brick_pose_readme";
    ASSERT_EQ(std::system(("mkdir -p " + bag_dir_).c_str()), 0);
    // 1 s of a single brick at 10 Hz, as the README's pile.bag.
    const std::string write_bag = std::string(SIMULATE_TOOL) + " --output " + bag_dir_ +
                                  "/pile.bag --frames 10 --rate 10 --scene single --seed 3 >" + bag_dir_ +
                                  "/simulate.log 2>&1";
    ASSERT_EQ(std::system(write_bag.c_str()), 0) << readFile(bag_dir_ + "/simulate.log");
    // One master for the suite; this client starts talking to it only once it is up.
    roscore_ = new Background(kRosEnv + "roscore -p " + kMasterPort, bag_dir_ + "/roscore.log");
    ASSERT_TRUE(waitFor(30.0, [] { return ros::master::check(); })) << readFile(bag_dir_ + "/roscore.log");
    spinner_ = new ros::AsyncSpinner(2);
    spinner_->start();
    ready_ = true;
  }

  // Without a master the ROS client would wait for one forever.
  void SetUp() override { ASSERT_TRUE(ready_) << "the suite's roscore did not start"; }

  static void TearDownTestSuite()
  {
    delete spinner_;
    delete roscore_;
  }

  /// Runs a README line in the bag's folder, with the workspace sourced.
  std::unique_ptr<Background> launch(const std::string& readme_command, const std::string& log_name)
  {
    return std::make_unique<Background>(kRosEnv + "cd " + bag_dir_ + " && " + readme_command,
                                        bag_dir_ + "/" + log_name);
  }

  static std::string bag_dir_;
  static Background* roscore_;
  static ros::AsyncSpinner* spinner_;
  static bool ready_;
};
bool ReadmeCommands::ready_ = false;
std::string ReadmeCommands::bag_dir_;
Background* ReadmeCommands::roscore_ = nullptr;
ros::AsyncSpinner* ReadmeCommands::spinner_ = nullptr;

TEST_F(ReadmeCommands, LoopedBagGivesDetectionsOnEveryPass)
{
  const std::string command = readmeLine("roslaunch brick_pose bag.launch", "loop:=true");
  auto pipeline = launch(command, "bag_loop.log");
  ros::NodeHandle node;
  DetectionLog log(node);
  ASSERT_TRUE(waitFor(60.0, [&] { return !log.snapshot().empty(); }))
      << "no detections from `" << command << "`:\n" << readFile(bag_dir_ + "/bag_loop.log");
  const double start_s = ros::WallTime::now().toSec();
  waitFor(10.0, [] { return false; });
  std::vector<Received> window;
  for (const Received& received : log.snapshot())
    if (received.wall_s >= start_s) window.push_back(received);
  EXPECT_GE(passesWithBricks(window), 3) << window.size() << " detection messages in 10 s; log:\n"
                                         << readFile(bag_dir_ + "/bag_loop.log");
  EXPECT_TRUE(pipeline->running());
}

TEST_F(ReadmeCommands, BagPlayedOnceLeavesTheServiceAnswering)
{
  const std::string command = readmeLine("roslaunch brick_pose bag.launch", "bag:=");
  ASSERT_EQ(command.find("loop:=true"), std::string::npos) << "the first bag line of the README plays once";
  auto pipeline = launch(command, "bag_once.log");
  ros::NodeHandle node;
  DetectionLog log(node);
  ASSERT_TRUE(waitFor(60.0, [&] { return !log.snapshot().empty(); }))
      << "no detections from `" << command << "`:\n" << readFile(bag_dir_ + "/bag_once.log");
  // The bag has ended once no detections come for 2 s; then wait 5 s more.
  ASSERT_TRUE(waitFor(30.0, [&] { return ros::WallTime::now().toSec() - log.snapshot().back().wall_s > 2.0; }));
  waitFor(5.0, [] { return false; });
  ASSERT_TRUE(pipeline->running()) << "the launch ended with the bag:\n" << readFile(bag_dir_ + "/bag_once.log");
  brick_pose::GetBrickPose call;
  call.request.policy = "nearest";
  ASSERT_TRUE(ros::service::waitForService("/brick_pose/get_brick_pose", ros::Duration(5.0)));
  ASSERT_TRUE(ros::service::call("/brick_pose/get_brick_pose", call));
  EXPECT_TRUE(call.response.success) << call.response.message;
  EXPECT_NE(call.response.message.find("s old"), std::string::npos) << call.response.message;
  EXPECT_GE(call.response.age_s, 0.0);
}

TEST_F(ReadmeCommands, BoxPalletWithTheRigsGroundGivesBoxes)
{
  // The synthetic D415's pallet layer with the box catalogue, its ground
  // (truth_ground) given as support_frame: boxes are detected, of the box
  // catalogue's types only.
  const std::string command = readmeLine("roslaunch brick_pose demo.launch", "support_frame:=truth_ground");
  // The bag tests' launches set /use_sim_time on the suite's master; a user
  // runs the demo on a master of their own, where it is unset.
  ros::param::del("/use_sim_time");
  auto pipeline = launch(command, "box_pallet.log");
  ros::NodeHandle node;
  std::mutex mutex;
  std::vector<std::string> types;
  const ros::Subscriber subscriber = node.subscribe<brick_pose::BrickDetectionArray>(
      "/brick_pose/detections", 10, [&](const brick_pose::BrickDetectionArrayConstPtr& message) {
        std::lock_guard<std::mutex> lock(mutex);
        for (const brick_pose::BrickDetection& detection : message->detections) types.push_back(detection.type);
      });
  ASSERT_TRUE(waitFor(90.0, [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return !types.empty();
  })) << "no boxes from `" << command << "`:\n"
      << readFile(bag_dir_ + "/box_pallet.log");
  std::lock_guard<std::mutex> lock(mutex);
  for (const std::string& type : types) EXPECT_EQ(type.rfind("box_", 0), 0u) << type;
  // (That the ground's plane reaches the frames is support_frame.test's.)
  EXPECT_TRUE(pipeline->running()) << readFile(bag_dir_ + "/box_pallet.log");
}

TEST_F(ReadmeCommands, DemoScriptWithTheReadmesArguments)
{
  // scripts/demo.sh starts a master of its own, on another port.
  const std::string command = readmeLine("scripts/demo.sh");
  const std::string log_path = bag_dir_ + "/demo.log";
  const int status = std::system(("cd " + kRepositoryDir + " && " + command + " >" + log_path + " 2>&1").c_str());
  const std::string output = readFile(log_path);
  EXPECT_EQ(WEXITSTATUS(status), 0) << output;
  EXPECT_NE(output.find("get_brick_pose"), std::string::npos) << output;
}
TEST(LaunchFiles, D415LaunchParsesAgainstTheDriversInterface)
{
  // realsense2_camera is not packaged by Debian: a stub of its rs_camera.launch
  // arguments (test/stubs) stands in; roslaunch resolves every include,
  // argument and substitution and lists the nodes it would start.
  const std::string list = std::string(::testing::TempDir()) + "brick_pose_d415_nodes.txt";
  const std::string command = kRosEnv + "export ROS_PACKAGE_PATH=" + kRepositoryDir + "/test/stubs:$ROS_PACKAGE_PATH; " +
                              "roslaunch --nodes " + kRepositoryDir + "/launch/d415.launch mode:=colour_free >" + list +
                              " 2>&1";
  const int status = std::system(("bash -c '" + command + "'").c_str());
  const std::string nodes = readFile(list);
  EXPECT_EQ(WEXITSTATUS(status), 0) << nodes;
  for (const char* node : {"/brick_pose/ingestion", "/brick_pose/segmentation", "/brick_pose/roi_filter",
                           "/brick_pose/registration", "/brick_pose/pose_correction"})
    EXPECT_NE(nodes.find(node), std::string::npos) << node << " missing from:\n" << nodes;
}

TEST(LaunchFiles, D415ScriptSaysWhatToInstallWithoutTheDriver)
{
  const std::string log_path = std::string(::testing::TempDir()) + "brick_pose_d415_script.txt";
  const int status = std::system(("cd " + kRepositoryDir + " && " + readmeLine("scripts/d415.sh") + " >" + log_path +
                                  " 2>&1").c_str());
  const std::string output = readFile(log_path);
  EXPECT_EQ(WEXITSTATUS(status), 1) << output;
  EXPECT_NE(output.find("realsense2_camera ROS driver is not installed"), std::string::npos) << output;
}
}  // namespace

int main(int argc, char** argv)
{
  ::testing::InitGoogleTest(&argc, argv);
  setenv("ROS_MASTER_URI", ("http://127.0.0.1:" + kMasterPort).c_str(), 1);
  setenv("ROS_HOSTNAME", "127.0.0.1", 1);
  ros::init(argc, argv, "readme_commands_test", ros::init_options::AnonymousName | ros::init_options::NoSigintHandler);
  const int result = RUN_ALL_TESTS();
  ros::shutdown();
  return result;
}
