// replay: re-applies a recorded folding (a bag of `operations`) to a running paper_model.
// Parameters: ~bag (path), ~speed (1: as recorded, 0: at once), ~animation_steps, ~data_dir
// (paper_model's, where the first state is handed over; default as paper_model's), ~max_gap
// (the longest pause between two operations, recorded seconds).
#include <algorithm>

#include <ros/ros.h>

#include "virtual_origami/ros/replay.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "replay");
  ros::NodeHandle nh, private_nh("~");
  const std::string bag = private_nh.param<std::string>("bag", "");
  const auto recording = virtual_origami::readRecording(bag);
  if (!recording)
  {
    ROS_FATAL("replay: %s", recording.message().c_str());
    return 1;
  }
  virtual_origami::ReplayOptions options;
  options.speed = private_nh.param("speed", options.speed);
  options.animation_steps = private_nh.param("animation_steps", options.animation_steps);
  options.data_dir = private_nh.param("data_dir", options.data_dir);
  options.max_gap = private_nh.param("max_gap", options.max_gap);
  options.progress = [](size_t done, size_t total) {
    // About every tenth, and the last.
    if (done == total || done % std::max<size_t>(1, total / 10) == 0)
      ROS_INFO("replay: %zu of %zu operations", done, total);
  };
  virtual_origami::OperationClient client(nh.getNamespace());
  if (!client.waitForServices(30.0))
  {
    ROS_FATAL("replay: the paper_model services in %s are not there", nh.getNamespace().c_str());
    return 1;
  }
  ROS_INFO("replay: %zu operations from %s", recording->operations.size(), bag.c_str());
  const virtual_origami::core::Status done = virtual_origami::replay(*recording, client, options);
  if (!done)
  {
    ROS_FATAL("replay: %s", done.message().c_str());
    return 1;
  }
  ROS_INFO("replay: done");
  return 0;
}
