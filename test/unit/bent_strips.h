// A sheet bent into strips, the closed form a kept bend is tested against (kept_bend_test, the
// record_replay rostest): the unit square meshed on a grid of `cells` × `cells` squares, each cut
// by its rising diagonal, the strips right of `from_x` turned about the y axis, the k-th by
// (k + 1) · `turn` from flat (so a crease at `from_x` folds by `turn` too). Every triangle keeps its
// shape exactly.
#pragma once

#include <cmath>

#include "virtual_origami/core/kept_bend.h"

namespace virtual_origami::core::test
{
inline BentSheet stripsBentFrom(double from_x, int cells, double turn)
{
  BentSheet sheet;
  const double h = 1.0 / cells;
  const int first = static_cast<int>(std::lround(from_x / h));
  for (int j = 0; j <= cells; ++j)
  {
    Vec3 at(0.0, j * h, 0.0);
    for (int i = 0; i <= cells; ++i)
    {
      sheet.points.emplace_back(i * h, j * h);
      sheet.positions.push_back(at);
      const double angle = i >= first ? (i - first + 1) * turn : 0.0;
      at += h * Vec3(std::cos(angle), 0.0, std::sin(angle));
    }
  }
  const auto node = [cells](int i, int j) { return j * (cells + 1) + i; };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i)
    {
      sheet.triangles.push_back({ node(i, j), node(i + 1, j), node(i + 1, j + 1) });
      sheet.triangles.push_back({ node(i, j), node(i + 1, j + 1), node(i, j + 1) });
    }
  return sheet;
}

}  // namespace virtual_origami::core::test
