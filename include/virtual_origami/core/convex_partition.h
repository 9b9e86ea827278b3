// A simple polygon cut into convex pieces: the FOLD reader splits a concave face so.
#pragma once

#include <array>
#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// Convex pieces of a simple polygon (each a cycle of indices into it), and the diagonals
/// between them.
struct ConvexPieces
{
  std::vector<std::vector<int>> pieces;
  std::vector<std::array<int, 2>> diagonals;
};

/// The convex pieces of a simple counter-clockwise polygon. Ear clipping cuts it into
/// triangles, then each diagonal whose removal leaves a convex piece is removed
/// (Hertel–Mehlhorn: at most four times the fewest pieces). Corners turning right by less than
/// `slack` (a cross product) count as straight. Empty when no ear is found (the polygon is not
/// simple).
ConvexPieces convexPieces(const std::vector<Vec2>& polygon, double slack);

/// `cycle` turned to start at `first`.
std::vector<int> startingAt(const std::vector<int>& cycle, int first);

}  // namespace virtual_origami::core
