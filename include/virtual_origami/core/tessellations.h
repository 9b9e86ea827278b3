// Crease-pattern tessellations at any size (Miura-ori, Yoshimura, square twist, waterbomb) for
// benchmarks and tests: flat papers with their mountain/valley assignment and target fold angles.
#pragma once

#include <string>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// A generated pattern. `paper` is flat (folded = crease pattern in z = 0, every fold angle 0),
/// its creases assigned M or V. Paper has no field for where a crease is meant to go, so it
/// rides beside it: target_fold_angle[e] is +π for a valley, −π for a mountain, 0 for a boundary
/// edge (FOLD sign, as Edge::fold_angle).
struct Tessellation
{
  Paper paper;
  std::vector<double> target_fold_angle;
  /// Every interior vertex satisfies Maekawa and Kawasaki (and big-little-big), so the targets
  /// describe a flat-folded state vertex by vertex. False for the waterbomb, whose row-boundary
  /// vertices do not fold flat: its targets then give only the direction each crease folds.
  bool flat_foldable = false;
  int columns = 0;
  int rows = 0;
};

/// Miura-ori of `columns` × `rows` parallelograms, built by miuraOri() (reference_patterns.h,
/// same vertex and face numbering) with sides `a` along x and `b` at angle `gamma` ∈ (0, π/2).
/// Straight crease (i, j)→(i+1, j) folds (−1)^(i+j)·π, zigzag crease (i, j)→(i, j+1) folds
/// −(−1)^i·π: the flat limit of miuraFoldAngles().
Expected<Tessellation> miuraTessellation(int columns, int rows, double a = 1.0, double b = 1.0,
                                         double gamma = 1.0471975511965976);

/// The same Miura-ori rigidly folded: straight creases at ±`rho` and zigzag creases at
/// ±2·atan(tan(ρ/2)/cos γ) (miuraFoldAngles), faces placed by foldToAngles. The targets stay the
/// flat-folded ones. Fails when rho is outside (−π, π).
Expected<Tessellation> miuraTessellationFolded(int columns, int rows, double a, double b, double gamma, double rho);

/// Yoshimura pattern on a `columns`·width × `rows`·height rectangle: horizontal mountain lines
/// every `height`, vertices on them every `width` (shifted by width/2 on odd lines, plus the two
/// sheet corners), valley diagonals between neighbouring lines. Interior vertices have degree 6
/// with sector angles φ, π − 2φ, φ, φ, π − 2φ, φ where tan φ = 2·height/width; the pattern is
/// flat-foldable when φ ≤ π/3 (otherwise the π − 2φ sector breaks big-little-big).
Expected<Tessellation> yoshimuraTessellation(int columns, int rows, double width = 1.0, double height = 0.5);

/// Square-twist tessellation by shrink-rotate: a `columns` × `rows` grid of square tiles of side
/// `pitch`, each shrunk by `shrink` about its centre and turned by `twist`; neighbouring tiles are
/// joined by parallelogram pleats, and four tiles meeting at an interior grid point by a small
/// square (the twist's centre). Needs 0 < twist < π/2 and 0 < shrink < cos(twist) (beyond it the
/// pleats overlap). Interior vertices have degree 4 with sectors 90°, θ, 90°, 180° − θ; the twist
/// squares alternate all-valley and all-mountain like a checkerboard. The outline is the tiles'
/// jagged border (no partial twists at the edge).
Expected<Tessellation> squareTwistTessellation(int columns, int rows, double pitch = 1.0,
                                               double twist = 0.5235987755982988, double shrink = 0.5);

/// Waterbomb tessellation (the waterbomb tube's pattern): rows of `columns` waterbomb bases, each
/// a width × height rectangle with its two diagonals (valley) and horizontal mid-line (mountain),
/// odd rows shifted by half a base (half bases at the ends); row boundaries are mountain lines.
/// The bases' centres are degree-6 vertices that satisfy Maekawa and Kawasaki; the degree-4
/// vertices on the row boundaries do not (flat_foldable is false).
Expected<Tessellation> waterbombTessellation(int columns, int rows, double width = 1.0, double height = 1.0);

enum class TessellationKind
{
  Miura,
  Yoshimura,
  SquareTwist,
  Waterbomb,
};

std::string tessellationName(TessellationKind kind);

/// Vertex count of the kind's pattern with `columns` × `rows` units (the generators' formulas).
long tessellationVertexCount(TessellationKind kind, int columns, int rows);

struct GridSize
{
  int columns = 0;
  int rows = 0;
};

/// The columns and rows whose default-parameter pattern has the vertex count nearest
/// `vertex_count`, among those whose sheet is no more than twice as long as it is wide.
GridSize gridForVertexCount(TessellationKind kind, long vertex_count);

/// The kind's pattern with default parameters and about `vertex_count` vertices
/// (gridForVertexCount), e.g. 1,000 to 10,000 for benchmarks.
Expected<Tessellation> tessellationWithVertices(TessellationKind kind, long vertex_count);

/// Local flat-foldability at every interior vertex (one with no boundary edge): Maekawa
/// (|M − V| = 2, every crease M or V), Kawasaki (the alternate sector angles sum to π within
/// `tolerance` radians) and big-little-big (a sector smaller than both its neighbours lies
/// between a mountain and a valley). Necessary conditions, not sufficient beyond degree 4. One
/// message per failing vertex; empty when all pass.
std::vector<std::string> flatFoldabilityProblems(const Paper& paper, double tolerance = 1e-9);

}  // namespace virtual_origami::core
