// spring_solver: restores face shapes for paper_model; see include/virtual_origami/ros/spring_solver_node.h.
#include <ros/ros.h>

#include "virtual_origami/ros/spring_solver_node.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "spring_solver");
  virtual_origami::SpringSolverNode node(ros::NodeHandle(), ros::NodeHandle("~"));
  ros::spin();
  return 0;
}
