// Paper in physical units (SPEC §4.2): thickness, Young's modulus, Poisson ratio and areal
// mass, and the moduli of the mesh's forces (CurvedMaterial) that give a thin plate's energies:
// the membrane's (E h, G h) and the bending's, D = E h³ / (12 (1 − ν²)). The sheet's
// coordinates are then metres, forces newtons and gravity m/s².
#pragma once

#include <string>
#include <vector>

#include "virtual_origami/core/result.h"
#include "virtual_origami/curved/curved_forces.h"

namespace virtual_origami::core
{
/// A sheet of paper, SI units.
struct PaperMaterial
{
  double thickness = 0.0;        // h, m
  double youngs_modulus = 0.0;   // E, Pa (in-plane, the mean of the machine and cross directions)
  double poisson_ratio = 0.0;    // ν
  double areal_density = 0.0;    // kg/m² (grammage / 1000)
};

/// The presets: "copy_paper", "kami", "card".
std::vector<std::string> paperPresetNames();
/// A preset by name; fails on any other name, listing the presets.
Expected<PaperMaterial> paperPreset(const std::string& name);

/// Plate stiffnesses of the sheet.
double membraneStiffness(const PaperMaterial& paper);  // E h / (1 − ν²), N/m
double shearStiffness(const PaperMaterial& paper);     // G h = E h / (2 (1 + ν)), N/m
double bendingStiffness(const PaperMaterial& paper);   // D = E h³ / (12 (1 − ν²)), N·m

/// Refuses a material whose thickness, modulus or areal density is not positive and finite, or
/// whose Poisson ratio lies outside (−1, 1/3] (the mesh's edge springs alone have ν = 1/3 and
/// its corner terms can only stiffen shear: a larger ν would need a negative corner modulus).
Status checkPaperMaterial(const PaperMaterial& paper);

/// How the mesh bends: as a plate per triangle (plate_bending.h: the paper's ν, exact for any
/// uniform curvature on any mesh), or by the seed's springs on the hinges (a plate of ν = −1/3
/// whose stiffness depends on the triangles' shapes; exact only on equilateral triangles).
enum class PaperBending
{
  Plate,
  Hinges,
};

/// The plate_smoothing of physical papers: the curvature's jumps between triangles cost 3 times
/// their plate energy, which keeps the less regular CGAL triangles from trading curvature for
/// mesh-scale wrinkles (they relax ~2.5 % / (1 + 3·s) of a cantilever's stiffness at every
/// spacing) while adding only O(spacing²) to a smooth bend (docs/CURVED.md, the closed forms).
constexpr double kPaperPlateSmoothing = 3.0;

/// The mesh's moduli for this paper (derivation in paper_material.cpp): uniaxial stretch ε
/// costs ½·E h·ε² per area, shear γ ½·G h·γ² (both exactly on equilateral triangles), a bend of
/// curvature K ½·D·(ν (tr K)² + (1 − ν) K : K) (Plate) or, on equilateral triangles, ½·D·κ²
/// for a cylindrical bend (Hinges). Plate bending comes with plate_smoothing kPaperPlateSmoothing.
/// `thickness` and `density` (the areal density) are set too. Fails as checkPaperMaterial.
Expected<CurvedMaterial> curvedMaterial(const PaperMaterial& paper, PaperBending bending = PaperBending::Plate);

/// Refuses moduli the solver cannot use: stretch or bend not positive and finite, shear, crease,
/// flat_face, density or thickness negative or not finite.
Status checkCurvedMaterial(const CurvedMaterial& material);

/// Refuses a mesh finer than the paper is thick: bending by dihedral angles is the thin-plate
/// limit, which elements shorter than the thickness are not in. No thickness (0): no limit.
Status checkThicknessAgainstSpacing(double thickness, double spacing);

}  // namespace virtual_origami::core
