// Accuracy of a folded state (SPEC §6): how far the faces are from their crease-pattern
// shapes, and the fold angles they make.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/face_springs.h"

namespace virtual_origami::core
{
struct ShapeMetrics
{
  StrainStats strain;               // |l/l0 − 1| over every vertex pair of each face
  double planarity = 0.0;           // largest distance of a vertex from its face's best plane, / scale
  double shape_residual = 0.0;      // largest distance of a vertex from its face's best rigid fit, / scale
  double force_residual = 0.0;      // largest seed spring force (eq. 2) on a free vertex, / scale
  std::vector<double> fold_angles;  // per edge (0 on the boundary), measured, on the edges' branches
};

/// Edge strain over every vertex pair of each face.
StrainStats edgeStrain(const Paper& paper);

/// Distance of the face's farthest vertex from its least-squares plane.
double facePlanarity(const Paper& paper, int face);

/// Every crease's fold angle measured from the folded positions (measureFoldAngle), on the
/// branch nearest the angle the edge records (so ±180° keeps its side); 0 on the boundary.
std::vector<double> measuredFoldAngles(const Paper& paper);

/// Largest |F_i| of the seed's spring forces over the vertices not in `fixed` (empty: none
/// fixed): zero at any exact solution.
double forceResidual(const Paper& paper, const std::vector<char>& fixed = {});

ShapeMetrics measureShape(const Paper& paper, const std::vector<char>& fixed = {});

}  // namespace virtual_origami::core
