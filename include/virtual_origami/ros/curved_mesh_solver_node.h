// The curved_mesh_solver node (SPEC §4.2, §5): follows paper_model's `state`, meshes the
// crease pattern into one conforming triangle mesh, lets the paper bend around its pinned
// vertices with the curved-paper solver, and publishes the bent sheet for rviz. Pins on tf
// frames are looked up at `pin_rate` and the sheet follows them from its last balance, also
// where the rigid faces of the model cannot (one face does not bend); so does a vertex the
// mouse drags where the rigid faces cannot follow (`curved_drag`); on large sheets each such move
// is shown at once as an anytime frame and settled to balance once the pins stand still. It
// never writes back into the model: the rigid faces stay the committed state, the mesh shows
// how real paper would bend between them, until a client keeps the sheet shown (`keep_bend`):
// then the model takes it (paper_model's `keep_bend`).
#pragma once

#include <optional>
#include <string>

#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <virtual_origami/CurvedMeshSolverConfig.h>
#include <virtual_origami/PaperState.h>
#include <virtual_origami/VertexTarget.h>

#include "virtual_origami/curved/curved_follow.h"
#include "virtual_origami/curved/curved_solver.h"
#include "virtual_origami/curved/paper_material.h"

namespace virtual_origami
{
/// The mesh of `paper` the node makes with `config` (its mesher and spacing).
core::Expected<core::CurvedMesh> meshCurvedSheet(const core::Paper& paper, const CurvedMeshSolverConfig& config);

/// The physical paper of `config` (material a preset or custom; thickness, youngs_modulus,
/// poisson_ratio, areal_density override a preset's where not 0); fails, saying why, on an
/// unknown preset or a paper checkPaperMaterial refuses.
core::Expected<core::PaperMaterial> physicalPaper(const CurvedMeshSolverConfig& config);

/// Material (relative: `bend`; else the physical paper's plate moduli), surroundings and solve
/// options from `config`; fails on a material or gravity the core refuses.
core::Expected<core::CurvedFollowOptions> curvedFollowOptions(const CurvedMeshSolverConfig& config);

/// The follower the node keeps: its mesher, material and solve options from `config`.
core::Expected<core::CurvedSheetFollower> curvedFollower(const CurvedMeshSolverConfig& config);

class CurvedMeshSolverNode
{
public:
  CurvedMeshSolverNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

private:
  void onState(const PaperState::ConstPtr& state);
  /// A vertex held at the mouse (or let go): solved on the next follow cycle.
  void onDrag(const VertexTarget::ConstPtr& drag);
  void reconfigure(CurvedMeshSolverConfig& config, uint32_t level);
  /// The last state solved (`anew`: from its rigid faces, not from the last balance).
  void solveAndPublish(bool anew = false);
  void followFrames(const ros::TimerEvent&);
  /// The pins of the last state, those on frames at their frame's origin as tf has it now
  /// (`stamp`: the newest transform used, else left as it is), and the vertex the mouse holds;
  /// false, with `error`, when tf cannot place a frame within `wait`.
  bool currentPins(std::vector<core::PullTarget>& pins, ros::Time& stamp, std::string& error,
                   const ros::Duration& wait = ros::Duration(0));
  void publish(const ros::Time& stamp, const core::CurvedReport& report, const char* what);
  /// Sends the sheet shown now to paper_model's `keep_bend` and answers what it did.
  bool keepBend(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);

  CurvedMeshSolverConfig config_;
  dynamic_reconfigure::Server<CurvedMeshSolverConfig> reconfigure_server_;
  PaperState::ConstPtr last_state_;
  std::optional<core::CurvedSheetFollower> follower_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  ros::Subscriber state_sub_, drag_sub_;
  std::optional<core::PullTarget> drag_;  // the vertex the mouse holds where rigid faces cannot follow
  ros::Time drag_stamp_;
  ros::Publisher mesh_pub_;
  ros::ServiceServer keep_bend_server_;
  ros::ServiceClient keep_bend_client_;
  ros::Timer follow_timer_;
  int resumed_ = 0;  // solves resumed on frames standing still since the sheet last balanced
};

}  // namespace virtual_origami
