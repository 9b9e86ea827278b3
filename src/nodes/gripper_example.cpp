// gripper_example: a gripper folds the sheet in half through pins on tf frames; see
// include/virtual_origami/ros/gripper_example.h.
#include <ros/ros.h>

#include "virtual_origami/ros/gripper_example.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "gripper_example");
  ros::NodeHandle private_nh("~");
  virtual_origami::GripperOptions options;
  private_nh.param("corner", options.corner, options.corner);
  private_nh.param("duration", options.duration, options.duration);
  private_nh.param("rate", options.rate, options.rate);
  private_nh.param("frame", options.frame, options.frame);
  private_nh.param("paper_frame", options.paper_frame, options.paper_frame);
  private_nh.param("crease", options.crease, options.crease);
  private_nh.param("curved", options.curved, options.curved);
  private_nh.param("timeout", options.timeout, options.timeout);
  virtual_origami::GripperExample gripper(ros::NodeHandle(), options);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const virtual_origami::core::Status done = gripper.run();
  if (!done)
  {
    ROS_ERROR("gripper_example: %s", done.message().c_str());
    return 1;
  }
  return 0;
}
