// CGAL's 2D mesher over the whole crease pattern: one constrained Delaunay triangulation
// with every boundary and crease segment as a constraint, refined by Ruppert/Shewchuk
// (refine_Delaunay_mesh_2) to an angle and size bound, smoothed by Lloyd iterations, its
// triangles given to the paper faces by a flood fill that stops at the constraints. One
// mesh for the whole sheet, so a node on a crease is shared by the faces on both sides.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/curved/curved_mesh.h"

namespace virtual_origami::core
{
struct CgalMeshOptions
{
  /// The mean edge length aimed at, in paper units (the size bound, the longest edge allowed,
  /// is √2 times it); 0: a tenth of the sheet's scale, as BubbleMeshOptions::spacing.
  /// Negative or not finite: an error.
  double spacing = 0.0;
  /// Bound on sin² of the smallest triangle angle: 0.125 ≈ 20.7°, the largest for which
  /// Delaunay refinement is guaranteed to end. Away from input angles smaller than that.
  double shape_bound = 0.125;
  /// Lloyd smoothing after refinement (0: none); it stops earlier once nodes stop moving.
  int lloyd_iterations = 10;
  /// Per paper face: 1 refines it so it can bend, 0 leaves it coarse: no node inside it, only
  /// its corners and the nodes refinement puts on its sides (on shared edges, and where a
  /// node nearby encroaches on a side). Empty: every face.
  std::vector<char> curved_faces;
};

/// Meshes the paper's crease pattern. Nodes: paper vertices first (node v is vertex v), then
/// the nodes inside paper edges in edge order and along each edge, then each face's interior
/// nodes. Fails on bad options or a degenerate paper (no faces, a face without area,
/// coordinates that are not finite, edges that cross), changing nothing.
Expected<CurvedMesh> cgalMesh(const Paper& paper, const CgalMeshOptions& options = {});

}  // namespace virtual_origami::core
