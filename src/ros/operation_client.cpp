#include "virtual_origami/ros/operation_client.h"

#include <ros/service.h>
#include <std_srvs/Trigger.h>
#include <virtual_origami/Crease.h>
#include <virtual_origami/DragVertex.h>
#include <virtual_origami/FlatFold.h>
#include <virtual_origami/FoldByAssignment.h>
#include <virtual_origami/KeepBend.h>
#include <virtual_origami/Load.h>
#include <virtual_origami/PinVertex.h>
#include <virtual_origami/Pull.h>
#include <virtual_origami/Rotate.h>
#include <virtual_origami/Save.h>

#include "virtual_origami/ros/service_call.h"

namespace virtual_origami
{
namespace
{
template <class Service>
core::Status call(ros::NodeHandle& nh, const std::string& name, Service& srv)
{
  if (!callService(nh.resolveName(name), srv))
    return core::failure("the service " + nh.resolveName(name) + " did not answer");
  if (!srv.response.success)
    return core::failure(name + " refused: " + srv.response.message);
  return core::success();
}
}  // namespace

OperationClient::OperationClient(const std::string& ns) : nh_(ns) {}

bool OperationClient::waitForServices(double seconds)
{
  for (const char* name : { "crease", "rotate", "squash", "undo", "redo", "reset", "pin", "pull", "load",
                            "fold_by_assignment", "flat_fold", "drag_vertex", "keep_bend" })
    if (!ros::service::waitForService(nh_.resolveName(name), ros::Duration(seconds)))
      return false;
  return true;
}

core::Status OperationClient::load(const std::string& path)
{
  Load srv;
  srv.request.path = path;
  return call(nh_, "load", srv);
}

core::Status OperationClient::save(const std::string& path)
{
  Save srv;
  srv.request.path = path;
  return call(nh_, "save", srv);
}

core::Status OperationClient::apply(const Operation& op, int animation_steps, double animation_seconds,
                                    std::optional<double> folded_from)
{
  if (op.type == "crease")
  {
    Crease srv;
    srv.request.start = op.start;
    srv.request.end = op.end;
    srv.request.has_eye = op.has_eye;
    srv.request.eye = op.eye;
    srv.request.snap = op.snap;
    return call(nh_, "crease", srv);
  }
  if (op.type == "rotate")
  {
    Rotate srv;
    srv.request.face = op.face;
    srv.request.axis_edge = op.axis_edge;
    srv.request.click = op.click;
    srv.request.picked_layers_only = op.picked_layers_only;
    for (int i = 1; i < animation_steps; ++i)
    {
      srv.request.angle = op.angle * i / animation_steps;
      srv.request.commit = false;
      callService(nh_.resolveName("rotate"), srv);  // a preview that fails only shows less
      ros::WallDuration(animation_seconds / animation_steps).sleep();
    }
    srv.request.angle = op.angle;
    srv.request.commit = true;
    srv.request.positions = op.folded;  // where it ended: taken, not solved again
    return call(nh_, "rotate", srv);
  }
  if (op.type == "pin")
  {
    // A pin on a tf frame is held in place instead: the frame is not there on replay, and the
    // recorded pulls move the vertex as the frame did.
    PinVertex srv;
    srv.request.vertex = op.vertex;
    srv.request.release = op.release;
    return call(nh_, "pin", srv);
  }
  if (op.type == "pull")
  {
    Pull srv;
    srv.request.vertices = op.vertices;
    srv.request.positions = op.positions;
    return call(nh_, "pull", srv);
  }
  if (op.type == "fold_by_assignment")
  {
    // Animated only from where the paper was (its recorded state): from a guess the previews
    // would show a motion that never happened.
    FoldByAssignment srv;
    for (int i = 1; folded_from && i < animation_steps; ++i)
    {
      srv.request.fraction = *folded_from + (op.fraction - *folded_from) * i / animation_steps;
      srv.request.preview = true;
      callService(nh_.resolveName("fold_by_assignment"), srv);  // a preview that fails only shows less
      ros::WallDuration(animation_seconds / animation_steps).sleep();
    }
    srv.request.fraction = op.fraction;
    srv.request.preview = false;
    srv.request.keep = true;  // it was accepted (or kept on purpose) when it was recorded
    srv.request.positions = op.folded;  // where it ended: taken, not solved again
    return call(nh_, "fold_by_assignment", srv);
  }
  if (op.type == "flat_fold")
  {
    // Shown folding from the paper as it is: the previews are frames of the same fold.
    FlatFold srv;
    srv.request.starts = op.crease_starts;
    srv.request.ends = op.crease_ends;
    srv.request.angles = op.crease_angles;
    srv.request.fixed = op.fixed;
    for (int i = 1; i < animation_steps; ++i)
    {
      srv.request.fraction = static_cast<double>(i) / animation_steps;
      srv.request.commit = false;
      callService(nh_.resolveName("flat_fold"), srv);  // a preview that fails only shows less
      ros::WallDuration(animation_seconds / animation_steps).sleep();
    }
    srv.request.fraction = 1.0;
    srv.request.commit = true;
    return call(nh_, "flat_fold", srv);
  }
  if (op.type == "drag_vertex")
  {
    DragVertex srv;
    srv.request.vertex = op.vertex;
    srv.request.position = op.position;
    srv.request.commit = true;
    return call(nh_, "drag_vertex", srv);
  }
  if (op.type == "keep_bend")
  {
    KeepBend srv;
    srv.request.points = op.bend_points;
    srv.request.triangles = op.bend_triangles;
    srv.request.positions = op.bend_positions;
    return call(nh_, "keep_bend", srv);
  }
  if (op.type == "load")
    return load(op.path);
  if (op.type == "squash" || op.type == "undo" || op.type == "redo" || op.type == "reset")
  {
    std_srvs::Trigger srv;
    return call(nh_, op.type, srv);
  }
  return core::failure("unknown operation type \"" + op.type + "\"");
}

}  // namespace virtual_origami
