#pragma once
// Lets a plain C++ type travel over a ros::Publisher between nodelets of one
// manager, as boost::shared_ptr<const T>, never serialised.
//
// roscpp hands intra-process subscribers the publisher's shared_ptr itself
// when the C++ types match, so images, clouds and candidates pass between the
// pipeline's nodelets without a copy. roscpp still wants the message traits
// and a serializer; the serializer writes nothing, so a subscriber outside the
// manager (rostopic hz) sees empty messages of type brick_pose/InProcess*.
// Use the ROS messages (detections, tf, images) to observe from outside.
//
// Each type has its own data type name and MD5 (the MD5 of a line naming
// the C++ type), so that a wrong remap - the segments topic fed to a stage
// that wants candidates - fails when the two connect instead of delivering a
// default-constructed message.

#include <ros/message_traits.h>
#include <ros/serialization.h>

#define BRICK_POSE_INPROCESS_MESSAGE(Type, Name, Md5)                                                 \
  namespace ros                                                                                      \
  {                                                                                                  \
  namespace message_traits                                                                           \
  {                                                                                                  \
  template <>                                                                                        \
  struct MD5Sum<Type>                                                                                \
  {                                                                                                  \
    static const char* value() { return Md5; }                                                     \
    static const char* value(const Type&) { return value(); }                                       \
  };                                                                                                 \
  template <>                                                                                        \
  struct DataType<Type>                                                                              \
  {                                                                                                  \
    static const char* value() { return "brick_pose/InProcess" Name; }                              \
    static const char* value(const Type&) { return value(); }                                       \
  };                                                                                                 \
  template <>                                                                                        \
  struct Definition<Type>                                                                            \
  {                                                                                                  \
    static const char* value() { return "# in-process only (" #Type "): no fields on the wire\n"; } \
    static const char* value(const Type&) { return value(); }                                       \
  };                                                                                                 \
  }                                                                                                  \
  namespace serialization                                                                            \
  {                                                                                                  \
  template <>                                                                                        \
  struct Serializer<Type>                                                                            \
  {                                                                                                  \
    template <typename Stream>                                                                       \
    inline static void write(Stream&, const Type&)                                                   \
    {                                                                                                \
    }                                                                                                \
    template <typename Stream>                                                                       \
    inline static void read(Stream&, Type&)                                                          \
    {                                                                                                \
    }                                                                                                \
    inline static uint32_t serializedLength(const Type&) { return 0; }                               \
  };                                                                                                 \
  }                                                                                                  \
  }
