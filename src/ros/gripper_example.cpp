#include "virtual_origami/ros/gripper_example.h"

#include <algorithm>
#include <cmath>

#include <std_srvs/Trigger.h>
#include <virtual_origami/Crease.h>
#include <virtual_origami/PinVertex.h>
#include <virtual_origami/Rotate.h>

#include "virtual_origami/ros/conversions.h"

namespace virtual_origami
{
namespace
{
core::Vec2 crease_pattern(const PaperState& state, int v)
{
  return { state.vertices_crease_pattern[v].x, state.vertices_crease_pattern[v].y };
}

core::Vec3 folded(const PaperState& state, int v)
{
  return toVec3(state.vertices_folded[v]);
}

int vertexAt(const PaperState& state, const core::Vec2& point, double tolerance)
{
  for (size_t v = 0; v < state.vertices_crease_pattern.size(); ++v)
    if ((crease_pattern(state, static_cast<int>(v)) - point).norm() < tolerance)
      return static_cast<int>(v);
  return -1;
}

/// Front normal of the face that uses `vertex` (Newell's method over its folded loop).
core::Vec3 normalAt(const PaperState& state, int vertex)
{
  for (const Face& face : state.faces)
    if (std::find(face.vertices.begin(), face.vertices.end(), vertex) != face.vertices.end())
    {
      core::Vec3 n = core::Vec3::Zero();
      for (size_t i = 0; i < face.vertices.size(); ++i)
        n += folded(state, face.vertices[i]).cross(folded(state, face.vertices[(i + 1) % face.vertices.size()]));
      return n.normalized();
    }
  return core::Vec3::UnitZ();
}
}  // namespace

GripperExample::GripperExample(ros::NodeHandle nh, GripperOptions options) : nh_(nh), options_(std::move(options))
{
  state_sub_ = nh_.subscribe<PaperState>("state", 10, [this](const PaperState::ConstPtr& s) {
    std::lock_guard<std::mutex> lock(mutex_);
    state_ = *s;
    have_state_ = true;
  });
  if (options_.curved)
    sheet_sub_ = nh_.subscribe<visualization_msgs::MarkerArray>(
        "curved_mesh", 10, [this](const visualization_msgs::MarkerArray::ConstPtr& sheet) {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const visualization_msgs::Marker& m : sheet->markers)
            sheet_stamp_ = std::max(sheet_stamp_, m.header.stamp);
        });
  timer_ = nh_.createWallTimer(ros::WallDuration(1.0 / std::max(options_.rate, 1.0)), &GripperExample::broadcast, this);
}

void GripperExample::broadcast(const ros::WallTimerEvent&)
{
  std::lock_guard<std::mutex> lock(mutex_);
  if (!broadcasting_)
    return;
  tf_.sendTransform(frameTransform(options_.paper_frame, options_.frame, gripper_));
}

ros::Time GripperExample::moveTo(const core::Vec3& position)
{
  std::lock_guard<std::mutex> lock(mutex_);
  gripper_ = position;
  broadcasting_ = true;
  return ros::Time::now();
}

void GripperExample::awaitCurvedSheet(const ros::Time& since)
{
  if (sheet_sub_.getNumPublishers() == 0)
    return;  // no curved_mesh_solver: nothing to wait for
  if (waitUntil([&] { return sheet_stamp_ > since; }))
    return;
  ROS_WARN("gripper_example: the curved sheet did not follow the gripper to the end of its path within %g s; "
           "pressing the fold anyway",
           options_.timeout);
}

core::Expected<PaperState> GripperExample::stateAfter(uint64_t revision)
{
  PaperState state;
  if (waitUntil([&] {
        if (!have_state_ || state_.revision < revision)
          return false;
        state = state_;
        return true;
      }))
    return state;
  return core::Expected<PaperState>::failure("no state of revision " + std::to_string(revision) + " on " +
                                             state_sub_.getTopic() + " within " + std::to_string(options_.timeout) +
                                             " s");
}

core::Status GripperExample::callPin(int vertex, const std::string& frame, bool release)
{
  PinVertex pin;
  pin.request.vertex = vertex;
  pin.request.frame_id = frame;
  pin.request.release = release;
  if (const core::Status called = call("pin", pin); !called)
    return called;
  if (!pin.response.success)
    return core::failure("pin vertex " + std::to_string(vertex) + ": " + pin.response.message);
  return core::success();
}

