// Bending as a thin plate, per triangle (CurvedMaterial::plate_bending): the triangle's
// curvature H (2 × 2, constant over it) is recovered from the dihedrals of three hinges — its
// own sides', or where a side bends freely (the sheet's edge, a free crease) a neighbour's —
// as the uniform curvature that gives them, exactly for any surface of uniform curvature on any
// mesh; it costs ½·D·A·(ν·(tr H)² + (1 − ν)·H : H). One spring per hinge (the seed's bending)
// is instead a plate of Poisson ratio −1/3 whose stiffness depends on the triangles' shapes.
// Known limit: the recovered curvatures of a patch need not add up to its hinges' total (the
// patch test), and on the CGAL mesh's less regular triangles a bent strip relaxes ~3 % of its
// bending energy into mesh-scale wrinkles at every spacing (0.3 % on the bubble mesh), unless
// the curvature's jumps cost (CurvedMaterial::plate_smoothing; physical papers use 3).
// Beside a held face (CurvedMesh::held_faces, a clamp) the paper is measured against its mirror
// image across the clamp line, so a clamped edge's curvature is recovered in full.
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
