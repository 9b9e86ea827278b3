// Strips of paper for the closed forms (SPEC §4.2, §6): a strip of length L and width b along
// +x, clamped flat at x = 0 (every node of a clamp zone x ∈ [−c, 0] held), and either held at
// its other end too (a zone x ∈ [L, L + c] turned and moved as one piece: Euler's elastica) or
// free there (a cantilever under its own weight). Flat creases at x = 0 and x = L give the
// meshes a line of nodes exactly where the strip starts and ends; they bend as the paper does
// (CurvedMaterial::crease 1), so the clamp is a clamp and not a hinge, and holdStripZones makes
// the plate terms measure the strip there against the clamp's plane (its mirror image).
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/curved/curved_mesh.h"
#include "virtual_origami/curved/curved_solver.h"
#include "virtual_origami/curved/elastica.h"

namespace virtual_origami::core
{
enum class StripMesher
{
  Bubble,
  Cgal,
};

struct StripScene
{
  Paper paper;
  double length = 0.0, width = 0.0, clamp = 0.0;
  bool held_end = false;  // a second clamp zone beyond x = L
};

/// The strip's paper (clamp zones `clamp` long, 0: half the width). Fails on a length, width
/// or clamp that is not positive and finite.
Expected<StripScene> stripScene(double length, double width, bool held_end, double clamp = 0.0);

/// The strip meshed at `spacing` (m) by either mesher.
Expected<CurvedMesh> meshStrip(const StripScene& scene, StripMesher mesher, double spacing);

/// Marks the zones stripPins holds as held faces (CurvedMesh::held_faces): plate bending then
/// measures the strip beside them as a clamped plate's edge. Without it they bend as paper.
void holdStripZones(const StripScene& scene, CurvedMesh& mesh);

/// The pins: the clamp zone (x ≤ 0) flat where it lies; with a held end, the end zone (x ≥ L)
/// turned by `end_angle` about y (towards +z) with its edge x = L moved to `end` (x, z).
std::vector<CurvedPin> stripPins(const StripScene& scene, const CurvedMesh& mesh, const Eigen::Vector2d& end = {0, 0},
                                 double end_angle = 0.0);

/// Node positions with the strip laid along `curve` (each node at arc length x, width y), the
/// clamp zone flat and the end zone carried on straight: a start near the answer.
Positions stripAlong(const StripScene& scene, const CurvedMesh& mesh, const ElasticaCurve& curve);

/// The sheet's position at a crease-pattern point (inside the triangle holding it, linearly);
/// fails for a point off the sheet.
Expected<Vec3> pointOnSheet(const CurvedMesh& mesh, const Positions& x, const Vec2& crease_pattern);

/// Largest distance between the strip's mid-line (y = b/2, at `samples` + 1 equal steps over
/// [0, L]) and the curve's (x, b/2, z), over L. Fails when a sample is off the sheet.
Expected<double> midlineDeviation(const StripScene& scene, const CurvedMesh& mesh, const Positions& x,
                                  const ElasticaCurve& curve, int samples = 100);

/// The material of the strip scenes: `material` with crease 1 (the flat creases bend as paper).
CurvedMaterial stripMaterial(CurvedMaterial material);

}  // namespace virtual_origami::core
