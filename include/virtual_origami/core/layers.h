// Which layer each face lies in, for drawing coincident layers of a flat fold apart.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// A level per face: 0 for faces with nothing recorded below them, else one more than the
/// highest face `face_orders` puts below it, "below" measured along +z of the `paper` frame.
/// Orders that contradict each other (a cycle) are ignored past the first.
std::vector<int> stackLevels(const Paper& paper);

}  // namespace virtual_origami::core
