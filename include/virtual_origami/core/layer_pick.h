// Choosing among stacked layers (SPEC §3.8, the seed's Fig. 15 problem): what lies under a point
// of the folded model, the layer the eye sees first. A press picks the first; a user cycles
// down through the rest.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// Faces the sight line through `point` (along `view`, from the eye into the scene) meets
/// inside, nearest to the eye first; coincident layers (a flat stack) by their stack order.
std::vector<int> facesUnder(const Paper& paper, const Vec3& point, const Vec3& view);

/// Creases that pass within `radius` of the sight line through `point`, nearest to the eye
/// first; coincident ones by the highest layer they border, then by how near they pass.
std::vector<int> creasesUnder(const Paper& paper, const Vec3& point, const Vec3& view, double radius);

/// Vertices within `radius` of the sight line through `point`, ordered as creasesUnder.
std::vector<int> verticesUnder(const Paper& paper, const Vec3& point, const Vec3& view, double radius);

}  // namespace virtual_origami::core
