#include "virtual_origami/core/paper.h"

#include <cmath>
#include <deque>
#include <map>

#include <Eigen/Geometry>

#include "virtual_origami/core/compliant_faces.h"
#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
char assignmentLetter(Assignment assignment)
{
  switch (assignment)
  {
    case Assignment::Boundary:
      return 'B';
    case Assignment::Mountain:
      return 'M';
    case Assignment::Valley:
      return 'V';
    case Assignment::Flat:
      return 'F';
    case Assignment::Unassigned:
      return 'U';
    case Assignment::Cut:
      return 'C';
  }
  return 'U';
}

std::optional<Assignment> assignmentFromLetter(const std::string& letter)
{
  if (letter.size() != 1)
    return std::nullopt;
  switch (letter[0])
  {
    case 'B':
    case 'b':
      return Assignment::Boundary;
    case 'M':
    case 'm':
      return Assignment::Mountain;
    case 'V':
    case 'v':
      return Assignment::Valley;
    case 'F':
    case 'f':
      return Assignment::Flat;
    case 'U':
    case 'u':
      return Assignment::Unassigned;
    case 'C':
    case 'c':
      return Assignment::Cut;
    default:
      return std::nullopt;
  }
}

Paper Paper::square(double size)
{
  Paper paper;
  const Vec2 corners[4] = { { 0, 0 }, { size, 0 }, { size, size }, { 0, size } };
  for (const Vec2& c : corners)
    paper.vertices.push_back({ c, Vec3(c.x(), c.y(), 0.0) });
  for (int i = 0; i < 4; ++i)
    paper.edges.push_back({ { i, (i + 1) % 4 }, Assignment::Boundary, 0.0, { -1, -1 }, false, {} });
  paper.faces.push_back({ { 0, 1, 2, 3 }, {} });
  paper.sheet_area = size * size;
  linkTopology(paper);
  return paper;
}

double Paper::scale() const { return sheet_area > 0 ? std::sqrt(sheet_area) : 1.0; }

Vec3 Paper::faceCentroid(int face) const
{
  Vec3 sum = Vec3::Zero();
  for (int v : faces[face].vertices)
    sum += vertices[v].folded;
  return sum / static_cast<double>(faces[face].vertices.size());
}

Vec3 Paper::faceNormal(int face) const
{
  // Newell's method: robust for slightly non-planar polygons and collinear vertices.
  const std::vector<int>& vs = faces[face].vertices;
  Vec3 n = Vec3::Zero();
  for (size_t i = 0; i < vs.size(); ++i)
  {
    const Vec3& a = vertices[vs[i]].folded;
    const Vec3& b = vertices[vs[(i + 1) % vs.size()]].folded;
    n += a.cross(b);
  }
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::UnitZ();
}

double Paper::faceArea(int face) const
{
  const std::vector<int>& vs = faces[face].vertices;
  double twice = 0;
  for (size_t i = 0; i < vs.size(); ++i)
  {
    const Vec2& a = vertices[vs[i]].crease_pattern;
    const Vec2& b = vertices[vs[(i + 1) % vs.size()]].crease_pattern;
    twice += cross2(a, b);
  }
  return 0.5 * twice;
}

int Paper::findEdge(int a, int b) const
{
  for (size_t e = 0; e < edges.size(); ++e)
  {
    const auto& ev = edges[e].vertices;
    if ((ev[0] == a && ev[1] == b) || (ev[0] == b && ev[1] == a))
      return static_cast<int>(e);
  }
  return -1;
}

int Paper::vertexAt(const Vec2& crease_pattern_point, double tolerance) const
{
  for (size_t v = 0; v < vertices.size(); ++v)
    if ((vertices[v].crease_pattern - crease_pattern_point).norm() <= tolerance)
      return static_cast<int>(v);
  return -1;
}

std::vector<int> Paper::facesOfVertex(int vertex) const
{
  std::vector<int> result;
  for (size_t f = 0; f < faces.size(); ++f)
    for (int v : faces[f].vertices)
      if (v == vertex)
      {
        result.push_back(static_cast<int>(f));
        break;
      }
  return result;
}

bool Paper::operator==(const Paper& o) const
{
  if (vertices.size() != o.vertices.size() || edges.size() != o.edges.size() || faces.size() != o.faces.size())
    return false;
  for (size_t i = 0; i < vertices.size(); ++i)
    if (vertices[i].crease_pattern != o.vertices[i].crease_pattern || vertices[i].folded != o.vertices[i].folded)
      return false;
  for (size_t i = 0; i < edges.size(); ++i)
  {
    const Edge& a = edges[i];
    const Edge& b = o.edges[i];
    if (a.vertices != b.vertices || a.assignment != b.assignment || a.fold_angle != b.fold_angle ||
        a.faces != b.faces || a.split != b.split || a.target_angle != b.target_angle)
      return false;
  }
  for (size_t i = 0; i < faces.size(); ++i)
    if (faces[i].vertices != o.faces[i].vertices || faces[i].edges != o.faces[i].edges)
      return false;
  return face_orders == o.face_orders && sheet_area == o.sheet_area;
}

