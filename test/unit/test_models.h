// Models the unit tests fold, built through the public operations.
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "virtual_origami/core/crease.h"
#include "virtual_origami/core/geometry.h"
#include "virtual_origami/core/rotate.h"
#include "virtual_origami/core/validity.h"

namespace virtual_origami::core::test
{
inline Vec3 p3(double x, double y, double z = 0.0) { return Vec3(x, y, z); }

/// Creases along the line a→b (plane rule); fails the test when the crease fails.
inline CreaseResult creaseLine(Paper& paper, const Vec3& a, const Vec3& b)
{
  CreaseRequest request;
  request.start = a;
  request.end = b;
  Expected<CreaseResult> result = crease(paper, request);
  EXPECT_TRUE(result.ok()) << result.message();
  return result.ok() ? *result : CreaseResult{};
}

/// Creases along a→b through every layer, then turns every layer on the side of `side`
/// about its piece of the new crease by `angle` (a stack folded as one).
inline void foldStack(Paper& paper, const Vec3& a, const Vec3& b, const Vec3& side, double angle)
{
  const CreaseResult creased = creaseLine(paper, a, b);
  const Vec2 dir = (b - a).head<2>();
  const auto sideOf = [&](const Vec3& p) {
    const Vec2 q = (p - a).head<2>();
    return dir.x() * q.y() - dir.y() * q.x() > 0;
  };
  // Pick every (face, hinge) pair before turning anything: turning moves centroids.
  std::vector<std::pair<int, int>> turns;
  for (int e : creased.new_edges)
    for (int f : paper.edges[e].faces)
      if (sideOf(paper.faceCentroid(f)) == sideOf(side))
        turns.emplace_back(f, e);
  std::vector<char> moved(paper.faces.size(), 0);
  for (const auto& [face, edge] : turns)
  {
    if (moved[face])
      continue;
    RotateRequest request;
    request.face = face;
    request.axis_edge = edge;
    request.angle = angle;
    const Expected<RotateResult> result = rotate(paper, request);
    ASSERT_TRUE(result.ok()) << result.message();
    for (int f : result->moved_faces)
      moved[f] = 1;
  }
}

inline Vec2 v2(double x, double y) { return Vec2(x, y); }

/// A crease of `face` across the sheet's x axis (not along it): on a Miura-ori's corner face, a
/// zigzag crease to turn the face about. −1 when it has none.
inline int slantedCreaseOf(const Paper& paper, int face)
{
  int axis = -1;
  for (int e : paper.faces[face].edges)
    if (paper.edges[e].isCrease() && std::abs(paper.vertices[paper.edges[e].vertices[1]].crease_pattern.y() -
                                              paper.vertices[paper.edges[e].vertices[0]].crease_pattern.y()) > 1e-9)
      axis = e;
  return axis;
}

/// The unit square creased along both diagonals and both midlines.
inline Paper creasedSquare()
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0, 0), p3(1, 1));
  creaseLine(paper, p3(1, 0), p3(0, 1));
  creaseLine(paper, p3(0.5, -0.1), p3(0.5, 1.1));
  creaseLine(paper, p3(-0.1, 0.5), p3(1.1, 0.5));
  return paper;
}

/// The unit square creased at x = 0.5, and the vertices of its half x ≤ 0.5.
inline Paper creasedInHalf(std::vector<int>& left_half)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -0.1), p3(0.5, 1.1));
  left_half.clear();
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    if (paper.vertices[v].crease_pattern.x() < 0.5 + 1e-12)
      left_half.push_back(static_cast<int>(v));
  return paper;
}

/// Unit square folded in half `times` times (valley folds of 180°): 2^times layers.
inline Paper stackOfLayers(int times)
{
  Paper paper = Paper::square(1.0);
  if (times >= 1)  // right half over the left: layers over [0, .5] × [0, 1]
    foldStack(paper, p3(0.5, -0.1), p3(0.5, 1.1), p3(0.75, 0.5), M_PI);
  if (times >= 2)  // top half down: [0, .5] × [0, .5]
    foldStack(paper, p3(-0.1, 0.5), p3(0.6, 0.5), p3(0.25, 0.75), M_PI);
  if (times >= 3)  // left quarter over: [.25, .5] × [0, .5]
    foldStack(paper, p3(0.25, -0.1), p3(0.25, 0.6), p3(0.1, 0.25), M_PI);
  return paper;
}

inline void expectValid(const Paper& paper)
{
  const ValidityReport report = checkValidity(paper);
  EXPECT_TRUE(report.ok()) << report.summary();
}

}  // namespace virtual_origami::core::test
