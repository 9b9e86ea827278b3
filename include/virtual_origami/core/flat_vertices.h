// The conditions a single vertex folded flat must meet, whatever the rest of the paper does:
// Maekawa (mountains and valleys differ by two), Kawasaki (alternate angles sum to 180°) and the
// big-little-big lemma (the creases about a smallest angle fold opposite ways, else the larger
// flaps beside it would have to pass through each other).
#pragma once

#include <string>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// A crease counts as folded flat within this of ±π, as unfolded within this of 0 (radians).
constexpr double kFlatAngleTolerance = 1e-6;

/// Checks every inner vertex of `paper` whose creases, with the fold angles `angles` (one per
/// edge, FOLD sign: + valley), are all flat (±π) or unfolded (0) and at least one folded.
/// Vertices with a crease at any other angle are not flat and are left to the solver. Fails with
/// the first vertex that cannot fold flat so, naming it (id and crease-pattern point), the rule it
/// breaks and, where changing one crease would make it fold, that crease. With `around_edges`,
/// only the ends of those edges are checked (the vertices a fold changes).
Status checkFlatVertices(const Paper& paper, const std::vector<double>& angles,
                         const std::vector<int>& around_edges = {});

/// A crease as fold flat's refusals name it: its id and its ends in the crease pattern,
/// "crease 7 (0.5, 0.5)–(1, 0.5)", so that a user who sees no ids finds it on the paper.
std::string creaseText(const Paper& paper, int edge);

/// A face as the layer checks' refusals name it: its id and where it lies on the sheet (the
/// centroid of its crease-pattern polygon), "face 4 (about (0.83, 0.17) on the sheet)".
std::string faceText(const Paper& paper, int face);

}  // namespace virtual_origami::core
