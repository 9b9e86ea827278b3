#include "virtual_origami/ros/interaction_markers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <visualization_msgs/InteractiveMarkerControl.h>

#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/markers.h"

namespace virtual_origami
{
namespace
{
using visualization_msgs::Marker;

/// A marker of the interaction: over the sheet's markers, never hidden in them.
Marker overSheet(const InteractionStyle& style, const ros::Time& stamp, const std::string& ns, int type)
{
  Marker m = baseMarker(style.frame_id, stamp, ns, type, style.line_width, rgba(0, 0, 0));
  m.pose.position.z = style.pick_lift;
  return m;
}

Marker points(const InteractionStyle& style, const ros::Time& stamp, const std::string& ns,
              const std::vector<core::Vec3>& at, const std_msgs::ColorRGBA& color, double size)
{
  Marker m = overSheet(style, stamp, ns, Marker::SPHERE_LIST);
  m.scale.x = m.scale.y = m.scale.z = size;
  m.color = color;
  for (const core::Vec3& p : at)
    m.points.push_back(toPoint(p));
  return m;
}

/// A dashed segment as a LINE_LIST: guides read as guides, not as creases.
void addDashed(Marker& m, const core::Vec3& a, const core::Vec3& b, double dash)
{
  const double length = (b - a).norm();
  const int n = std::max(1, static_cast<int>(length / dash));
  for (int i = 0; i < n; i += 2)
  {
    m.points.push_back(toPoint(a + (b - a) * (static_cast<double>(i) / n)));
    m.points.push_back(toPoint(a + (b - a) * (static_cast<double>(i + 1) / n)));
  }
}

void addSnapGuides(visualization_msgs::MarkerArray& array, const core::Snap& snap, const std::string& which,
                   const InteractionStyle& style, const ros::Time& stamp)
{
  if (snap.kind == core::SnapKind::None)
    return;
  const auto colour = snap.kind == core::SnapKind::Vertex       ? rgba(0.85f, 0.1f, 0.1f) :
                      snap.kind == core::SnapKind::EdgeDivision ? rgba(0.1f, 0.6f, 0.2f) :
                                                                  rgba(0.55f, 0.2f, 0.75f);
  array.markers.push_back(points(style, stamp, which + "_snap", { snap.point }, colour, 1.6 * style.point_size));
  if (!snap.guide_points.empty())
    array.markers.push_back(points(style, stamp, which + "_guide_points", snap.guide_points,
                                   rgba(0.1f, 0.6f, 0.2f, 0.7f), style.point_size));
  if (!snap.guide_lines.empty())
  {
    Marker lines = overSheet(style, stamp, which + "_guide_lines", Marker::LINE_LIST);
    lines.scale.x = 0.5 * style.line_width;
    lines.color = rgba(0.55f, 0.2f, 0.75f, 0.8f);
    for (const core::Segment3& s : snap.guide_lines)
      addDashed(lines, s.a, s.b, 0.02);
    array.markers.push_back(lines);
  }
}
}  // namespace

visualization_msgs::InteractiveMarker paperInteractiveMarker(const core::Paper& paper, const std::string& description,
                                                             const InteractionStyle& style)
{
  visualization_msgs::InteractiveMarker im;
  im.header.frame_id = style.frame_id;  // stamp zero: rviz follows the frame as it moves
  im.name = style.marker_name;
  im.description = description;
  im.pose.orientation.w = 1.0;
  im.scale = static_cast<float>(paper.scale());

  Marker mesh;
  mesh.type = Marker::TRIANGLE_LIST;
  mesh.pose.orientation.w = 1.0;
  mesh.scale.x = mesh.scale.y = mesh.scale.z = 1.0;
  mesh.color = rgba(0.0f, 0.0f, 0.0f, style.pick_alpha);
  core::Vec3 lo = core::Vec3::Constant(INFINITY), hi = -lo;
  // Each face twice, off both its sides along its normal: whichever side the eye sees, a copy
  // lies in front of the drawn paper (a copy lifted along z lay in a standing face, where
  // rviz picked the drawing instead: 0 of 25 points on a half turned to 90°).
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const core::Face& face = paper.faces[f];
    core::Vec3 n = paper.faceNormal(static_cast<int>(f));
    if (n.z() < 0)
      n = -n;  // the first copy over the sheet: its first point's z is the lift of a flat sheet
    for (double side : { 1.0, -1.0 })
      for (size_t i = 1; i + 1 < face.vertices.size(); ++i)  // a fan: faces are convex
        for (int v : { face.vertices[0], face.vertices[i], face.vertices[i + 1] })
          mesh.points.push_back(toPoint(paper.vertices[v].folded + side * style.pick_lift * n));
  }
  for (const core::Vertex& v : paper.vertices)
  {
    lo = lo.cwiseMin(v.folded);
    hi = hi.cwiseMax(v.folded);
  }
  if (!paper.vertices.empty())
  {
    // The margin lies on the table below the sheet: a line may start or end just off it.
    const double m = style.margin * paper.scale();
    const double z = lo.z() + style.pick_lift - 1e-4 * paper.scale();
    const core::Vec3 a(lo.x() - m, lo.y() - m, z), b(hi.x() + m, lo.y() - m, z), c(hi.x() + m, hi.y() + m, z),
        d(lo.x() - m, hi.y() + m, z);
    for (const core::Vec3* p : { &a, &b, &c, &a, &c, &d })
      mesh.points.push_back(toPoint(*p));
  }

