// recorder: writes `operations` and `state` to a bag that survives kill -9 (SPEC §7).
// rosparam ~path: the bag, in the data folder (~data_dir, ~allowed_dirs: as paper_model's).
// `rosbag record operations state` works too, but keeps the last chunk in memory until it stops.
#include <ros/ros.h>

#include "virtual_origami/core/data_folder.h"
#include "virtual_origami/ros/recording.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "recorder");
  ros::NodeHandle nh, private_nh("~");
  std::vector<std::string> allowed;
  private_nh.param("allowed_dirs", allowed, allowed);
  const std::string data_dir = private_nh.param<std::string>("data_dir", "");
  const auto folder =
      virtual_origami::core::DataFolder::open(data_dir.empty() ? virtual_origami::core::defaultDataFolder() : data_dir,
                                              allowed);
  const auto path = folder ? folder->resolve(private_nh.param<std::string>("path", "folding.bag")) :
                             virtual_origami::core::Expected<std::string>::failure(folder.message());
  if (!path)
  {
    ROS_FATAL("recorder: the bag: %s", path.message().c_str());
    return 1;
  }
  virtual_origami::DurableBagWriter writer(*path);
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
