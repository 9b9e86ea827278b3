// The three tests of seed 002 §4.1 (SPEC §4.2, §6), on the square abcd with a = (0, 0),
// b = (s, 0), c = (s, s), d = (0, s): (1) the uncreased sheet, corner a pulled onto c with c
// fixed; (2) the same with a crease on the diagonal bd; (3) the triangle ade folded 180°
// (valley) on de, e the midpoint of ab, then b pulled onto c with c fixed — where the
// seed's simulation broke.
#pragma once

#include <string>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/curved_metrics.h"
#include "virtual_origami/curved/curved_solver.h"

namespace virtual_origami::core
{
struct SeedScene
{
  std::string name;
  Paper paper;             // creased and folded as the pull starts
  int pulled = -1;         // paper vertex pulled by the hand
  int fixed = -1;          // paper vertex held in place
  Vec3 axis_point = Vec3::Zero(), axis = Vec3::UnitZ();  // the pull turns `pulled` about this line
  double lift = 0.0;       // and raises it this far by the end, so it lands on top of `fixed`

  /// Where the pulled corner is at fraction `s` ∈ [0, 1] of the pull: turned by s·π about
  /// the perpendicular bisector of pulled–fixed (the path of a fold there), rising off the
  /// front of the sheet, and lifted s·lift so it ends one gap above the fixed corner.
  Vec3 pullAt(double s) const;
};

/// Scene 1, 2 or 3 on a square of side `size`; `gap` is how far above the fixed corner the
/// pulled one ends (two paper thicknesses keeps them from pressing). Fails for any other
/// number.
Expected<SeedScene> seedScene(int number, double size = 1.0, double gap = 2e-3);

struct SeedSceneOptions
{
  BubbleMeshOptions mesh;  // spacing 0: a tenth of the sheet
  int steps = 20;          // the pull in equal steps, each solved to balance (a drag)
  double until = 1.0;      // the fraction of the pull the steps end at
  CurvedMaterial material;
  ContactOptions contact;
  CurvedSolveOptions solve;
};

struct SeedSceneStep
{
  double fraction = 0.0;  // of the pull
  CurvedReport report;
  CurvedMetrics metrics;
};

struct SeedSceneRun
{
  CurvedMesh mesh;
  Positions positions;  // at the end
  std::vector<SeedSceneStep> steps;
  /// Every step balanced, none diverged, no layer through another.
  bool passed() const;
};

/// Meshes the scene's paper and pulls: the fixed corner pinned where it is, the pulled one
/// along pullAt, step by step. Stops early at a step that diverges. Fails when meshing does.
Expected<SeedSceneRun> runSeedScene(const SeedScene& scene, const SeedSceneOptions& options = {});

/// The same pull on a mesh of the scene's paper made by any mesher (options.mesh unused).
SeedSceneRun runSeedSceneOn(const SeedScene& scene, CurvedMesh mesh, const SeedSceneOptions& options = {});

/// Scene 1 as its mesh-refinement study runs it (mesh_bench, docs/CURVED.md): pulled to `pull`
/// of the half turn in steps of 0.05, bending `bend` (q/k in side²) as a plate (ν = 0.3,
/// smoothing kPaperPlateSmoothing: the seed's hinges cost a bend by the triangles' shapes, which
/// differ from mesh to mesh), every balance solved to 1e-11 and tested for stability. The
/// default, 72° with q/k = 1e-3, is far past the sheet's buckling, so every mesh curls alike and
/// the curl converges; at 36° the sheet has only just buckled, and how far it curls depends on
/// where each mesh puts the buckling load.
SeedSceneOptions refinementPullOptions(double bend = 1e-3, double pull = 0.4);

/// A sheet at a per_side × per_side grid of points of its paper (the square [0, side]², inset by
/// a thousandth of the side: a point on the edge may lie in no triangle by rounding), wherever
/// its nodes are: solutions on different meshes compared point for point (shapeDistance).
Positions sheetOnGrid(const CurvedMesh& mesh, const Positions& positions, double side, int per_side = 21);

}  // namespace virtual_origami::core
