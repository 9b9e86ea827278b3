// Keeping a bend (seed 002; docs/CURVED.md "A bend kept"): the curved model's bent sheet made
// the paper's own state. A face the sheet bent becomes the sheet's triangles inside it, joined
// by facets that hold the bend as their rest angle (compliant_faces.h, isFacet); a face that did
// not bend stays one rigid face and only moves where the sheet moved it. The model holds no more
// than the scene needs: the mesh only where the paper is curved.
#pragma once

#include <array>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// The curved model's sheet as it was let go: its triangle mesh in the crease pattern (each
/// triangle inside one face of the paper, a node on every paper vertex) and where each node is.
struct BentSheet
{
  std::vector<Vec2> points;                   // the nodes in the crease pattern
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise in the crease pattern
  std::vector<Vec3> positions;                // where each node is (paper frame)
};

struct KeptBend
{
  std::vector<int> bent_faces;  // the faces (of the paper before) that bent
  int triangles = 0;            // the faces they became
  int facets = 0;               // the edges between them that hold the bend
  double largest_bend = 0.0;    // the largest facet angle (radians)
  double max_strain = 0.0;      // |l/l0 − 1| over every vertex pair of each face, after
};

/// How far (relative to the sheet's scale) a face's nodes may lie off their best rigid placement
/// and the face still count as not bent.
constexpr double kBentFaceTolerance = 1e-6;
/// The stretch a kept sheet may carry: paper bends, it hardly stretches (the curved model's
/// membrane keeps its sides within a fraction of this).
constexpr double kKeptBendMaxStrain = 0.01;

/// Keeps `sheet`'s shape as the paper's state: every vertex goes where the sheet put its node,
/// each bent face is replaced by its triangles (the first keeps the face's number, the others
/// come after), the paper edges the triangles' nodes lie on are split there (the face beside
/// keeps the new points on its side), and the triangles' sides inside a face become facets with
/// the bend as their target. Creases keep their assignments; the layer order of bent faces is
/// dropped (they no longer lie flat on anything). Refused, with the paper untouched, when the
/// sheet does not fit the paper (a vertex without a node, a triangle outside every face or
/// across one's side, faces not covered), a number is not finite, nothing bent, or the sheet
/// stretches the paper beyond kKeptBendMaxStrain.
Expected<KeptBend> keepBend(Paper& paper, const BentSheet& sheet);

/// Per face: whether it is part of a kept bend (a facet of it holds a bend, not flat).
std::vector<char> keptBendFaces(const Paper& paper);

}  // namespace virtual_origami::core