Status linkTopology(Paper& paper)
{
  const int nv = static_cast<int>(paper.vertices.size());
  std::map<std::pair<int, int>, int> edge_of;
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    Edge& edge = paper.edges[e];
    const int a = edge.vertices[0], b = edge.vertices[1];
    if (a < 0 || b < 0 || a >= nv || b >= nv || a == b)
      return failure("edge " + std::to_string(e) + " has invalid vertices");
    const auto key = std::minmax(a, b);
    if (!edge_of.emplace(key, static_cast<int>(e)).second)
      return failure("edge " + std::to_string(e) + " duplicates edge " + std::to_string(edge_of[key]));
    edge.faces = { -1, -1 };
  }
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    Face& face = paper.faces[f];
    const size_t n = face.vertices.size();
    if (n < 3)
      return failure("face " + std::to_string(f) + " has fewer than 3 vertices");
    face.edges.assign(n, -1);
    for (size_t i = 0; i < n; ++i)
    {
      const int a = face.vertices[i], b = face.vertices[(i + 1) % n];
      if (a < 0 || a >= nv)
        return failure("face " + std::to_string(f) + " names vertex " + std::to_string(a) + " out of range");
      auto it = edge_of.find(std::minmax(a, b));
      if (it == edge_of.end())
        return failure("face " + std::to_string(f) + " side " + std::to_string(a) + "-" + std::to_string(b) +
                       " is not an edge");
      Edge& edge = paper.edges[it->second];
      // The face lies left of a→b because it is counter-clockwise.
      const int side = edge.vertices[0] == a ? 0 : 1;
      if (edge.faces[side] >= 0)
        return failure("edge " + std::to_string(it->second) + " has two faces on one side (faces " +
                       std::to_string(edge.faces[side]) + " and " + std::to_string(f) + ")");
      edge.faces[side] = static_cast<int>(f);
      face.edges[i] = it->second;
    }
  }
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].faces[0] < 0 && paper.edges[e].faces[1] < 0)
      return failure("edge " + std::to_string(e) + " belongs to no face");
  return success();
}

std::vector<char> walkFaces(const Paper& paper, int start, const std::function<void(int, int, int)>& step,
                            const std::function<bool(int)>& crossable)
{
  std::vector<char> reached(paper.faces.size(), 0);
  std::deque<int> queue{ start };
  reached[start] = 1;
  while (!queue.empty())
  {
    const int f = queue.front();
    queue.pop_front();
    for (int e : paper.faces[f].edges)
    {
      const Edge& edge = paper.edges[e];
      if (!edge.isCrease() || reached[edge.otherFace(f)] || (crossable && !crossable(e)))
        continue;
      const int g = edge.otherFace(f);
      reached[g] = 1;
      if (step)
        step(f, e, g);
      queue.push_back(g);
    }
  }
  return reached;
}

namespace
{
/// The crease `e`'s fold angle between its faces' normals: positive when the faces turn towards
/// each other on the front side (valley).
double foldAngleBetween(const Paper& paper, const Edge& e, const Vec3& n_left, const Vec3& n_right)
{
  const Vec3 axis = (paper.vertices[e.vertices[1]].folded - paper.vertices[e.vertices[0]].folded).normalized();
  return std::atan2(axis.dot(n_right.cross(n_left)), n_left.dot(n_right));
}
}  // namespace

double measureFoldAngle(const Paper& paper, int edge)
{
  const Edge& e = paper.edges[edge];
  if (!e.isCrease())
    return 0.0;
  return foldAngleBetween(paper, e, paper.faceNormal(e.faces[0]), paper.faceNormal(e.faces[1]));
}

void updateFoldAngles(Paper& paper, double assign_threshold)
{
  // Each face's normal once, not once per crease beside it (measureFoldAngle's, the same
  // figures): a preview frame of a 10,000-vertex paper measured its angles in 2 ms, mostly these.
  std::vector<Vec3> normals(paper.faces.size());
  for (size_t f = 0; f < paper.faces.size(); ++f)
    normals[f] = paper.faceNormal(static_cast<int>(f));
  for (size_t i = 0; i < paper.edges.size(); ++i)
  {
    Edge& edge = paper.edges[i];
    if (!edge.isCrease())
      continue;
    double angle = foldAngleBetween(paper, edge, normals[edge.faces[0]], normals[edge.faces[1]]);
    // At ±π the dihedral alone cannot tell mountain from valley; continuity can.
    while (angle - edge.fold_angle > M_PI)
      angle -= 2 * M_PI;
    while (edge.fold_angle - angle > M_PI)
      angle += 2 * M_PI;
    edge.fold_angle = std::max(-M_PI, std::min(M_PI, angle));
    // A facet (a compliant face's or a kept bend's) bends without becoming a crease.
    if (edge.assignment != Assignment::Cut && !isFacet(edge))
    {
      if (edge.fold_angle > assign_threshold)
        edge.assignment = Assignment::Valley;
      else if (edge.fold_angle < -assign_threshold)
        edge.assignment = Assignment::Mountain;
    }
  }
}

}  // namespace virtual_origami::core
