#include "virtual_origami/core/validity.h"

#include <cmath>
#include <numeric>
#include <utility>
#include <sstream>

#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
std::string ValidityReport::summary() const
{
  std::ostringstream out;
  for (const std::string& p : problems)
    out << p << '\n';
  return out.str();
}

namespace
{
int findRoot(std::vector<int>& parent, int i)
{
  while (parent[i] != i)
    i = parent[i] = parent[parent[i]];
  return i;
}

/// Pieces: faces joined through shared vertices. Each piece has one outer boundary loop, and a
/// loop more for each hole (a slit opened inside the paper is one too): holes = loops - pieces.
std::pair<long, long> piecesAndHoles(const Paper& paper)
{
  const auto count = [&](const std::vector<std::vector<int>>& groups) {
    std::vector<int> parent(paper.vertices.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<char> used(paper.vertices.size(), 0);
    for (const std::vector<int>& group : groups)
      for (int v : group)
      {
        used[v] = 1;
        parent[findRoot(parent, v)] = findRoot(parent, group.front());
      }
    long roots = 0;
    for (size_t v = 0; v < parent.size(); ++v)
      roots += used[v] && findRoot(parent, static_cast<int>(v)) == static_cast<int>(v);
    return roots;
  };
  std::vector<std::vector<int>> faces, boundary;
  for (const Face& face : paper.faces)
    faces.push_back(face.vertices);
  for (const Edge& edge : paper.edges)
    if (!edge.isCrease())
      boundary.push_back({ edge.vertices[0], edge.vertices[1] });
  const long pieces = count(faces);
  return { pieces, count(boundary) - pieces };
}

void checkTopology(const Paper& paper, ValidityReport& report)
{
  Paper linked = paper;
  const Status linked_ok = linkTopology(linked);
  if (!linked_ok)
  {
    report.problems.push_back("topology: " + linked_ok.message());
    return;
  }
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (edge.faces != linked.edges[e].faces)
      report.problems.push_back("edge " + std::to_string(e) + " has stale face links");
    const bool boundary = edge.assignment == Assignment::Boundary;
    if (boundary && edge.isCrease())
      report.problems.push_back("boundary edge " + std::to_string(e) + " has two faces");
    if (!boundary && !edge.isCrease())
      report.problems.push_back("crease " + std::to_string(e) + " does not have exactly two faces");
    if (!std::isfinite(edge.fold_angle))
      report.problems.push_back("edge " + std::to_string(e) + " has a non-finite fold angle");
  }
  for (size_t f = 0; f < paper.faces.size(); ++f)
    if (paper.faces[f].edges != linked.faces[f].edges)
      report.problems.push_back("face " + std::to_string(f) + " has stale edge links");
  const long euler = static_cast<long>(paper.vertices.size()) - static_cast<long>(paper.edges.size()) +
                     static_cast<long>(paper.faces.size());
  const auto [pieces, holes] = piecesAndHoles(linked);
  if (euler != pieces - holes)
    report.problems.push_back("V - E + F = " + std::to_string(euler) + ", not " + std::to_string(pieces - holes) +
                              " (pieces - holes: " + std::to_string(pieces) + " - " + std::to_string(holes) + ")");
}

void checkFaceShapes(const Paper& paper, const ValidityTolerance& tolerance, ValidityReport& report)
{
  const double scale = paper.scale();
  const double length_tol = tolerance.length * scale;
  double area_sum = 0;
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const std::vector<int>& vs = paper.faces[f].vertices;
    const size_t n = vs.size();
    for (size_t i = 0; i < n; ++i)
    {
      const Vec2& a = paper.vertices[vs[i]].crease_pattern;
      const Vec2& b = paper.vertices[vs[(i + 1) % n]].crease_pattern;
      const Vec2& c = paper.vertices[vs[(i + 2) % n]].crease_pattern;
      const Vec2 ab = b - a, bc = c - b;
      const double turn = cross2(ab, bc);
      if (turn < -tolerance.convexity * scale * scale)
        report.problems.push_back("face " + std::to_string(f) + " is not convex and counter-clockwise at vertex " +
                                  std::to_string(vs[(i + 1) % n]));
    }
    area_sum += paper.faceArea(static_cast<int>(f));
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i + 1; j < n; ++j)
      {
        const Vertex& a = paper.vertices[vs[i]];
        const Vertex& b = paper.vertices[vs[j]];
        const double flat = (a.crease_pattern - b.crease_pattern).norm();
        const double folded = (a.folded - b.folded).norm();
        if (!(std::abs(flat - folded) <= length_tol))
        {
          std::ostringstream msg;
          msg << "face " << f << ": vertices " << vs[i] << " and " << vs[j] << " are " << folded << " apart folded but "
              << flat << " in the crease pattern";
          report.problems.push_back(msg.str());
        }
      }
  }
  if (!(std::abs(area_sum - paper.sheet_area) <= tolerance.area * paper.sheet_area))
  {
    std::ostringstream msg;
    msg << "face areas sum to " << area_sum << ", the sheet's area is " << paper.sheet_area;
    report.problems.push_back(msg.str());
  }
}
}  // namespace

ValidityReport checkValidity(const Paper& paper, const ValidityTolerance& tolerance)
{
  ValidityReport report;
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    if (!paper.vertices[v].crease_pattern.allFinite() || !paper.vertices[v].folded.allFinite())
      report.problems.push_back("vertex " + std::to_string(v) + " has a non-finite position");
  checkTopology(paper, report);
  if (report.ok())
    checkFaceShapes(paper, tolerance, report);
  return report;
}

}  // namespace virtual_origami::core
