// Choosing the rotation axis from a click (seed 000 §3.3.2, Fig. 8–9), or naming it by a
// click on a crease (the seed's manual axis).
#pragma once

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// The crease "on the other side of the centre from the click", for every click on the face
/// (Fig. 9a divides the whole face into one region per crease):
/// seed steps 1–5 first: the plane G through the click P and the face centre C,
/// perpendicular to the face; of the face's creases G crosses, the one farthest from P.
/// Where G crosses no crease (a face with fewer creases than sides), the crease seen from C
/// nearest in angle to the direction from P through C. Fails only when the face has no
/// crease (or on bad input).
Expected<int> automaticAxis(const Paper& paper, int face, const Vec3& click);

/// The rule the seed rejects (Fig. 9b): the face's crease farthest from the click. Kept to
/// show the difference in tests.
Expected<int> farthestCreaseAxis(const Paper& paper, int face, const Vec3& click);

/// The crease nearest to `point` in the folded model, within `radius`; -1 when none is.
/// How a click on a crease line names the axis by hand.
int creaseNear(const Paper& paper, const Vec3& point, double radius);

}  // namespace virtual_origami::core
