// Constrained Delaunay triangulation of points in the plane (seed 002 §2.2.3): the mesher's
// last step. The one place CGAL is used; its headers stay in the .cpp.
#pragma once

#include <array>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// Triangles (indices into `points`, counter-clockwise) of the Delaunay triangulation of
/// `points` that keeps every segment of `constraints` as an edge, over their convex hull.
/// Fails on coincident points or constraints that cross.
Expected<std::vector<std::array<int, 3>>> constrainedDelaunay(const std::vector<Vec2>& points,
                                                              const std::vector<std::array<int, 2>>& constraints);

}  // namespace virtual_origami::core
