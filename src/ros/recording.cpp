#include "virtual_origami/ros/recording.h"

#include <rosbag/bag.h>
#include <rosbag/view.h>

namespace virtual_origami
{
namespace
{
bool endsWith(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

core::Expected<Recording> readRecording(const std::string& path)
{
  Recording recording;
  try
  {
    rosbag::Bag bag(path, rosbag::bagmode::Read);
    rosbag::View view(bag);
    for (const rosbag::MessageInstance& m : view)
    {
      if (endsWith(m.getTopic(), "/operations"))
      {
        if (const auto op = m.instantiate<Operation>())
          recording.operations.push_back(*op);
      }
      else if (endsWith(m.getTopic(), "/state"))
      {
        if (const auto state = m.instantiate<PaperState>())
          recording.states.push_back(*state);
      }
    }
  }
  catch (const rosbag::BagException& e)
  {
    return core::Expected<Recording>::failure("cannot read the bag " + path + ": " + e.what());
  }
  if (!recording.operations.empty())
  {
    const uint64_t before = recording.operations.front().revision - 1;
    for (const PaperState& s : recording.states)
      if (s.revision == before)
        recording.initial_state = s;
  }
  return recording;
}

template <class Message>
core::Status DurableBagWriter::append(const std::string& topic, const Message& message)
{
  try
  {
    rosbag::Bag bag(path_, started_ ? rosbag::bagmode::Append : rosbag::bagmode::Write);
    const ros::Time stamp = message.header.stamp.isZero() ? ros::Time::now() : message.header.stamp;
    bag.write(topic, stamp, message);
    bag.close();  // index and data on disk now, not at the end of the recording
    started_ = true;
    return core::success();
  }
  catch (const rosbag::BagException& e)
  {
    return core::failure("cannot write the bag " + path_ + ": " + e.what());
  }
}

core::Status DurableBagWriter::write(const std::string& topic, const Operation& operation)
{
  return append(topic, operation);
}

core::Status DurableBagWriter::write(const std::string& topic, const PaperState& state)
{
  return append(topic, state);
}

}  // namespace virtual_origami
