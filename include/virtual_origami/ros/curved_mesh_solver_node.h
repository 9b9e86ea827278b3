// The curved_mesh_solver node (SPEC §4.2, §5): follows paper_model's `state`, meshes the
// crease pattern into one conforming triangle mesh, lets the paper bend around its pinned
// vertices with the curved-paper solver, and publishes the bent sheet for rviz. It never
// writes back into the model: the rigid faces stay the committed state, the mesh shows how
// real paper would sag between them.
#pragma once

#include <optional>
#include <string>

#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>
#include <virtual_origami/CurvedMeshSolverConfig.h>
#include <virtual_origami/PaperState.h>

#include "virtual_origami/curved/curved_solver.h"

namespace virtual_origami
{
/// The curved sheet of one state: its mesh, the balanced node positions and how the solve went.
struct CurvedSheet
{
  core::CurvedMesh mesh;
  core::Positions positions;
  core::CurvedReport report;
};

/// Meshes `paper` (bubble mesh at `spacing` × the sheet's scale) and balances it with every
/// vertex in `held` kept at its folded position. Fails on a paper the mesher cannot mesh.
core::Expected<CurvedSheet> solveCurvedSheet(const core::Paper& paper, const std::vector<int>& held,
                                             const CurvedMeshSolverConfig& config);

class CurvedMeshSolverNode
{
public:
  CurvedMeshSolverNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

private:
  void onState(const PaperState::ConstPtr& state);
  void reconfigure(CurvedMeshSolverConfig& config, uint32_t level);
  void solveAndPublish();

  CurvedMeshSolverConfig config_;
  dynamic_reconfigure::Server<CurvedMeshSolverConfig> reconfigure_server_;
  PaperState::ConstPtr last_state_;
  ros::Subscriber state_sub_;
  ros::Publisher mesh_pub_;
};

}  // namespace virtual_origami
