// spring_solver: restores face shapes for paper_model; see include/virtual_origami/ros/spring_solver_node.h.
#include <ros/ros.h>

#include "virtual_origami/numerics/heap_reuse.h"
#include "virtual_origami/ros/spring_solver_node.h"

int main(int argc, char** argv)
{
  // Its solves make their matrices afresh: freed memory is kept for the next (heap_reuse.h).
  virtual_origami::numerics::keepFreedMemory();
  ros::init(argc, argv, "spring_solver");
  virtual_origami::SpringSolverNode node(ros::NodeHandle(), ros::NodeHandle("~"));
  ros::spin();
  return 0;
}
