// Accuracy of a curved state (SPEC §6): stretch, how sharply the paper bends inside its faces,
// the fold angles its creases make, and whether any layer went through another.
#pragma once

#include <vector>

#include "virtual_origami/curved/curved_mesh.h"
#include "virtual_origami/core/face_springs.h"

namespace virtual_origami::core
{
struct CurvedMetrics
{
  StrainStats strain;          // |l/l0 − 1| over the mesh edges
  double max_bend = 0.0;       // largest |dihedral| on a hinge inside a face, radians
  double max_curvature = 0.0;  // largest |dihedral| / distance between the two triangles' centroids
  /// Per paper edge: the mean dihedral of the mesh hinges along it (FOLD sign, on the branch
  /// nearest the edge's recorded angle); 0 on the boundary.
  std::vector<double> crease_angles;
  double flatness = 0.0;  // largest |dihedral| on a hinge inside a face kept flat (curved_faces 0)
  int penetrations = 0;   // crossing triangle pairs (findTriangleCrossings) at `penetration_tolerance`
};

/// `penetration_tolerance` 0: 1e-9 of the sheet's scale.
CurvedMetrics measureCurved(const CurvedMesh& mesh, const Paper& paper, const Positions& x,
                            double penetration_tolerance = 0.0);

}  // namespace virtual_origami::core
