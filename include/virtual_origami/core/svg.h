// A picture of a paper as SVG: the crease pattern beside the folded form seen from above.
#pragma once

#include <string>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// Crease pattern (mountain red dash-dot, valley blue dashed, boundary black) on the left,
/// the folded form projected on the table (faces shaded by layer height) on the right.
std::string paperSvg(const Paper& paper, const std::string& title = "");

}  // namespace virtual_origami::core
