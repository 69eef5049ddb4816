// Test-only nodelet, loaded into the pipeline's manager: subscribes to every
// in-process topic of the chain and checks that what arrives downstream holds
// the very objects that arrived upstream (same addresses, same pixel buffers),
// i.e. that nothing was serialised or copied between the nodelets. Reports on
// ~report (std_srvs/Trigger). ~frame_support (std_srvs/Trigger) tells the
// supporting plane the last frame carried (from the ingestion's
// support_frame), as "nx ny nz d", and fails when it carried none.

#include <mutex>
#include <optional>
#include <sstream>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "brick_pose/ros/pipeline_messages.h"

namespace brick_pose
{
/// The last few objects received on a topic, held alive so that their
/// addresses cannot be reused by new allocations while we compare.
template <typename T>
class RecentObjects
{
public:
  void add(const boost::shared_ptr<const T>& object)
  {
    kept_.push_back(object);
    if (kept_.size() > 30) kept_.erase(kept_.begin());
    ++count_;
  }
  bool contains(const T* pointer) const
  {
    for (const auto& object : kept_)
      if (object.get() == pointer) return true;
    return false;
  }
  int count() const { return count_; }

private:
  std::vector<boost::shared_ptr<const T>> kept_;
  int count_ = 0;
};

class ZeroCopyProbeNodelet : public nodelet::Nodelet
{
private:
  void onInit() override
  {
    ros::NodeHandle& node = getNodeHandle();
    subscribers_.push_back(node.subscribe("frame", 10, &ZeroCopyProbeNodelet::onFrame, this));
    subscribers_.push_back(node.subscribe("segments", 10, &ZeroCopyProbeNodelet::onSegments, this));
    subscribers_.push_back(node.subscribe("candidates", 10, &ZeroCopyProbeNodelet::onCandidates, this));
    subscribers_.push_back(node.subscribe("registrations", 10, &ZeroCopyProbeNodelet::onRegistrations, this));
    report_ = getPrivateNodeHandle().advertiseService("report", &ZeroCopyProbeNodelet::onReport, this);
    support_ = getPrivateNodeHandle().advertiseService("frame_support", &ZeroCopyProbeNodelet::onSupport, this);
  }

  void onFrame(const FrameMessageConstPtr& frame)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    frames_.add(frame);
    if (frame->frame.rgb.empty()) fail("a frame arrived without pixels (was it deserialised?)");
    last_support_ = frame->frame.support_in_camera;
  }

  void onSegments(const SegmentsMessageConstPtr& segments)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    segments_.add(segments);
    if (!frames_.contains(segments->frame.get())) fail("segments point to a frame the probe never received");
  }

  void onCandidates(const CandidatesMessageConstPtr& candidates)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    candidates_.add(candidates);
    if (!segments_.contains(candidates->segments.get())) fail("candidates point to segments the probe never received");
    if (candidates->frame.get() != candidates->segments->frame.get()) fail("candidates carry a copy of the frame");
    if (candidates->frame->frame.depth_m.data != candidates->segments->frame->frame.depth_m.data)
      fail("the depth buffer was copied");
    if (!frames_.contains(candidates->frame.get())) fail("candidates point to a frame the probe never received");
  }

  void onRegistrations(const RegistrationsMessageConstPtr& registrations)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++registration_messages_;
    if (!candidates_.contains(registrations->candidates.get()))
      fail("registrations point to candidates the probe never received");
    else
      ++verified_chains_;
  }

  bool onReport(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    std::ostringstream text;
    text << frames_.count() << " frames, " << segments_.count() << " segments, " << candidates_.count()
         << " candidates, " << registration_messages_ << " registrations, " << verified_chains_
         << " chains verified end to end";
    if (!failure_.empty()) text << "; FIRST FAILURE: " << failure_;
    response.success = failure_.empty() && verified_chains_ > 0;
    response.message = text.str();
    return true;
  }

  bool onSupport(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    response.success = last_support_.has_value();
    if (!last_support_)
    {
      response.message = frames_.count() > 0 ? "the last frame carried no supporting plane" : "no frame yet";
      return true;
    }
    std::ostringstream text;
    text.precision(9);
    text << (*last_support_)[0] << " " << (*last_support_)[1] << " " << (*last_support_)[2] << " "
         << (*last_support_)[3];
    response.message = text.str();
    return true;
  }

  void fail(const std::string& what)
  {
    if (failure_.empty()) failure_ = what;
  }

  std::mutex mutex_;
  std::vector<ros::Subscriber> subscribers_;
  ros::ServiceServer report_;
  ros::ServiceServer support_;
  std::optional<Eigen::Vector4d> last_support_;
  RecentObjects<FrameMessage> frames_;
  RecentObjects<SegmentsMessage> segments_;
  RecentObjects<CandidatesMessage> candidates_;
  int registration_messages_ = 0;
  int verified_chains_ = 0;
  std::string failure_;
};
}  // namespace brick_pose

PLUGINLIB_EXPORT_CLASS(brick_pose::ZeroCopyProbeNodelet, nodelet::Nodelet)
