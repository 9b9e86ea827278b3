// Cursor snapping of seed 000 Fig. 6: to a vertex, to an edge's n-division points, and
// (when the line starts at a vertex) to the n-division directions of the angle there.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
struct SnapSettings
{
  double radius = 0.03;                      // in the paper's length unit
  std::vector<int> edge_divisions{ 2, 4 };   // n for the edge division points
  std::vector<int> angle_divisions{ 2, 4 };  // n for the angle division directions
};

enum class SnapKind
{
  None,
  Vertex,
  EdgeDivision,
  AngleDivision,
};

struct Segment3
{
  Vec3 a = Vec3::Zero();
  Vec3 b = Vec3::Zero();
};

/// Where the cursor went, and the guide to draw for it.
struct Snap
{
  Vec3 point = Vec3::Zero();
  SnapKind kind = SnapKind::None;
  int vertex = -1;                    // Vertex: the vertex; AngleDivision: the start vertex (or the
                                      // one of a layer lying on it whose face is divided)
  int edge = -1;                      // EdgeDivision: the edge
  int face = -1;                      // AngleDivision: the face whose angle is divided
  int divisions = 0;                  // n of the division snapped to
  int index = 0;                      // k of k/n
  std::vector<Vec3> guide_points;     // EdgeDivision: all division points of the edge
  std::vector<Segment3> guide_lines;  // AngleDivision: the division directions, across the face
};

/// Snaps a cursor point (in the `paper` frame, on the folded surface). `start_vertex`, when
/// not -1, is the vertex the line starts at and enables the angle rule (the angles of the faces
/// of every vertex lying at the same point, in any layer, are divided); a direction snapped
/// to goes on to where it leaves the face (or to the cursor, when that lies farther), so a
/// line that ends inside the face still creases it all the way across.
Snap snapPoint(const Paper& paper, const Vec3& cursor, const SnapSettings& settings, int start_vertex = -1);

}  // namespace virtual_origami::core
