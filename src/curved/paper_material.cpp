#include "virtual_origami/curved/paper_material.h"

#include <cmath>
#include <sstream>

namespace virtual_origami::core
{
namespace
{
struct Preset
{
  const char* name;
  PaperMaterial paper;
};

// Paper is orthotropic (machine direction 2–3 × stiffer than cross direction); E is a mean of
// the two. Tensile stiffness indices of printing papers are 5–10 MN·m/kg along, 2–4 across
// (Niskanen, "Paper Physics", 2nd ed., 2008, ch. 5); E = index × bulk density (~800 kg/m³ for
// copy paper) gives 2–8 GPa. In-plane Poisson ratios are 0.1–0.4 (Baum, Brennan & Habeger,
// "Orthotropic elastic constants of paper", Tappi J. 64(8), 1981); 0.3 is their mean.
const Preset kPresets[] = {
  // 80 g/m² office paper (ISO 536 grammage), caliper ~0.1 mm.
  { "copy_paper", { 0.1e-3, 4e9, 0.3, 0.080 } },
  // 15-cm origami kami: 60–70 g/m², ~0.07 mm; softer, less filled than copy paper.
  { "kami", { 0.07e-3, 3e9, 0.3, 0.060 } },
  // 0.3-mm card (folding boxboard), ~300 g/m² at a density of ~1000 kg/m³.
  { "card", { 0.3e-3, 3e9, 0.3, 0.300 } },
};

bool positiveFinite(double v) { return std::isfinite(v) && v > 0; }
bool nonNegativeFinite(double v) { return std::isfinite(v) && v >= 0; }

std::string number(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

std::vector<std::string> paperPresetNames()
{
  std::vector<std::string> names;
  for (const Preset& p : kPresets)
    names.emplace_back(p.name);
  return names;
}

Expected<PaperMaterial> paperPreset(const std::string& name)
{
  std::string known;
  for (const Preset& p : kPresets)
  {
    if (name == p.name)
      return p.paper;
    known += (known.empty() ? "" : ", ") + std::string(p.name);
  }
  return Expected<PaperMaterial>::failure("no paper preset \"" + name + "\" (the presets are " + known + ")");
}

double membraneStiffness(const PaperMaterial& paper)
{
  const double nu = paper.poisson_ratio;
  return paper.youngs_modulus * paper.thickness / (1 - nu * nu);
}

double shearStiffness(const PaperMaterial& paper)
{
  return paper.youngs_modulus * paper.thickness / (2 * (1 + paper.poisson_ratio));
}

double bendingStiffness(const PaperMaterial& paper)
{
  const double h = paper.thickness, nu = paper.poisson_ratio;
  return paper.youngs_modulus * h * h * h / (12 * (1 - nu * nu));
}

Status checkPaperMaterial(const PaperMaterial& paper)
{
  if (!positiveFinite(paper.thickness))
    return failure("the paper's thickness must be positive and finite (it is " + number(paper.thickness) + " m)");
  if (!positiveFinite(paper.youngs_modulus))
    return failure("the paper's Young's modulus must be positive and finite (it is " + number(paper.youngs_modulus) +
                   " Pa)");
  if (!positiveFinite(paper.areal_density))
    return failure("the paper's areal density must be positive and finite (it is " + number(paper.areal_density) +
                   " kg/m²)");
  if (!std::isfinite(paper.poisson_ratio) || paper.poisson_ratio <= -1 || paper.poisson_ratio > 1.0 / 3.0)
    return failure("the paper's Poisson ratio must lie in (-1, 1/3] (it is " + number(paper.poisson_ratio) +
                   "): the mesh's edge springs alone have 1/3 and its corner terms can only stiffen shear");
  return success();
}

// The mesh's energies under a uniform strain ε and curvature K, on triangles of side l and
// area A = (√3/4)·l² (each edge then has weight k, each hinge q; see curvedTerms):
// - Edge springs ½·k·(l·êᵀεê)², three directions 60° apart: the triangular spring lattice, a
//   2D solid with Lamé moduli λ' = μ' = (√3/4)·k.
// - Corner terms ½·p·A·Δθ²: an even stretch keeps the angles; a deviatoric strain ε_d changes
//   them by Σ Δθ² = (9/4)·ε_d : ε_d (worked for ε = diag(e, −e): Δθ = −(√3/2)e, −(√3/2)e, √3e),
//   adding (9/8)·p to the shear modulus only.
//   A plate in plane stress has λ = E h ν/(1 − ν²), μ = E h/(2(1 + ν)): its bulk λ + μ = 2λ'
//   and shear μ = μ' + (9/8)p give k = 2(λ + μ)/√3 = E h/(√3 (1 − ν)) and
//   p = (4/9)(μ − λ) = 2 E h (1 − 3ν)/(9 (1 − ν²)), not negative for ν ≤ 1/3.
// - Hinges ½·q·φ²: the dihedrals of the three hinge directions of a lattice on the surface
//   z = ½·xᵀKx (worked exactly for K = κ·x̂x̂ᵀ: φ = κl/(2√3)·(1, 2, 2) by direction 0°, 60°, 120°)
//   give, per area, ½·(√3/2)·q·((tr K)² − (8/3)·det K): a plate with ν = −1/3. Matching a
//   cylindrical bend, ½·D·κ²: q = (2/√3)·D. (A narrow strip free to curve across bends as a beam
//   of (8/9)·D·b then, where paper's is (1 − ν²)·D·b: 2.3 % softer at ν = 0.3.)
Expected<CurvedMaterial> curvedMaterial(const PaperMaterial& paper, PaperBending bending)
{
  if (const Status checked = checkPaperMaterial(paper); !checked)
    return Expected<CurvedMaterial>::failure(checked.message());
  const double eh = paper.youngs_modulus * paper.thickness, nu = paper.poisson_ratio;
  const double lambda = eh * nu / (1 - nu * nu), mu = eh / (2 * (1 + nu));
  CurvedMaterial material;
  material.stretch = 2 * (lambda + mu) / std::sqrt(3.0);
  material.shear = 4.0 / 9.0 * (mu - lambda);
  if (bending == PaperBending::Plate)
  {
    material.plate_bending = true;
    material.plate_smoothing = kPaperPlateSmoothing;
    material.poisson_ratio = nu;
    material.bend = bendingStiffness(paper);
  }
  else
    material.bend = 2 / std::sqrt(3.0) * bendingStiffness(paper);
  material.density = paper.areal_density;
  material.thickness = paper.thickness;
  return material;
}

Status checkCurvedMaterial(const CurvedMaterial& m)
{
  if (!positiveFinite(m.stretch))
    return failure("the stretch modulus must be positive and finite (it is " + number(m.stretch) + ")");
  if (!positiveFinite(m.bend))
    return failure("the bending modulus must be positive and finite (it is " + number(m.bend) + ")");
  if (!nonNegativeFinite(m.shear))
    return failure("the shear modulus must be finite and not negative (it is " + number(m.shear) + ")");
  if (!nonNegativeFinite(m.crease) || !nonNegativeFinite(m.flat_face))
    return failure("the crease and flat-face factors must be finite and not negative (they are " + number(m.crease) +
                   " and " + number(m.flat_face) + ")");
  if (!nonNegativeFinite(m.density))
    return failure("the density must be finite and not negative (it is " + number(m.density) + ")");
  if (!nonNegativeFinite(m.thickness))
    return failure("the thickness must be finite and not negative (it is " + number(m.thickness) + ")");
  return success();
}

Status checkThicknessAgainstSpacing(double thickness, double spacing)
{
  if (!nonNegativeFinite(thickness))
    return failure("the paper's thickness must be finite and not negative (it is " + number(thickness) + " m)");
  if (thickness > 0 && !(thickness <= spacing))
    return failure("the paper (" + number(thickness) + " m thick) is thicker than the mesh spacing (" +
                   number(spacing) + " m): bending by the mesh's hinges is the thin-plate limit; mesh coarser "
                   "or give a thinner paper");
  return success();
}

}  // namespace virtual_origami::core
