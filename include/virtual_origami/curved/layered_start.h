// A folded model's layers lie on each other (a flat fold puts them in one plane), and contact
// that keeps layers apart with a barrier (no pair may ever touch) needs them apart to begin
// with. Each face is lifted off its plane by its place in the stack (a few 1e-6 of the sheet
// per layer), the faces of other planes moving with the layers they hang from; each fold's
// hinge rises half way between its two faces inside the mesh's crease strips (triangles one
// strip wide beside every crease, BubbleMeshOptions::crease_strip) and is set out past the
// hinges it wraps; and the sheet's raw edges draw back a strip's width, clear of the hinges
// of the folds they lie in. What still touches lies next to paper vertices, where the hinges
// of several folds at several levels meet (on the crane of sequences/crane.json: 81 pairs of
// triangles of 2,088, all within 1e-3 of a vertex; docs/CURVED.md).
#pragma once

#include <vector>

#include "virtual_origami/core/result.h"
#include "virtual_origami/curved/curved_mesh.h"

namespace virtual_origami::core
{
struct LayeredStartOptions
{
  double gap = 0.0;  // the lift between two layers of a stack; 0: 1e-6 of the sheet's scale
  /// The width of the mesh's crease strips (BubbleMeshOptions::crease_strip), 0: 120 gaps.
  /// The sheet's own edges draw back that far into their faces, clear of the hinges of folds
  /// they lie in (a hinge between levels a and b rises over the strip's width).
  double strip = 0.0;
  /// A hinge joining layers k levels apart moves out past the crease by setback × k × gap, so
  /// that nested folds' hinges lie outside one another.
  double setback = 0.01;
  double plane_tolerance = 1e-7;  // faces within it of one plane share a stack (× scale)

  double gapFor(const Paper& paper) const { return gap > 0 ? gap : 1e-6 * paper.scale(); }
  double stripFor(const Paper& paper) const { return strip > 0 ? strip : 120 * gapFor(paper); }
};

struct LayeredStart
{
  Positions positions;
  std::vector<int> levels;       // per paper face: its place in its plane's stack (0: lowest)
  std::vector<int> plane_of;     // per paper face: which plane (stack) it lies in
  int planes = 0;
};

/// The nodes of `mesh` placed as the folded `paper` has them (placeNodes), each moved off its
/// faces' planes by their stack levels (from `paper.face_orders` and flat folds), hinges set out,
/// the sheet's raw edges drawn back a strip's width.
LayeredStart layeredStart(const CurvedMesh& mesh, const Paper& paper, const LayeredStartOptions& options = {});

/// How far apart across `plane` (along its first face's normal) the nodes on its faces lie at
/// `x`: a stack's thickness, its levels × the gap as laid out, more where its layers part (a
/// folded crane's body opening as its wings are pulled apart).
double stackThickness(const CurvedMesh& mesh, const Paper& paper, const LayeredStart& start, int plane,
                      const Positions& x);

}  // namespace virtual_origami::core
