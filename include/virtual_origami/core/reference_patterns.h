// Crease patterns of the reference scenes (SPEC §6) built directly as papers, for tests and
// the benchmark: a degree-4 vertex and Miura-ori, with closed-form fold angles.
#pragma once

#include <array>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// A flat paper from crease-pattern vertices and counter-clockwise faces: a side shared by
/// two faces becomes an unassigned crease, any other a boundary edge, numbered in order of
/// first appearance. Fails when the faces do not link (linkTopology).
Expected<Paper> patternPaper(const std::vector<Vec2>& vertices, const std::vector<std::vector<int>>& faces);

/// One interior vertex (index 0, at the origin) with creases to boundary vertices 1–4 at
/// `radius`; crease k runs to vertex k + 1 and sectors[k] is the angle from crease k to crease
/// k + 1 (counter-clockwise, radians, summing to 2π). Faces are the four triangles.
Paper degree4Vertex(const std::array<double, 4>& sectors, double radius = 1.0);

/// Miura-ori of `columns` × `rows` parallelograms with sides `a` (along x) and `b` (at angle
/// `gamma` to x, leaning alternately right and left from row to row). Vertex (i, j),
/// 0 ≤ i ≤ columns, 0 ≤ j ≤ rows, is number j·(columns + 1) + i; face (i, j) is
/// j·columns + i.
Paper miuraOri(int columns, int rows, double a, double b, double gamma);

/// Fold angles of a flat-foldable degree-4 vertex with sectors α, β, π − α, π − β between
/// creases 1→2, 2→3, 3→4, 4→1, given ρ1. Mode 1: ρ3 = ρ1, ρ4 = −ρ2,
/// tan(ρ2/2) = −cos((α+β)/2)/cos((α−β)/2)·tan(ρ1/2). Mode 2: ρ3 = −ρ1, ρ4 = ρ2,
/// tan(ρ2/2) = sin((α+β)/2)/sin((α−β)/2)·tan(ρ1/2).
std::array<double, 4> degree4FoldAngles(double alpha, double beta, double rho1, int mode);

/// One fold angle per edge of miuraOri(columns, rows, …) folded rigidly with straight-crease
/// angle ρ: straight crease (i, j)→(i+1, j) gets (−1)^(i+j)·ρ, zigzag crease (i, j)→(i, j+1)
/// gets −(−1)^i·2·atan(tan(ρ/2)/cos γ) (mode 2 of degree4FoldAngles at every vertex).
std::vector<double> miuraFoldAngles(const Paper& miura, int columns, int rows, double gamma, double rho);

/// Places every face rigidly at the given fold angles (one per edge), face 0 where it lies in
/// the crease pattern, and records the angles. Fails, changing nothing, when they do not close.
Status foldToAngles(Paper& paper, const std::vector<double>& fold_angles);

}  // namespace virtual_origami::core
