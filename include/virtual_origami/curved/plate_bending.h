// Bending as a thin plate, per triangle (CurvedMaterial::plate_bending): the triangle's
// curvature H (2 × 2, constant over it) is the one whose quadratic surface leaves the normal
// slopes at its sides' midpoints (Morley's plate element) where the mesh's hinges put them —
// each hinge's dihedral split between its two triangles in proportion to their heights — and
// it costs ½·D·A·(ν·(tr H)² + (1 − ν)·H : H). Unlike one spring per hinge (a plate of Poisson
// ratio −1/3, its stiffness set by the triangles' shapes) this has the paper's ν, and a side on
// the sheet's edge (or a free crease) is a free edge: its slope is whatever costs least.
#pragma once

#include <vector>

#include "virtual_origami/curved/curved_forces.h"

namespace virtual_origami::core
{
/// The plate terms of a mesh with material.bend = D and material.poisson_ratio = ν. A crease
/// turns freely (crease 0) or bends as the paper towards its recorded fold angle (crease > 0);
/// faces kept flat bend flat_face times stiffer.
std::vector<PlateTerm> plateTerms(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material);

/// Their energy at `x`, and its gradient and Hessian into `out`.
double evaluatePlate(const std::vector<PlateTerm>& terms, const Positions& x, const Assembly& out = {});

}  // namespace virtual_origami::core
