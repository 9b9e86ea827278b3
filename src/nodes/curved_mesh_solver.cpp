// curved_mesh_solver: the bent sheet of paper_model's state as a mesh marker (SPEC §4.2).
#include "virtual_origami/numerics/heap_reuse.h"
#include "virtual_origami/ros/curved_mesh_solver_node.h"

int main(int argc, char** argv)
{
  // Its frames and the factors made for them at once: a heap per thread, freed memory kept
  // (heap_reuse.h).
  virtual_origami::numerics::keepFreedMemory(virtual_origami::numerics::ThreadHeaps::PerThread);
  ros::init(argc, argv, "curved_mesh_solver");
  virtual_origami::CurvedMeshSolverNode node(ros::NodeHandle(), ros::NodeHandle("~"));
  ros::spin();
  return 0;
}