core::Expected<PaperState> GripperExample::creaseMiddle(const core::Vec2& a, const core::Vec2& b)
{
  Crease crease;
  crease.request.start.x = a.x();
  crease.request.start.y = a.y();
  crease.request.end.x = b.x();
  crease.request.end.y = b.y();
  if (const core::Status called = call("crease", crease); !called)
    return core::Expected<PaperState>::failure(called.message());
  if (!crease.response.success)
    return core::Expected<PaperState>::failure("creasing the middle line: " + crease.response.message);
  return stateAfter(crease.response.revision);
}

core::Status GripperExample::press(const core::Vec2& a, const core::Vec2& b, int carried)
{
  core::Expected<PaperState> state = stateAfter(0);
  if (!state)
    return core::failure(state.message());
  const double tolerance = 1e-6 * std::max(a.norm(), b.norm());
  if (vertexAt(*state, a, tolerance) < 0 || vertexAt(*state, b, tolerance) < 0)
  {
    state = creaseMiddle(a, b);
    if (!state)
      return core::failure(state.message());
  }
  const int va = vertexAt(*state, a, tolerance), vb = vertexAt(*state, b, tolerance);
  int axis = -1;
  for (size_t e = 0; e < state->edges.size(); ++e)
  {
    const Edge& edge = state->edges[e];
    if ((edge.v0 == va && edge.v1 == vb) || (edge.v0 == vb && edge.v1 == va))
      axis = static_cast<int>(e);
  }
  int face = -1;
  for (size_t f = 0; f < state->faces.size(); ++f)
    if (std::find(state->faces[f].vertices.begin(), state->faces[f].vertices.end(), carried) !=
        state->faces[f].vertices.end())
      face = static_cast<int>(f);
  if (axis < 0 || face < 0 || state->edges[axis].face_left < 0 || state->edges[axis].face_right < 0)
    return core::failure("the middle line is not one crease of the sheet; cannot fold it");
  const double turn = M_PI - state->edges[axis].fold_angle;  // to a valley of 180°
  if (std::abs(turn) < 1e-9)
    return core::success();
  Rotate rotate;
  rotate.request.face = face;
  rotate.request.axis_edge = axis;
  rotate.request.angle = turn;
  rotate.request.commit = true;
  if (const core::Status called = call("rotate", rotate); !called)
    return called;
  if (!rotate.response.success)
    return core::failure("folding the middle line: " + rotate.response.message);
  state = stateAfter(rotate.response.revision);
  return state ? core::success() : core::failure(state.message());
}

