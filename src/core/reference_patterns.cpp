#include "virtual_origami/core/reference_patterns.h"

#include <cmath>
#include <map>

#include "virtual_origami/core/kinematics.h"

namespace virtual_origami::core
{
Expected<Paper> patternPaper(const std::vector<Vec2>& vertices, const std::vector<std::vector<int>>& faces)
{
  Paper paper;
  for (const Vec2& c : vertices)
    paper.vertices.push_back({ c, Vec3(c.x(), c.y(), 0.0) });
  std::map<std::pair<int, int>, int> edge_of;
  for (const std::vector<int>& cycle : faces)
  {
    for (size_t k = 0; k < cycle.size(); ++k)
    {
      const auto key = std::minmax(cycle[k], cycle[(k + 1) % cycle.size()]);
      auto [it, added] = edge_of.emplace(key, static_cast<int>(paper.edges.size()));
      if (added)
        paper.edges.push_back({ { cycle[k], cycle[(k + 1) % cycle.size()] }, Assignment::Boundary, 0.0, { -1, -1 }, false, {} });
      else
        paper.edges[it->second].assignment = Assignment::Unassigned;
    }
    paper.faces.push_back({ cycle, {} });
  }
  const Status linked = linkTopology(paper);
  if (!linked)
    return Expected<Paper>::failure(linked.message());
  for (size_t f = 0; f < paper.faces.size(); ++f)
    paper.sheet_area += paper.faceArea(static_cast<int>(f));
  return paper;
}

Paper degree4Vertex(const std::array<double, 4>& sectors, double radius)
{
  std::vector<Vec2> vertices{ Vec2::Zero() };
  double angle = 0.0;
  for (int k = 0; k < 4; ++k)
  {
    vertices.push_back(radius * Vec2(std::cos(angle), std::sin(angle)));
    angle += sectors[k];
  }
  std::vector<std::vector<int>> faces;
  for (int k = 0; k < 4; ++k)
    faces.push_back({ 0, k + 1, (k + 1) % 4 + 1 });
  return *patternPaper(vertices, faces);
}

Paper miuraOri(int columns, int rows, double a, double b, double gamma)
{
  std::vector<Vec2> vertices;
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= columns; ++i)
      vertices.emplace_back(i * a + (j % 2) * b * std::cos(gamma), j * b * std::sin(gamma));
  std::vector<std::vector<int>> faces;
  const auto id = [columns](int i, int j) { return j * (columns + 1) + i; };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i)
      faces.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1) });
  return *patternPaper(vertices, faces);
}

std::array<double, 4> degree4FoldAngles(double alpha, double beta, double rho1, int mode)
{
  const double t1 = std::tan(rho1 / 2);
  if (mode == 1)
  {
    const double rho2 = 2 * std::atan(-std::cos((alpha + beta) / 2) / std::cos((alpha - beta) / 2) * t1);
    return { rho1, rho2, rho1, -rho2 };
  }
  const double rho2 = 2 * std::atan(std::sin((alpha + beta) / 2) / std::sin((alpha - beta) / 2) * t1);
  return { rho1, rho2, -rho1, rho2 };
}

std::vector<double> miuraFoldAngles(const Paper& miura, int columns, int rows, double gamma, double rho)
{
  std::vector<double> angles(miura.edges.size(), 0.0);
  const auto id = [columns](int i, int j) { return j * (columns + 1) + i; };
  const double zigzag = 2 * std::atan(std::tan(rho / 2) / std::cos(gamma));
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= columns; ++i)
    {
      const double sign = (i + j) % 2 ? -1.0 : 1.0;
      const int straight = i < columns ? miura.findEdge(id(i, j), id(i + 1, j)) : -1;
      if (straight >= 0 && miura.edges[straight].isCrease())
        angles[straight] = sign * rho;
      const int zig = j < rows ? miura.findEdge(id(i, j), id(i, j + 1)) : -1;
      if (zig >= 0 && miura.edges[zig].isCrease())
        angles[zig] = (i % 2 ? 1.0 : -1.0) * zigzag;
    }
  return angles;
}

Status foldToAngles(Paper& paper, const std::vector<double>& fold_angles)
{
  const Expected<std::vector<Vec3>> positions =
      foldedPositionsFromAngles(paper, fold_angles, 0, Eigen::Isometry3d::Identity(), 1e-9 * paper.scale());
  if (!positions)
    return failure(positions.message());
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    paper.vertices[v].folded = (*positions)[v];
  for (size_t e = 0; e < paper.edges.size(); ++e)
    paper.edges[e].fold_angle = fold_angles[e];
  updateFoldAngles(paper);
  return success();
}

}  // namespace virtual_origami::core
