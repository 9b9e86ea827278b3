// Faces that must bend: where rigid faces lock a crease (the bands between curved creases, cut
// into convex pieces held as one face), they fold as compliant triangulated faces instead, their
// facets stiff in the plane but free to bend (as Origami Simulator folds every face). The rest of
// the sheet stays rigid.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// A facet: an edge inside a face of the file (`split`) that bends, held softly at its target
/// (`target_angle`, flat), instead of joining its two pieces into one rigid face.
inline bool isFacet(const Edge& edge)
{
  return edge.split && edge.isCrease() && edge.target_angle.has_value();
}

/// A facet's bending stiffness over a crease's of the same length: as stiff, as Origami Simulator
/// has them by default (its panel and crease stiffness are both 0.7). Softer facets let the
/// creases come nearer their targets but crumple the bands (a curved pleat at 75 % crossed itself
/// with facets 10 or 1000 times softer) instead of bending them smoothly.
constexpr double kFacetBending = 1.0;

struct CompliantFaces
{
  int bodies = 0;     // faces of the file that became compliant (each cut into triangles)
  int triangles = 0;  // the faces they are now
  int facets = 0;     // their edges that bend
};

/// Finds the faces of the file (the pieces joined by split edges) that rigid faces would lock —
/// two that meet along creases not on one line (a curved band and the band beside it; off the
/// line by more than 1e-3 of the sheet), or one with a crease inside it — and makes each
/// compliant: its pieces cut into triangles by new split edges, and every split edge inside it a
/// facet (isFacet). Faces already compliant and every other face stay as they are. The faces
/// keep their numbers (a cut face keeps its first triangle; the others come after); no vertex is
/// added.
CompliantFaces makeLockedFacesCompliant(Paper& paper);

/// Makes the faces of the file that `faces` belong to compliant, as above: where a rigid fold
/// left the creases stuck (a hypar's trapezoids, which must twist). `bodies` counts those that
/// were not compliant already.
CompliantFaces makeFacesCompliant(Paper& paper, const std::vector<int>& faces);

/// How many faces of the file are compliant (have a facet).
int compliantFaceCount(const Paper& paper);

}  // namespace virtual_origami::core
