// Choosing the rotation axis from a click (seed 000 §3.3.2, Fig. 8–9).
#pragma once

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// Seed steps 1–5: the plane G through the click P and the face centre C, perpendicular to
/// the face; of the face's creases G crosses, the one farthest from P ("the crease on the
/// other side of the centre from the click").
Expected<int> automaticAxis(const Paper& paper, int face, const Vec3& click);

/// The rule the seed rejects (Fig. 9b): the face's crease farthest from the click. Kept to
/// show the difference in tests.
Expected<int> farthestCreaseAxis(const Paper& paper, int face, const Vec3& click);

}  // namespace virtual_origami::core
