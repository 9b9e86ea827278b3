// curved_mesh_solver: the bent sheet of paper_model's state as a mesh marker (SPEC §4.2).
#include "virtual_origami/numerics/heap_reuse.h"
#include "virtual_origami/ros/curved_mesh_solver_node.h"

int main(int argc, char** argv)
{
  // Its solves make their matrices afresh: freed memory is kept for the next (heap_reuse.h).
  virtual_origami::numerics::keepFreedMemory();
  ros::init(argc, argv, "curved_mesh_solver");
  virtual_origami::CurvedMeshSolverNode node(ros::NodeHandle(), ros::NodeHandle("~"));
  ros::spin();
  return 0;
}
