// paper_model: owns the paper and its history; see include/virtual_origami/ros/paper_model_node.h.
#include <algorithm>
#include <stdexcept>

#include <ros/ros.h>

#include "virtual_origami/numerics/heap_reuse.h"
#include "virtual_origami/ros/paper_model_node.h"

int main(int argc, char** argv)
{
  // Its service threads take turns at solves that make their matrices afresh: one heap, and
  // freed memory kept for the next (heap_reuse.h).
  virtual_origami::numerics::keepFreedMemory(virtual_origami::numerics::ThreadHeaps::Shared);
  ros::init(argc, argv, "paper_model");
  ros::NodeHandle private_nh("~");
  try
  {
    virtual_origami::PaperModelNode node(ros::NodeHandle(), private_nh);
    // Several clients are served at once; a solve in progress holds up nobody (see the node).
    ros::AsyncSpinner spinner(std::max(2, private_nh.param("threads", 4)));
    spinner.start();
    ros::waitForShutdown();
  }
  catch (const std::runtime_error& e)
  {
    ROS_FATAL("paper_model: %s", e.what());
    return 1;
  }
  return 0;
}
