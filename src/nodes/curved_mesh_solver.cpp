// curved_mesh_solver: the bent sheet of paper_model's state as a mesh marker (SPEC §4.2).
#include "virtual_origami/ros/curved_mesh_solver_node.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "curved_mesh_solver");
  virtual_origami::CurvedMeshSolverNode node(ros::NodeHandle(), ros::NodeHandle("~"));
  ros::spin();
  return 0;
}
