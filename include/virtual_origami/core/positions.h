// Folded positions as one 3 × V matrix, the form the solvers iterate on.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
using Positions = Eigen::Matrix3Xd;

Positions foldedPositions(const Paper& paper);
void setFoldedPositions(Paper& paper, const Positions& positions);

/// For each vertex its index among the free (not fixed) vertices, or -1 when fixed. An empty
/// `fixed` holds none.
std::vector<int> freeIndices(const std::vector<char>& fixed, size_t vertex_count, int* free_count = nullptr);

}  // namespace virtual_origami::core
