// spring_solver: restores face shapes for paper_model; see include/virtual_origami/ros/spring_solver_node.h.
#include <ros/ros.h>

#include "virtual_origami/numerics/heap_reuse.h"
#include "virtual_origami/ros/spring_solver_node.h"

int main(int argc, char** argv)
{
  // Its service threads take turns at solves that make their matrices afresh: one heap, and
  // freed memory kept for the next (heap_reuse.h).
  virtual_origami::numerics::keepFreedMemory(virtual_origami::numerics::ThreadHeaps::Shared);
  ros::init(argc, argv, "spring_solver");
  virtual_origami::SpringSolverNode node(ros::NodeHandle(), ros::NodeHandle("~"));
  ros::spin();
  return 0;
}
