// crane_puff: the crane folded, its wing tips pinned to tf frames and pulled apart, so that
// curved_mesh_solver puffs its body (seed 002 Fig. 1.1); see include/virtual_origami/ros/crane_puff.h.
#include <ros/ros.h>

#include "virtual_origami/ros/crane_puff.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "crane_puff");
  ros::NodeHandle private_nh("~");
  virtual_origami::CranePuffOptions options;
  private_nh.param("sequence", options.sequence, options.sequence);
  private_nh.param("spread", options.spread, options.spread);
  private_nh.param("duration", options.duration, options.duration);
  private_nh.param("rate", options.rate, options.rate);
  private_nh.param("paper_frame", options.paper_frame, options.paper_frame);
  private_nh.param("timeout", options.timeout, options.timeout);
  virtual_origami::CranePuff puff(ros::NodeHandle(), options);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const virtual_origami::core::Status done = puff.run();
  if (!done)
  {
    ROS_ERROR("crane_puff: %s", done.message().c_str());
    return 1;
  }
  ros::waitForShutdown();
  return 0;
}
