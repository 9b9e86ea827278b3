// A sheet around one vertex: creases from the origin along the given directions (degrees,
// counter-clockwise), the sheet the triangles between consecutive creases. The vertex is the
// sheet's only inner vertex, so whether the sheet folds flat is whether that vertex does.
#pragma once

#include <cmath>
#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core::test
{
inline Paper singleVertex(const std::vector<double>& degrees)
{
  Paper paper;
  paper.vertices.push_back({ Vec2::Zero(), Vec3::Zero() });
  const int n = static_cast<int>(degrees.size());
  for (double d : degrees)
  {
    const Vec2 p(std::cos(d * M_PI / 180.0), std::sin(d * M_PI / 180.0));
    paper.vertices.push_back({ p, Vec3(p.x(), p.y(), 0.0) });
  }
  for (int i = 0; i < n; ++i)
  {
    Edge spoke;
    spoke.vertices = { 0, i + 1 };
    spoke.assignment = Assignment::Unassigned;
    paper.edges.push_back(spoke);
    Edge rim;
    rim.vertices = { i + 1, (i + 1) % n + 1 };
    paper.edges.push_back(rim);
    paper.faces.push_back({ { 0, i + 1, (i + 1) % n + 1 }, {} });
  }
  for (int f = 0; f < n; ++f)
    paper.sheet_area += paper.faceArea(f);
  (void)linkTopology(paper);
  return paper;
}

/// The fold angles that fold the spokes flat by `signs` (+1 valley, −1 mountain; spoke i is edge 2i).
inline std::vector<double> spokeAngles(const Paper& paper, const std::vector<int>& signs)
{
  std::vector<double> angles(paper.edges.size(), 0.0);
  for (size_t i = 0; i < signs.size(); ++i)
    angles[2 * i] = signs[i] * M_PI;
  return angles;
}
}  // namespace virtual_origami::core::test
