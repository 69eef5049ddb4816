// Test-only nodelet, loaded into the pipeline's manager: on request it blocks
// every worker thread of the manager, so that a test can check what still
// answers when the pipeline is as busy as it can get (a long frame in every
// stage, or a camera driver hogging the shared manager).
//
// It subscribes `~worker_count` times to `image` on the multi-threaded queue
// (one subscription per worker: callbacks of different subscriptions run
// concurrently). When the parameter `~stall` is true, each callback blocks
// until `~stall` turns false again. Progress is reported through parameters,
// not services, since a service of this nodelet would itself need a worker:
//   ~blocked_workers   callbacks blocked right now.
// Parameters go to the master over XML-RPC, which no worker thread serves.

#include <atomic>
#include <memory>
#include <thread>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

namespace brick_pose
{
class WorkerStallNodelet : public nodelet::Nodelet
{
public:
  ~WorkerStallNodelet() override { shutting_down_ = true; }

private:
  void onInit() override
  {
    ros::NodeHandle& private_node = getPrivateNodeHandle();
    const int worker_count = private_node.param("worker_count", 4);
    private_node.setParam("stall", false);
    private_node.setParam("blocked_workers", 0);
    for (int i = 0; i < worker_count; ++i)
      subscribers_.push_back(getMTNodeHandle().subscribe("image", 1, &WorkerStallNodelet::onImage, this));
    NODELET_INFO("ready to stall %d workers on %s", worker_count, subscribers_.front().getTopic().c_str());
  }

  void onImage(const sensor_msgs::ImageConstPtr&)
  {
    if (!stallRequested()) return;
    getPrivateNodeHandle().setParam("blocked_workers", ++blocked_);
    while (!shutting_down_ && stallRequested())
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    getPrivateNodeHandle().setParam("blocked_workers", --blocked_);
  }

  bool stallRequested() const
  {
    bool stall = false;
    return getPrivateNodeHandle().getParamCached("stall", stall) && stall;
  }

  std::vector<ros::Subscriber> subscribers_;
  std::atomic<int> blocked_{0};
  std::atomic<bool> shutting_down_{false};
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::WorkerStallNodelet, nodelet::Nodelet)
