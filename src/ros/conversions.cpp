#include "virtual_origami/ros/conversions.h"

#include <cmath>

#include <tf2/LinearMath/Quaternion.h>

namespace virtual_origami
{
geometry_msgs::Point toPoint(const core::Vec3& v)
{
  geometry_msgs::Point p;
  p.x = v.x();
  p.y = v.y();
  p.z = v.z();
  return p;
}

core::Vec3 toVec3(const geometry_msgs::Point& p) { return core::Vec3(p.x, p.y, p.z); }

geometry_msgs::TransformStamped frameTransform(const std::string& parent, const std::string& child,
                                               const core::Vec3& at, double yaw)
{
  geometry_msgs::TransformStamped t;
  t.header.stamp = ros::Time::now();
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform.translation.x = at.x();
  t.transform.translation.y = at.y();
  t.transform.translation.z = at.z();
  tf2::Quaternion q;
  q.setRPY(0, 0, yaw);
  t.transform.rotation.x = q.x();
  t.transform.rotation.y = q.y();
  t.transform.rotation.z = q.z();
  t.transform.rotation.w = q.w();
  return t;
}

PaperState toMessage(const core::Paper& paper, uint64_t revision, const Pins& pins)
{
  PaperState state;
  state.revision = revision;
  for (const core::Vertex& v : paper.vertices)
  {
    state.vertices_crease_pattern.push_back(toPoint(core::Vec3(v.crease_pattern.x(), v.crease_pattern.y(), 0.0)));
    state.vertices_folded.push_back(toPoint(v.folded));
  }
  for (const core::Edge& e : paper.edges)
  {
    Edge edge;
    edge.v0 = e.vertices[0];
    edge.v1 = e.vertices[1];
    edge.assignment = std::string(1, core::assignmentLetter(e.assignment));
    edge.fold_angle = e.fold_angle;
    edge.face_left = e.faces[0];
    edge.face_right = e.faces[1];
    edge.split = e.split;
    edge.has_target_angle = e.target_angle.has_value();
    edge.target_angle = e.target_angle.value_or(0.0);
    state.edges.push_back(edge);
  }
  for (const core::Face& f : paper.faces)
  {
    Face face;
    face.vertices.assign(f.vertices.begin(), f.vertices.end());
    state.faces.push_back(face);
  }
  for (const core::FaceOrder& o : paper.face_orders)
  {
    FaceOrder order;
    order.face = o.face;
    order.other = o.other;
    order.above = static_cast<int8_t>(o.above);
    state.face_orders.push_back(order);
  }
  for (const auto& [vertex, pin] : pins)
  {
    Pin p;
    p.vertex = vertex;
    p.frame_id = pin.frame_id;
    p.position = toPoint(pin.position);
    state.pins.push_back(p);
  }
  return state;
}

core::Expected<core::Paper> fromMessage(const PaperState& state)
{
  using Failure = core::Expected<core::Paper>;
  if (state.vertices_crease_pattern.size() != state.vertices_folded.size())
    return Failure::failure("vertices_crease_pattern and vertices_folded differ in length");
  core::Paper paper;
  for (size_t i = 0; i < state.vertices_folded.size(); ++i)
  {
    core::Vertex v;
    v.crease_pattern = toVec3(state.vertices_crease_pattern[i]).head<2>();
    v.folded = toVec3(state.vertices_folded[i]);
    if (!v.crease_pattern.allFinite() || !v.folded.allFinite())
      return Failure::failure("vertex " + std::to_string(i) + " has a non-finite coordinate");
    paper.vertices.push_back(v);
  }
  for (size_t i = 0; i < state.edges.size(); ++i)
  {
    const Edge& e = state.edges[i];
    const auto assignment = core::assignmentFromLetter(e.assignment);
    if (!assignment)
      return Failure::failure("edge " + std::to_string(i) + " has assignment \"" + e.assignment + "\"");
    core::Edge edge;
    edge.vertices = { e.v0, e.v1 };
    edge.assignment = *assignment;
    edge.fold_angle = e.fold_angle;
    edge.split = e.split;
    if (e.has_target_angle)
    {
      if (!std::isfinite(e.target_angle))
        return Failure::failure("edge " + std::to_string(i) + " has a non-finite target angle");
      edge.target_angle = e.target_angle;
    }
    paper.edges.push_back(edge);
  }
  for (const Face& f : state.faces)
    paper.faces.push_back({ std::vector<int>(f.vertices.begin(), f.vertices.end()), {} });
  for (const FaceOrder& o : state.face_orders)
    paper.face_orders.push_back({ o.face, o.other, o.above });
  // Link first: it checks every index, and the areas read the vertices faces name.
  if (paper.faces.empty())
    return Failure::failure("the paper has no faces");
  const core::Status linked = core::linkTopology(paper);
  if (!linked)
    return Failure::failure(linked.message());
  // The faces an edge names are derived again; a message that names others is not this paper.
  for (size_t i = 0; i < state.edges.size(); ++i)
  {
    const Edge& e = state.edges[i];
    const std::array<int, 2>& derived = paper.edges[i].faces;
    if (e.face_left != derived[0] || e.face_right != derived[1])
      return Failure::failure("edge " + std::to_string(i) + " names faces " + std::to_string(e.face_left) + " and " +
                              std::to_string(e.face_right) + ", but its faces are " + std::to_string(derived[0]) +
                              " and " + std::to_string(derived[1]));
  }
  for (size_t f = 0; f < paper.faces.size(); ++f)
    paper.sheet_area += paper.faceArea(static_cast<int>(f));
  return paper;
}

namespace
{
/// Where every vertex ended (recorded, else the state after the operation): what a replay takes.
void recordFolded(const core::Operation& op, const core::Paper* after, Operation& msg)
{
  for (const core::Vec3& p : op.folded)
    msg.folded.push_back(toPoint(p));
  if (op.folded.empty() && after)
    for (const core::Vertex& v : after->vertices)
      msg.folded.push_back(toPoint(v.folded));
}
}  // namespace

Operation toMessage(const core::Operation& op, const core::Paper* after)
{
  Operation msg;
  msg.revision = op.revision;
  msg.type = core::kindName(op.kind);
  msg.face = -1;
  msg.axis_edge = -1;
  msg.vertex = -1;
  switch (op.kind)
  {
    case core::Operation::Kind::Crease:
      msg.start = toPoint(op.crease.start);
      msg.end = toPoint(op.crease.end);
      msg.has_eye = op.crease.eye.has_value();
      if (op.crease.eye)
        msg.eye = toPoint(*op.crease.eye);
      msg.snap = op.crease.snap;
      break;
    case core::Operation::Kind::Rotate:
      msg.face = op.rotate.face;
      msg.axis_edge = op.rotate.axis_edge;
      msg.click = toPoint(op.rotate.click);
      msg.angle = op.rotate.angle;
      msg.picked_layers_only = !op.rotate.carry_stack;
      recordFolded(op, after, msg);
      break;
    case core::Operation::Kind::FlatFold:
      for (const core::CreaseLineAngle& line : op.flat_fold.creases)
      {
        msg.crease_starts.push_back(toPoint(core::Vec3(line.start.x(), line.start.y(), 0.0)));
        msg.crease_ends.push_back(toPoint(core::Vec3(line.end.x(), line.end.y(), 0.0)));
        msg.crease_angles.push_back(line.angle);
      }
      msg.fixed = toPoint(core::Vec3(op.flat_fold.fixed_point.x(), op.flat_fold.fixed_point.y(), 0.0));
      break;
    case core::Operation::Kind::DragVertex:
      msg.vertex = op.drag.vertex;
      msg.position = toPoint(op.drag.position);
      break;
    case core::Operation::Kind::Load:
      msg.path = op.path;
      break;
    case core::Operation::Kind::Reset:
      msg.size = op.size;
      break;
    case core::Operation::Kind::AssignmentFold:
      msg.fraction = op.fraction;
      recordFolded(op, after, msg);
      break;
    case core::Operation::Kind::Pull:
      for (const core::PullTarget& target : op.pull)
      {
        msg.vertices.push_back(target.vertex);
        msg.positions.push_back(toPoint(target.position));
      }
      break;
    case core::Operation::Kind::KeepBend:
      for (const core::Vec2& p : op.bend.points)
        msg.bend_points.push_back(toPoint(core::Vec3(p.x(), p.y(), 0.0)));
      for (const std::array<int, 3>& t : op.bend.triangles)
        msg.bend_triangles.insert(msg.bend_triangles.end(), t.begin(), t.end());
      for (const core::Vec3& p : op.bend.positions)
        msg.bend_positions.push_back(toPoint(p));
      break;
    default:
      break;
  }
  return msg;
}

core::Expected<core::FlatFoldRequest> flatFoldRequest(const std::vector<geometry_msgs::Point>& starts,
                                                     const std::vector<geometry_msgs::Point>& ends,
                                                     const std::vector<double>& angles,
                                                     const geometry_msgs::Point& fixed)
{
  using Failure = core::Expected<core::FlatFoldRequest>;
  if (starts.size() != ends.size() || starts.size() != angles.size())
    return Failure::failure("a fold on chosen creases needs one end and one angle per start (" +
                            std::to_string(starts.size()) + " starts, " + std::to_string(ends.size()) + " ends, " +
                            std::to_string(angles.size()) + " angles)");
  if (starts.empty())
    return Failure::failure("no creases are chosen: mark at least one crease to fold");
  core::FlatFoldRequest request;
  for (size_t k = 0; k < starts.size(); ++k)
    request.creases.push_back({ toVec3(starts[k]).head<2>(), toVec3(ends[k]).head<2>(), angles[k] });
  request.fixed_point = toVec3(fixed).head<2>();
  return request;
}

core::Expected<core::Operation> fromMessage(const Operation& msg)
{
  using Failure = core::Expected<core::Operation>;
  core::Operation op;
  op.revision = msg.revision;
  bool known = false;
  for (core::Operation::Kind kind :
       { core::Operation::Kind::Crease, core::Operation::Kind::Rotate, core::Operation::Kind::Squash,
         core::Operation::Kind::Undo, core::Operation::Kind::Redo, core::Operation::Kind::Reset,
         core::Operation::Kind::Load, core::Operation::Kind::Pull, core::Operation::Kind::AssignmentFold,
         core::Operation::Kind::FlatFold, core::Operation::Kind::DragVertex, core::Operation::Kind::KeepBend })
    if (msg.type == core::kindName(kind))
    {
      op.kind = kind;
      known = true;
    }
  if (!known)
    return Failure::failure("\"" + msg.type + "\" is not an operation of the model's history");
  switch (op.kind)
  {
    case core::Operation::Kind::Crease:
      op.crease.start = toVec3(msg.start);
      op.crease.end = toVec3(msg.end);
      if (msg.has_eye)
        op.crease.eye = toVec3(msg.eye);
      op.crease.snap = msg.snap;
      break;
    case core::Operation::Kind::Rotate:
      op.rotate.face = msg.face;
      op.rotate.axis_edge = msg.axis_edge;
      op.rotate.click = toVec3(msg.click);
      op.rotate.angle = msg.angle;
      op.rotate.carry_stack = !msg.picked_layers_only;
      for (const geometry_msgs::Point& p : msg.folded)
        op.folded.push_back(toVec3(p));
      break;
    case core::Operation::Kind::Load:
      op.path = msg.path;
      break;
    case core::Operation::Kind::Reset:
      op.size = msg.size;
      break;
    case core::Operation::Kind::AssignmentFold:
      op.fraction = msg.fraction;
      for (const geometry_msgs::Point& p : msg.folded)
        op.folded.push_back(toVec3(p));
      break;
    case core::Operation::Kind::Pull:
      if (msg.vertices.size() != msg.positions.size())
        return Failure::failure("a pull needs one position per vertex");
      for (size_t i = 0; i < msg.vertices.size(); ++i)
        op.pull.push_back({ msg.vertices[i], toVec3(msg.positions[i]) });
      break;
    case core::Operation::Kind::FlatFold:
    {
      core::Expected<core::FlatFoldRequest> request =
          flatFoldRequest(msg.crease_starts, msg.crease_ends, msg.crease_angles, msg.fixed);
      if (!request)
        return Failure::failure(request.message());
      op.flat_fold = std::move(*request);
      break;
    }
    case core::Operation::Kind::DragVertex:
      op.drag = { msg.vertex, toVec3(msg.position) };
      break;
    case core::Operation::Kind::KeepBend:
    {
      core::Expected<core::BentSheet> sheet = bentSheet(msg.bend_points, msg.bend_triangles, msg.bend_positions);
      if (!sheet)
        return Failure::failure(sheet.message());
      op.bend = std::move(*sheet);
      break;
    }
    default:
      break;
  }
  return op;
}

core::Expected<core::BentSheet> bentSheet(const std::vector<geometry_msgs::Point>& points,
                                          const std::vector<int>& triangles,
                                          const std::vector<geometry_msgs::Point>& positions)
{
  if (triangles.size() % 3 != 0)
    return core::Expected<core::BentSheet>::failure("a bent sheet needs three node indices per triangle (" +
                                                    std::to_string(triangles.size()) + " given)");
  core::BentSheet sheet;
  for (const geometry_msgs::Point& p : points)
    sheet.points.emplace_back(p.x, p.y);
  for (size_t i = 0; i < triangles.size(); i += 3)
    sheet.triangles.push_back({ triangles[i], triangles[i + 1], triangles[i + 2] });
  for (const geometry_msgs::Point& p : positions)
    sheet.positions.push_back(toVec3(p));
  return sheet;
}

}  // namespace virtual_origami
