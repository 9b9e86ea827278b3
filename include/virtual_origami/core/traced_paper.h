// The paper that lines drawn in the plane leave: where a crease pattern gives its edges but no
// faces (a FOLD file without faces_vertices, an SVG drawing), which regions are paper, which are
// holes, where cuts open, and each region as a face.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// A vertex of the traced paper: the drawn point `a` (a == b, t == 0), or the point a fraction t
/// of the way along the drawn edge from `a` to `b` (where a joint meets that edge).
struct VertexSource
{
  int a = -1;
  int b = -1;
  double t = 0.0;
};

/// Faces counter-clockwise; every vertex is used by a face and is simple in each.
struct TracedPaper
{
  std::vector<Vec2> points;
  std::vector<VertexSource> sources;  // per vertex
  std::vector<std::array<int, 2>> edges;
  /// The drawn edge each edge lies on, or -1 for a joint: a flat edge added so that no face
  /// surrounds a hole, a slit or a ring of creases that nothing else reaches.
  std::vector<int> edge_sources;
  std::vector<std::vector<int>> faces;
};

/// How messages name a drawn point and edge (as the file calls them).
struct DrawingNames
{
  std::function<std::string(int)> point = [](int p) { return "point " + std::to_string(p); };
  std::function<std::string(int)> edge = [](int e) { return "edge " + std::to_string(e); };
};

/// The paper a planar straight-line graph draws (its edges meet only at their ends). A region is
/// paper when the shortest way in from outside crosses an odd number of boundary (B) edges,
/// counting the first edge crossed from outside as boundary whatever it is marked: holes are
/// regions ringed by B edges inside paper and never get a face. Cut (C) edges keep paper on both
/// sides and are opened: every vertex along a cut gets a copy for each side, so a slit's sides,
/// and the two edges a cut edge becomes, are different vertices and edges. A chain of other edges
/// that ends inside a region (a crease with a loose end), or a crease with the same region on both
/// sides, folds nothing rigid paper can fold and is left out, as are edges with no paper on either side and the points
/// only they used. A cut that ends inside the paper runs on from its tip as a flat joint to the first line it meets
/// (faces stay convex beside the tip). A hole or island of creases that lies inside a face, touching nothing, is joined
/// to what surrounds it by two horizontal flat joints (from its leftmost and rightmost points). Separate pieces stay
/// separate. Regions of no more than `min_area` are slivers and make no face.
Expected<TracedPaper> tracePaper(const std::vector<Vec2>& points, const std::vector<std::array<int, 2>>& edges,
                                 const std::vector<Assignment>& assignments, double min_area,
                                 const DrawingNames& names = {});

}  // namespace virtual_origami::core