core::Status GripperExample::run()
{
  if (options_.corner < 0 || options_.corner > 3)
    return core::failure("corner must be 0, 1, 2 or 3, not " + std::to_string(options_.corner));
  if (!(options_.duration > 0) || !(options_.rate > 0))
    return core::failure("duration and rate must be positive");
  core::Expected<PaperState> state = stateAfter(0);
  if (!state)
    return core::failure(state.message());
  double side = 0.0;
  for (const auto& p : state->vertices_crease_pattern)
    side = std::max(side, std::max(p.x, p.y));
  const double tolerance = 1e-6 * side;
  const core::Vec2 corner((options_.corner == 1 || options_.corner == 2) ? side : 0.0,
                          options_.corner >= 2 ? side : 0.0);
  // The middle line between the grasped corner and its neighbour along x.
  const core::Vec2 line_a(side / 2, 0.0), line_b(side / 2, side);

  const bool curved = options_.curved;
  if (!curved && options_.crease &&
      (vertexAt(*state, line_a, tolerance) < 0 || vertexAt(*state, line_b, tolerance) < 0))
  {
    state = creaseMiddle(line_a, line_b);
    if (!state)
      return core::failure(state.message());
  }
  const int grasped = vertexAt(*state, corner, tolerance);
  const int axis_a = vertexAt(*state, line_a, tolerance), axis_b = vertexAt(*state, line_b, tolerance);
  // Uncreased, the middle line is where the corners either side of it meet.
  const int near_a = vertexAt(*state, { corner.x(), 0.0 }, tolerance),
            far_a = vertexAt(*state, { side - corner.x(), 0.0 }, tolerance);
  const int near_b = vertexAt(*state, { corner.x(), side }, tolerance),
            far_b = vertexAt(*state, { side - corner.x(), side }, tolerance);
  if (grasped < 0 || (!curved && (axis_a < 0 || axis_b < 0)) ||
      (curved && (axis_a < 0 || axis_b < 0) && (near_a < 0 || far_a < 0 || near_b < 0 || far_b < 0)))
    return core::failure("the sheet has no vertex at the corner or at the ends of the middle line");

  // The other hand holds the far half (the middle line included) where it lies; in the curved
  // mode only the far edge, so that the sheet is free to bend.
  std::vector<int> held;
  const double reach = curved ? side - tolerance : side / 2 - tolerance;
  for (size_t v = 0; v < state->vertices_crease_pattern.size(); ++v)
    if (std::abs(crease_pattern(*state, static_cast<int>(v)).x() - corner.x()) >= reach)
      held.push_back(static_cast<int>(v));
  for (int v : held)
    if (const core::Status pinned = callPin(v, "", false); !pinned)
      return pinned;

  // The half circle about the middle line: from the corner, up along the sheet's front
  // normal, onto the far half.
  const core::Vec3 a = axis_a >= 0 && axis_b >= 0 ? folded(*state, axis_a) :
                                                    core::Vec3((folded(*state, near_a) + folded(*state, far_a)) / 2);
  const core::Vec3 b = axis_a >= 0 && axis_b >= 0 ? folded(*state, axis_b) :
                                                    core::Vec3((folded(*state, near_b) + folded(*state, far_b)) / 2);
  const core::Vec3 start = folded(*state, grasped);
  const core::Vec3 direction = (b - a).normalized();
  const core::Vec3 foot = a + direction * direction.dot(start - a);
  const core::Vec3 out = start - foot;
  const core::Vec3 normal = normalAt(*state, grasped);
  const core::Vec3 up = (normal - normal.dot(direction) * direction).normalized() * out.norm();
  const auto along = [&](double angle) { return core::Vec3(foot + out * std::cos(angle) + up * std::sin(angle)); };

  moveTo(start);
  if (const core::Status pinned = callPin(grasped, options_.frame, false); !pinned)
    return pinned;
  ROS_INFO("gripper_example: holding vertex %d at corner (%g, %g) on %s; folding over %g s%s", grasped, corner.x(),
           corner.y(), options_.frame.c_str(), options_.duration, curved ? ", the sheet bending" : "");
  const int steps = std::max(1, static_cast<int>(std::ceil(options_.duration * options_.rate)));
  ros::WallRate rate(options_.rate);
  ros::Time at_end;
  for (int k = 1; k <= steps && ros::ok(); ++k)
  {
    at_end = moveTo(along(M_PI * k / steps));
    rate.sleep();
  }
  if (curved)
  {
    // The model's one rigid face cannot follow the frame (only curved_mesh_solver's sheet
    // bends); at the end of the path, once the sheet is there, the gripper lets go of the
    // corner and presses the fold.
    awaitCurvedSheet(at_end);
    if (const core::Status released = callPin(grasped, "", true); !released)
      return released;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      broadcasting_ = false;
    }
    if (const core::Status pressed = press(line_a, line_b, grasped); !pressed)
      return pressed;
    for (int v : held)
      if (const core::Status released = callPin(v, "", true); !released)
        return released;
    ROS_INFO("gripper_example: bent the sheet over, pressed the fold and released");
    return core::success();
  }

  // Let the model catch up with the end of the trajectory before letting go.
  const core::Vec3 end = along(M_PI);
  const bool arrived = waitUntil([&] {
    return grasped < static_cast<int>(state_.vertices_folded.size()) &&
           (folded(state_, grasped) - end).norm() < tolerance;
  });
  if (!arrived)
    return core::failure("the paper did not follow the gripper to the end of its path within " +
                         std::to_string(options_.timeout) + " s");
  if (const core::Status released = callPin(grasped, "", true); !released)
    return released;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    broadcasting_ = false;
  }
  for (int v : held)
    if (const core::Status released = callPin(v, "", true); !released)
      return released;
  ROS_INFO("gripper_example: folded in half and released");
  return core::success();
}

}  // namespace virtual_origami
