// The curved model's sheet as the kept bend takes it (kept_bend.h): its mesh and positions.
#pragma once

#include "virtual_origami/core/kept_bend.h"
#include "virtual_origami/curved/curved_mesh.h"

namespace virtual_origami::core
{
/// The mesh's nodes in the crease pattern, its triangles, and the nodes where `positions` has them.
BentSheet bentSheetOf(const CurvedMesh& mesh, const Positions& positions);

}  // namespace virtual_origami::core
