// Seed 002's first picture (Fig. 1.1) as a ROS example: the crane folded through the paper's
// services from a fold-sequence file, its two wing tips pinned to tf frames of their own (as a
// robot's grippers would hold them), and the frames moved apart; curved_mesh_solver (with
// `layers`: the stacked layers kept apart) bends the folded model, and the crane's body opens.
#pragma once

#include <mutex>
#include <string>

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>
#include <virtual_origami/PaperState.h>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami
{
struct CranePuffOptions
{
  std::string sequence;        // the fold-sequence file folded first (sequences/crane.json)
  /// How much farther apart the wing tips end, × the sheet's side. A hundredth opens the body's
  /// stack to about 2 % of the side; the wings' leading edges then stretch by a few percent
  /// where they meet the body (docs/CURVED.md, "A barrier on that start").
  double spread = 0.01;
  double duration = 5.0;       // seconds the pull takes
  double rate = 30.0;          // Hz of the tip frames' broadcast
  std::string paper_frame = "paper";
  std::string frame_prefix = "wing_tip_";  // the frames: wing_tip_0 at corner (0, 0), wing_tip_1 at (s, s)
  double timeout = 60.0;       // longest wait for the model (services, a state)
};

class CranePuff
{
public:
  CranePuff(ros::NodeHandle nh, CranePuffOptions options);
  /// Folds, pins, pulls, and keeps broadcasting the frames where the pull ended until the node
  /// shuts down. Needs a spinner running (the node starts an AsyncSpinner).
  core::Status run();

private:
  core::Expected<PaperState> stateAfter(uint64_t revision);
  void broadcast(const ros::WallTimerEvent&);

  ros::NodeHandle nh_;
  CranePuffOptions options_;
  ros::Subscriber state_sub_;
  ros::WallTimer timer_;
  tf2_ros::TransformBroadcaster tf_;
  std::mutex mutex_;
  PaperState state_;
  bool have_state_ = false;
  bool broadcasting_ = false;
  core::Vec3 tips_[2];
};

}  // namespace virtual_origami
