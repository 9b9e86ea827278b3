#include "virtual_origami/ros/markers.h"

#include "virtual_origami/core/assignment_fold.h"
#include "virtual_origami/core/layers.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/strain_colours.h"

namespace virtual_origami
{
std_msgs::ColorRGBA rgba(float r, float g, float b, float a)
{
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

visualization_msgs::Marker baseMarker(const std::string& frame_id, const ros::Time& stamp, const std::string& ns,
                                      int type, double scale, const std_msgs::ColorRGBA& color)
{
  visualization_msgs::Marker m;
  m.header.frame_id = frame_id;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = 0;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = scale;
  m.color = color;
  m.frame_locked = true;
  return m;
}

namespace
{
/// Every face's front normal, each computed once: the sides, the lifts and the creases all
/// need them (a 10,000-vertex paper's markers took 3.5 ms computing each four times).
std::vector<core::Vec3> faceNormals(const core::Paper& paper)
{
  std::vector<core::Vec3> normals(paper.faces.size());
  for (size_t f = 0; f < paper.faces.size(); ++f)
    normals[f] = paper.faceNormal(static_cast<int>(f));
  return normals;
}

/// Each face's lift off its plane: its stack level along the stack's upward normal.
std::vector<core::Vec3> layerLifts(const core::Paper& paper, const std::vector<core::Vec3>& normals,
                                   const MarkerStyle& style)
{
  std::vector<core::Vec3> lift(paper.faces.size(), core::Vec3::Zero());
  if (paper.face_orders.empty())
    return lift;  // one layer: every face at level 0
  const std::vector<int> levels = core::stackLevels(paper);
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    core::Vec3 up = normals[f];
    if (up.z() < 0)
      up = -up;
    lift[f] = up * (levels[f] * style.layer_gap);
  }
  return lift;
}
}  // namespace

visualization_msgs::MarkerArray paperMarkers(const core::Paper& paper, const MarkerStyle& style, const ros::Time& stamp)
{
  using visualization_msgs::Marker;
  const std::vector<core::Vec3> normals = faceNormals(paper);
  const std::vector<core::Vec3> lift = layerLifts(paper, normals, style);
  Marker front = baseMarker(style.frame_id, stamp, "front", Marker::TRIANGLE_LIST);
  Marker back = baseMarker(style.frame_id, stamp, "back", Marker::TRIANGLE_LIST);
  front.color = rgba(0.96f, 0.89f, 0.76f);  // the coloured side of the sheet
  back.color = rgba(0.55f, 0.70f, 0.86f);
  std::vector<double> strain;
  if (style.colour_by_strain)
    strain = core::faceStrains(paper);
  size_t corners = 0;  // of the triangles of every face's fan
  for (const core::Face& face : paper.faces)
    corners += face.vertices.size() >= 3 ? 3 * (face.vertices.size() - 2) : 0;
  front.points.reserve(corners);
  back.points.reserve(corners);
  if (style.colour_by_strain)
  {
    front.colors.reserve(corners);
    back.colors.reserve(corners);
  }
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const std::vector<int>& vs = paper.faces[f].vertices;
    const core::Vec3& n = normals[f];
    const core::Vec3 to_front = lift[f] + n * style.side_offset;
    const core::Vec3 to_back = lift[f] - n * style.side_offset;
    for (size_t i = 1; i + 1 < vs.size(); ++i)  // a fan: faces are convex
    {
      const core::Vec3& a = paper.vertices[vs[0]].folded;
      const core::Vec3& b = paper.vertices[vs[i]].folded;
      const core::Vec3& c = paper.vertices[vs[i + 1]].folded;
      for (const core::Vec3* p : { &a, &b, &c })
        front.points.push_back(toPoint(*p + to_front));
      for (const core::Vec3* p : { &a, &c, &b })  // wound the other way: seen from behind
        back.points.push_back(toPoint(*p + to_back));
      if (style.colour_by_strain)
      {
        // Per vertex: rviz multiplies them by the marker's colour, white then.
        const std_msgs::ColorRGBA colour = strainColour(strain[f], style.strain_scale);
        front.colors.insert(front.colors.end(), 3, colour);
        back.colors.insert(back.colors.end(), 3, colour);
      }
    }
  }
  Marker mountain = baseMarker(style.frame_id, stamp, "mountain", Marker::LINE_LIST);
  Marker valley = baseMarker(style.frame_id, stamp, "valley", Marker::LINE_LIST);
  Marker other = baseMarker(style.frame_id, stamp, "crease", Marker::LINE_LIST);
  Marker boundary = baseMarker(style.frame_id, stamp, "boundary", Marker::LINE_LIST);
  mountain.color = rgba(0.84f, 0.15f, 0.16f);
  valley.color = rgba(0.12f, 0.47f, 0.71f);
  other.color = rgba(0.5f, 0.5f, 0.5f);
  boundary.color = rgba(0.1f, 0.1f, 0.1f);
  for (Marker* m : { &mountain, &valley, &other, &boundary })
    m->scale.x = style.line_width;
  for (const core::Edge& e : paper.edges)
  {
    Marker& m = e.assignment == core::Assignment::Mountain ? mountain :
                e.assignment == core::Assignment::Valley   ? valley :
                e.assignment == core::Assignment::Boundary ? boundary :
                                                             other;
    core::Vec3 offset = core::Vec3::Zero();  // drawn with the higher of its faces
    for (int f : e.faces)
      if (f >= 0 && lift[f].norm() > offset.norm())
        offset = lift[f];
    // Just over the upper surface (front or back), where a view from above sees it.
    core::Vec3 up = e.faces[0] >= 0 ? normals[e.faces[0]] : core::Vec3::UnitZ();
    if (up.z() < 0)
      up = -up;
    offset += up * (2 * style.side_offset);
    for (int v : e.vertices)
      m.points.push_back(toPoint(paper.vertices[v].folded + offset));
  }
  if (style.colour_by_strain)
    front.color = back.color = rgba(1, 1, 1);
  visualization_msgs::MarkerArray array;
  array.markers.reserve(6);
  for (Marker* m : { &front, &back, &mountain, &valley, &other, &boundary })
  {
    if (m->points.empty())
      m->action = Marker::DELETE;  // rviz rejects an empty list; nothing of that kind to show
    array.markers.push_back(std::move(*m));
  }
  return array;
}

}  // namespace virtual_origami
