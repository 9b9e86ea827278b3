// Which layer each face lies in, for drawing coincident layers of a flat fold apart.
#pragma once

#include <array>
#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// A level per face from pairs (below, above): 0 for a face with nothing below it, else one
/// more than the highest face below it (the longest path up to it). A cycle's faces keep what
/// they reached before it.
std::vector<int> levelsFromOrders(size_t faces, const std::vector<std::array<int, 2>>& below_above);

/// A level per face: 0 for faces with nothing recorded below them, else one more than the
/// highest face `face_orders` puts below it, "below" measured along +z of the `paper` frame.
/// Orders that contradict each other (a cycle) are ignored past the first.
std::vector<int> stackLevels(const Paper& paper);

/// How many layers of paper a point of the folded model lies in: the faces whose folded
/// polygon contains it (strictly inside, by more than `margin`) and whose plane passes within
/// `margin` of it. Count it away from creases and vertices, where faces only touch.
int layerCount(const Paper& paper, const Vec3& point, double margin = 1e-9);

}  // namespace virtual_origami::core
