// How far two states of one paper differ in shape: the measure the tests that fold a model by
// mouse or by script hold their steps to.
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "virtual_origami/core/geometry.h"
#include "virtual_origami/core/paper.h"

namespace virtual_origami::core::test
{
/// Largest distance between the vertices of `a` and `b` (matched by crease-pattern position)
/// after the rigid motion that fits `a` onto `b` best; infinity when their vertices differ.
inline double rigidFitDistance(const Paper& a, const Paper& b)
{
  if (a.vertices.size() != b.vertices.size())
    return INFINITY;
  Positions pa(3, static_cast<Eigen::Index>(a.vertices.size())), pb(3, static_cast<Eigen::Index>(a.vertices.size()));
  for (size_t i = 0; i < a.vertices.size(); ++i)
  {
    const int j = b.vertexAt(a.vertices[i].crease_pattern, 1e-9);
    if (j < 0)
      return INFINITY;
    pa.col(static_cast<Eigen::Index>(i)) = a.vertices[i].folded;
    pb.col(static_cast<Eigen::Index>(i)) = b.vertices[j].folded;
  }
  return shapeDistance(pa, pb).largest;
}

/// Where the paper puts the vertex at a crease-pattern point (NaN, and a failure, without one).
inline Vec3 foldedAt(const Paper& paper, const Vec2& crease_pattern_point)
{
  const int v = paper.vertexAt(crease_pattern_point, 1e-9);
  EXPECT_GE(v, 0) << "no vertex at (" << crease_pattern_point.transpose() << ")";
  return v >= 0 ? paper.vertices[v].folded : Vec3::Constant(NAN);
}

}  // namespace virtual_origami::core::test