  visualization_msgs::InteractiveMarkerControl control;
  control.name = "drag";
  control.interaction_mode = visualization_msgs::InteractiveMarkerControl::MOVE_PLANE;
  if (style.view_facing_drag)
  {
    // The plane's normal (the control's x axis) towards the camera; the sheet's mesh stays put.
    control.orientation_mode = visualization_msgs::InteractiveMarkerControl::VIEW_FACING;
    control.independent_marker_orientation = true;
    control.orientation.w = 1.0;
  }
  else
  {
    // The control's x axis is the plane's normal: turned onto z, the mouse drags in the sheet's plane.
    control.orientation.w = std::sqrt(0.5);
    control.orientation.y = -std::sqrt(0.5);
  }
  control.always_visible = true;
  control.markers.push_back(mesh);
  im.controls.push_back(control);
  return im;
}

visualization_msgs::MarkerArray creaseDragMarkers(const core::CreaseDrag& drag, const InteractionStyle& style,
                                                  const ros::Time& stamp)
{
  visualization_msgs::MarkerArray array = clearedMarkers(style, stamp);
  Marker line = overSheet(style, stamp, "line", Marker::LINE_LIST);
  line.color = rgba(0.9f, 0.45f, 0.0f);
  line.points = { toPoint(drag.start.point), toPoint(drag.end.point) };
  array.markers.push_back(line);
  addSnapGuides(array, drag.start, "start", style, stamp);
  addSnapGuides(array, drag.end, "end", style, stamp);
  return array;
}

visualization_msgs::MarkerArray rotationDragMarkers(const core::RotationRing& ring, double angle,
                                                    const InteractionStyle& style, const ros::Time& stamp)
{
  visualization_msgs::MarkerArray array = clearedMarkers(style, stamp);
  Marker axis = overSheet(style, stamp, "axis", Marker::LINE_LIST);
  axis.scale.x = 2.5 * style.line_width;
  axis.color = rgba(1.0f, 0.75f, 0.0f);
  axis.points = { toPoint(ring.axis_a), toPoint(ring.axis_b) };
  array.markers.push_back(axis);

  Marker circle = overSheet(style, stamp, "ring", Marker::LINE_STRIP);
  circle.color = rgba(0.2f, 0.4f, 0.9f, 0.8f);
  const int segments = 72;
  for (int i = 0; i <= segments; ++i)
  {
    const double a = 2 * M_PI * i / segments;
    circle.points.push_back(toPoint(ring.centre + ring.radius * (std::cos(a) * ring.u + std::sin(a) * ring.w)));
  }
  array.markers.push_back(circle);

  Marker spokes = overSheet(style, stamp, "spokes", Marker::LINE_LIST);
  spokes.color = rgba(0.2f, 0.4f, 0.9f);
  const core::Vec3 now = core::ringPoint(ring, angle);
  spokes.points = { toPoint(ring.centre), toPoint(ring.press), toPoint(ring.centre), toPoint(now) };
  array.markers.push_back(spokes);
  array.markers.push_back(
      points(style, stamp, "pointer", { ring.press, now }, rgba(0.2f, 0.4f, 0.9f), 1.4 * style.point_size));

  Marker text = overSheet(style, stamp, "angle", Marker::TEXT_VIEW_FACING);
  text.scale.z = style.text_size;
  text.color = rgba(0.1f, 0.1f, 0.3f);
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%+.0f°", angle * 180.0 / M_PI);
  text.text = buffer;
  text.pose.position = toPoint(now + 1.5 * style.text_size * ring.w);
  array.markers.push_back(text);
  return array;
}

