// recorder: writes `operations` and `state` to a bag that survives kill -9 (SPEC §7).
// rosparam ~path: the bag. `rosbag record operations state` works too, but keeps the
// last chunk in memory until it stops.
#include <ros/ros.h>

#include "virtual_origami/ros/recording.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "recorder");
  ros::NodeHandle nh, private_nh("~");
  virtual_origami::DurableBagWriter writer(private_nh.param<std::string>("path", "folding.bag"));
  const auto report = [](const virtual_origami::core::Status& s) {
    if (!s)
      ROS_ERROR("recorder: %s", s.message().c_str());
  };
  const std::string operations = nh.resolveName("operations"), state = nh.resolveName("state");
  ros::Subscriber ops_sub = nh.subscribe<virtual_origami::Operation>(
      "operations", 100, [&](const virtual_origami::Operation::ConstPtr& op) { report(writer.write(operations, *op)); });
  ros::Subscriber state_sub = nh.subscribe<virtual_origami::PaperState>(
      "state", 100, [&](const virtual_origami::PaperState::ConstPtr& s) { report(writer.write(state, *s)); });
  ROS_INFO("recorder: %s and %s into %s", operations.c_str(), state.c_str(), writer.path().c_str());
  ros::spin();
  return 0;
}
