// An example robot coupled to the paper (SPEC §1): a gripper that grasps a corner of the
// sheet by pinning it to its own tf frame, swings the frame on a half circle about the
// middle line so the sheet folds in half, and lets go; the sheet stays folded. With rigid
// faces the middle line is creased first and the model follows the frame; in the curved mode
// the sheet is grasped uncreased, bends (curved_mesh_solver follows the frame; the model's
// one rigid face cannot), and the crease is pressed in at the end of the path.
#pragma once

#include <mutex>
#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>
#include <virtual_origami/PaperState.h>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami
{
struct GripperOptions
{
  /// The corner grasped, counter-clockwise from the origin: 0 (0, 0), 1 (s, 0), 2 (s, s), 3 (0, s).
  int corner = 1;
  double duration = 4.0;  // seconds the half circle takes
  double rate = 30.0;     // Hz of the gripper frame's broadcast
  std::string frame = "gripper";
  std::string paper_frame = "paper";
  bool crease = true;  // crease the middle line first (rigid faces turn only about creases)
  /// Grasp the uncreased sheet, hold only its far edge, let it bend on the way, and crease
  /// and fold the middle line (the carried half on top) at the end of the path.
  bool curved = false;
  double timeout = 30.0;  // longest wait for the model (services, catching up)
};

class GripperExample
{
public:
  GripperExample(ros::NodeHandle nh, GripperOptions options);
  /// Creases, grasps, folds, releases. Blocks; needs a spinner running for its timer and
  /// the state subscription (the node starts an AsyncSpinner).
  core::Status run();

private:
  /// Calls the paper's service `name` (waiting for it up to the timeout); fails when it does
  /// not answer. Whether it succeeded is the response's.
  template <class Service>
  core::Status call(const std::string& name, Service& service)
  {
    const std::string resolved = nh_.resolveName(name);
    if (!ros::service::waitForService(resolved, ros::Duration(options_.timeout)) ||
        !ros::service::call(resolved, service))
      return core::failure("the service " + resolved + " did not answer");
    return core::success();
  }
  core::Status callPin(int vertex, const std::string& frame, bool release);
  /// Polls `ready` (called with the mutex held) until it holds, for at most the timeout.
  template <class Ready>
  bool waitUntil(Ready ready)
  {
    const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(options_.timeout);
    while (ros::ok() && ros::WallTime::now() < until)
    {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (ready())
          return true;
      }
      ros::WallDuration(0.01).sleep();
    }
    return false;
  }
  core::Expected<PaperState> creaseMiddle(const core::Vec2& a, const core::Vec2& b);
  /// The curved mode's end: presses the middle line a→b into a crease and folds the half that
  /// holds `carried` onto the other, a valley of 180° (the carried half on top).
  core::Status press(const core::Vec2& a, const core::Vec2& b, int carried);
  core::Expected<PaperState> stateAfter(uint64_t revision);
  void broadcast(const ros::WallTimerEvent&);
  /// Moves the frame; the time from which every broadcast has it there.
  ros::Time moveTo(const core::Vec3& position);
  /// The curved mode: waits until curved_mesh_solver (when one publishes `curved_mesh`) has
  /// bent the sheet with the frame where it has been since `since`.
  void awaitCurvedSheet(const ros::Time& since);

  ros::NodeHandle nh_;
  GripperOptions options_;
  ros::Subscriber state_sub_;
  ros::Subscriber sheet_sub_;
  ros::Time sheet_stamp_;  // of the newest curved_mesh
  ros::WallTimer timer_;
  tf2_ros::TransformBroadcaster tf_;
  std::mutex mutex_;
  PaperState state_;
  bool have_state_ = false;
  bool broadcasting_ = false;
  core::Vec3 gripper_ = core::Vec3::Zero();  // in the paper frame
};

}  // namespace virtual_origami