visualization_msgs::MarkerArray namedAxisMarkers(const core::Vec3& a, const core::Vec3& b,
                                                 const InteractionStyle& style, const ros::Time& stamp)
{
  visualization_msgs::MarkerArray array;
  Marker axis = overSheet(style, stamp, "named_axis", Marker::LINE_LIST);
  axis.scale.x = 2.5 * style.line_width;
  axis.color = rgba(0.9f, 0.3f, 0.0f);
  axis.points = { toPoint(a), toPoint(b) };
  array.markers.push_back(axis);
  return array;
}

namespace
{
/// Marks that stay on show while the user clicks lie between the paper's drawn layers and the
/// pickable copy over them: rviz gives a click on a marker in front of the copy to the marker.
double underPickable(const InteractionStyle& style)
{
  return style.pick_lift - 0.4 * (style.pick_lift - style.drawn_top);
}

/// A face's outline as a LINE_LIST, a little inside it (so that it shows beside its neighbours').
void addOutline(Marker& m, const core::Paper& paper, int face)
{
  const std::vector<int>& vs = paper.faces[face].vertices;
  const core::Vec3 c = paper.faceCentroid(face);
  for (size_t i = 0; i < vs.size(); ++i)
  {
    const core::Vec3 a = paper.vertices[vs[i]].folded, b = paper.vertices[vs[(i + 1) % vs.size()]].folded;
    m.points.push_back(toPoint(a + 0.06 * (c - a)));
    m.points.push_back(toPoint(b + 0.06 * (c - b)));
  }
}
}  // namespace

visualization_msgs::MarkerArray chosenCreaseMarkers(const core::Paper& paper,
                                                    const std::vector<std::pair<int, core::CreaseMark>>& marks,
                                                    int picked_edge, int keep_face, const InteractionStyle& style,
                                                    const ros::Time& stamp)
{
  visualization_msgs::MarkerArray array;
  Marker valley = overSheet(style, stamp, "marks", Marker::LINE_LIST);
  valley.id = 0;
  valley.scale.x = 2.0 * style.line_width;
  valley.color = rgba(0.1f, 0.3f, 0.9f);
  Marker mountain = valley;
  mountain.id = 1;
  mountain.color = rgba(0.9f, 0.1f, 0.1f);
  Marker unfold = valley;
  unfold.id = 2;
  unfold.color = rgba(0.45f, 0.45f, 0.45f);
  for (const auto& [edge, mark] : marks)
  {
    const core::Vec3& a = paper.vertices[paper.edges[edge].vertices[0]].folded;
    const core::Vec3& b = paper.vertices[paper.edges[edge].vertices[1]].folded;
    if (mark == core::CreaseMark::Unfold)
      addDashed(unfold, a, b, 0.02 * paper.scale());
    else
    {
      Marker& m = mark == core::CreaseMark::Valley ? valley : mountain;
      m.points.push_back(toPoint(a));
      m.points.push_back(toPoint(b));
    }
  }
  Marker picked = overSheet(style, stamp, "marks", Marker::LINE_LIST);
  picked.id = 3;
  picked.scale.x = 4.0 * style.line_width;
  picked.color = rgba(1.0f, 0.85f, 0.0f, 0.6f);
  if (picked_edge >= 0 && static_cast<size_t>(picked_edge) < paper.edges.size())
    for (int v : paper.edges[picked_edge].vertices)
      picked.points.push_back(toPoint(paper.vertices[v].folded));
  Marker keep = overSheet(style, stamp, "marks", Marker::LINE_LIST);
  keep.id = 4;
  keep.scale.x = 1.5 * style.line_width;
  keep.color = rgba(0.1f, 0.7f, 0.2f);
  if (keep_face >= 0 && static_cast<size_t>(keep_face) < paper.faces.size())
    addOutline(keep, paper, keep_face);
  for (Marker* m : { &valley, &mountain, &unfold, &picked, &keep })
  {
    m->pose.position.z = underPickable(style);
    if (m->points.empty())
      m->action = Marker::DELETE;  // what is no longer marked goes
    array.markers.push_back(*m);
  }
  return array;
}

