// Wavefront OBJ of the folded paper, for tools that do not read FOLD.
#pragma once

#include <string>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// Folded vertices, crease-pattern texture coordinates, one polygon per face.
std::string formatObj(const Paper& paper);

}  // namespace virtual_origami::core
