// Faces that must bend: where rigid faces lock a crease (the bands between curved creases, cut
// into convex pieces held as one face), they fold as compliant triangulated faces instead, their
// facets stiff in the plane but free to bend (as Origami Simulator folds every face). The rest of
// the sheet stays rigid.
#pragma once

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// A facet: an edge inside a face of the file (`split`) that bends, held softly at its target
/// (`target_angle`, flat), instead of joining its two pieces into one rigid face.
inline bool isFacet(const Edge& edge)
{
  return edge.split && edge.isCrease() && edge.target_angle.has_value();
}

/// How many times softer a facet bends than a crease of its length turns: soft enough that the
/// creases reach their targets (a facet bent by φ holds its crease about 1e-3 φ off), stiff
/// enough that a band keeps the least bent shape.
constexpr double kFacetBending = 1.0;

struct CompliantFaces
{
  int bodies = 0;     // faces of the file that became compliant (each cut into triangles)
  int triangles = 0;  // the faces they are now
  int facets = 0;     // their edges that bend
};

/// Finds the faces of the file (the pieces joined by split edges) that rigid faces would lock —
/// two that meet along creases not on one line (the pieces of a curved band, and the band beside
/// it), or one with a crease inside it — and makes each compliant: its pieces cut into triangles
/// by new split edges, and every split edge inside it a facet (isFacet). Faces already compliant
/// and every other face stay as they are. The faces keep their numbers (a cut face keeps its
/// first triangle; the others come after); no vertex is added.
CompliantFaces makeLockedFacesCompliant(Paper& paper);

}  // namespace virtual_origami::core