visualization_msgs::MarkerArray pickMarkers(const core::Paper& paper, int face, int vertex,
                                            const InteractionStyle& style, const ros::Time& stamp)
{
  visualization_msgs::MarkerArray array;
  Marker outline = overSheet(style, stamp, "pick", Marker::LINE_LIST);
  outline.id = 0;
  outline.scale.x = 1.5 * style.line_width;
  outline.color = rgba(1.0f, 0.6f, 0.0f);
  if (face >= 0 && static_cast<size_t>(face) < paper.faces.size())
    addOutline(outline, paper, face);
  std::vector<core::Vec3> at;
  if (vertex >= 0 && static_cast<size_t>(vertex) < paper.vertices.size())
    at.push_back(paper.vertices[vertex].folded);
  Marker point = points(style, stamp, "pick", at, rgba(1.0f, 0.6f, 0.0f), style.point_size);
  point.id = 1;
  for (Marker* m : { &outline, &point })
  {
    m->pose.position.z = underPickable(style);
    if (m->points.empty())
      m->action = Marker::DELETE;
    array.markers.push_back(*m);
  }
  return array;
}

visualization_msgs::MarkerArray messageMarker(const std::string& text, const core::Vec3& at,
                                              const InteractionStyle& style, const ros::Time& stamp)
{
  visualization_msgs::MarkerArray array;
  Marker m = overSheet(style, stamp, "message", Marker::TEXT_VIEW_FACING);
  m.scale.z = style.text_size;
  m.color = rgba(0.6f, 0.1f, 0.1f);
  m.text = text;
  m.pose.position = toPoint(at);
  m.lifetime = ros::Duration(4.0);
  array.markers.push_back(m);
  return array;
}

core::Vec3 messageAnchor(const core::Paper& paper, const core::Vec3& at, const std::string& text,
                         const InteractionStyle& style)
{
  if (paper.vertices.empty())
    return at;
  core::Vec3 lo = paper.vertices[0].folded, hi = lo;
  for (const core::Vertex& v : paper.vertices)
  {
    lo = lo.cwiseMin(v.folded);
    hi = hi.cwiseMax(v.folded);
  }
  size_t lines = 1, longest = 0, line = 0;
  for (char c : text)
  {
    if (c == '\n')
    {
      ++lines;
      line = 0;
    }
    else if ((static_cast<unsigned char>(c) & 0xC0) != 0x80)  // a character, not a UTF-8 continuation
      longest = std::max(longest, ++line);
  }
  // rviz draws its font about 0.6 of the line height wide per character; which way the lines
  // run depends on the view, so they must fit both ways.
  const double half = 0.3 * style.text_size * static_cast<double>(longest);
  core::Vec3 anchor = at.allFinite() ? at : core::Vec3(0.5 * (lo + hi));
  for (int i = 0; i < 2; ++i)
    anchor[i] = hi[i] - lo[i] <= 2 * half ? 0.5 * (lo[i] + hi[i]) : std::clamp(anchor[i], lo[i] + half, hi[i] - half);
  anchor.z() = hi.z() + style.text_size * (0.5 * static_cast<double>(lines) + 1.0);
  return anchor;
}

core::Vec3 besideAnchor(const core::Paper& paper, const std::string& text, const InteractionStyle& style)
{
  if (paper.vertices.empty())
    return core::Vec3::Zero();
  core::Vec3 lo = paper.vertices[0].folded, hi = lo;
  for (const core::Vertex& v : paper.vertices)
  {
    lo = lo.cwiseMin(v.folded);
    hi = hi.cwiseMax(v.folded);
  }
  const double lines = 1.0 + static_cast<double>(std::count(text.begin(), text.end(), '\n'));
  return core::Vec3(0.5 * (lo.x() + hi.x()), hi.y() + style.text_size * (0.5 * lines + 1.0), hi.z() + style.text_size);
}

visualization_msgs::MarkerArray clearedMarkers(const InteractionStyle& style, const ros::Time& stamp)
{
  visualization_msgs::MarkerArray array;
  Marker all = overSheet(style, stamp, "", Marker::DELETEALL);
  all.action = Marker::DELETEALL;
  array.markers.push_back(all);
  return array;
}

}  // namespace virtual_origami
