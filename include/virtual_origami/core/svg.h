// A picture of a paper as SVG: the crease pattern beside the folded form.
#pragma once

#include <string>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// Crease pattern (mountain red dash-dot, valley blue dashed, boundary black) on the left,
/// the folded form seen obliquely from above on the right (front side light, back darker).
std::string paperSvg(const Paper& paper, const std::string& title = "");

}  // namespace virtual_origami::core
