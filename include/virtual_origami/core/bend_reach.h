// Where a dragged vertex can go once the faces may bend (SPEC §4.3: rigid faces first, the
// curved model where they cannot follow). Paper bends but does not stretch: a vertex stays
// within its distance along the sheet of every vertex that is held.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/pull.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// Whether bent paper can take `target.vertex` to `target.position` with the `held` vertices
/// where they are: no held vertex may end farther from it than the two lie apart on the crease
/// pattern (the straight line there is the shortest path on a convex sheet; on a sheet with
/// notches the path is longer, so there this lets through some points only stretching reaches).
/// Fails, saying why, on an unknown vertex, a point that is not finite, a held vertex dragged,
/// or a held vertex the point is too far from (the nearest miss is named).
Status bendingReaches(const Paper& paper, const PullTarget& target, const std::vector<int>& held);

}  // namespace virtual_origami::core
