// Faces passing through each other: what a fold must never leave (SPEC §2: paper does not
// penetrate itself). Layers lying flat on each other are not crossings here; whether they can
// be stacked is the layer order's question (layer_order.h).
#pragma once

#include <utility>
#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// Pairs (a < b) of faces that are not coplanar and whose interiors cross: each face has
/// points strictly on both sides of the other's plane (beyond `tolerance`), and the two chords
/// the planes cut from them overlap by more than `tolerance`. Faces that only touch (a corner,
/// an edge resting on a face, a shared crease or vertex) do not cross. `tolerance` 0: 1e-6 of
/// the sheet's scale, well above a rigid state's error (faces that meet along a line, like the
/// flaps of a square base half folded, lie 1e-8 of the sheet off each other's planes there) and
/// far below a crossing's depth.
std::vector<std::pair<int, int>> findFaceCrossings(const Paper& paper, double tolerance = 0.0);

}  // namespace virtual_origami::core
