// Issue 13: each in-process message type has its own data type name and
// MD5. roscpp refuses a connection whose MD5s differ, so a wrong remap (the
// segments topic fed to a stage that wants candidates) fails at connect
// instead of delivering a default-constructed message with a null frame.

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "brick_pose/ros/pipeline_messages.h"

namespace brick_pose
{
namespace
{
template <typename Message>
std::pair<std::string, std::string> traitsOf()
{
  return {ros::message_traits::MD5Sum<Message>::value(), ros::message_traits::DataType<Message>::value()};
}

TEST(InProcessMessages, EachTypeHasItsOwnMd5AndName)
{
  const std::vector<std::pair<std::string, std::string>> traits = {
      traitsOf<FrameMessage>(), traitsOf<SegmentsMessage>(), traitsOf<CandidatesMessage>(),
      traitsOf<RegistrationsMessage>()};
  std::set<std::string> md5s, names;
  for (const auto& [md5, name] : traits)
  {
    EXPECT_EQ(md5.size(), 32u) << name;
    EXPECT_EQ(md5.find_first_not_of("0123456789abcdef"), std::string::npos) << name << ": " << md5;
    EXPECT_NE(md5, "*") << name << ": a wildcard MD5 would connect to anything";
    EXPECT_EQ(name.rfind("brick_pose/InProcess", 0), 0u) << name;
    md5s.insert(md5);
    names.insert(name);
  }
  EXPECT_EQ(md5s.size(), traits.size()) << "two in-process types share an MD5";
  EXPECT_EQ(names.size(), traits.size()) << "two in-process types share a data type name";
}
}  // namespace
}  // namespace brick_pose
