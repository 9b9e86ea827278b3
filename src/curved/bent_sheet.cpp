#include "virtual_origami/curved/bent_sheet.h"

namespace virtual_origami::core
{
BentSheet bentSheetOf(const CurvedMesh& mesh, const Positions& positions)
{
  BentSheet sheet;
  sheet.points.reserve(mesh.nodes.size());
  sheet.positions.reserve(mesh.nodes.size());
  for (size_t k = 0; k < mesh.nodes.size(); ++k)
  {
    sheet.points.push_back(mesh.nodes[k].crease_pattern);
    sheet.positions.push_back(positions.col(static_cast<Eigen::Index>(k)));
  }
  sheet.triangles.reserve(mesh.triangles.size());
  for (const MeshTriangle& t : mesh.triangles)
    sheet.triangles.push_back(t.nodes);
  return sheet;
}

}  // namespace virtual_origami::core
