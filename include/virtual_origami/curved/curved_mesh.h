// The triangle mesh of curved paper (seed 002 §2.1): nodes in the crease pattern, each on a
// paper vertex, inside a paper edge or inside a face; triangles that never cross a crease.
// A node on a crease belongs to the faces on both sides, so stacked layers joined there
// share it: the cure for the seed's scene 3, where non-matching meshes fought over the edge.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/core/positions.h"

namespace virtual_origami::core
{
struct MeshNode
{
  Vec2 crease_pattern = Vec2::Zero();
  int paper_vertex = -1;  // the paper vertex it sits on, or -1
  int paper_edge = -1;    // else the paper edge it lies inside, or -1
  double edge_t = 0.0;    // where along that edge, from vertices[0] (0) to vertices[1] (1)
  int paper_face = -1;    // else the face it lies inside
};

struct MeshTriangle
{
  std::array<int, 3> nodes{ -1, -1, -1 };  // counter-clockwise in the crease pattern
  int face = -1;                           // the paper face it lies in
};

struct MeshEdge
{
  std::array<int, 2> nodes{ -1, -1 };
  /// triangles[0] lies left of nodes[0]→nodes[1] in the crease pattern, triangles[1] right;
  /// -1 on the sheet's boundary.
  std::array<int, 2> triangles{ -1, -1 };
  int paper_edge = -1;  // the paper edge (crease or boundary) it runs along, or -1 inside a face
  bool isHinge() const { return triangles[0] >= 0 && triangles[1] >= 0; }
};

struct CurvedMesh
{
  std::vector<MeshNode> nodes;
  std::vector<MeshTriangle> triangles;
  std::vector<MeshEdge> edges;     // derived by linkMesh()
  std::vector<int> vertex_nodes;   // paper vertex → its node
  std::vector<char> curved_faces;  // per paper face: 1 meshed to bend, 0 kept flat and coarse
  /// Per paper face (empty: none): 1 where the caller pins every node of the face (a clamp).
  /// Plate bending then gives the face no energy and measures the paper beside it against the
  /// face's plane, as at a clamped plate's edge (plate_bending.h).
  std::vector<char> held_faces;
  double spacing = 0.0;            // the bubble diameter it was meshed with

  /// Rest (crease-pattern) area of a triangle.
  double restArea(int triangle) const;
  /// The node's rest position as a 3-vector (z = 0), the frame of the crease pattern.
  Vec3 restPosition(int node) const;
  /// Every paper face a node belongs to (one inside a face, two on a crease, more at a vertex).
  std::vector<int> facesOfNode(const Paper& paper, int node) const;
  /// facesOfNode of every node at once, each in the order facesOfNode gives: in time
  /// proportional to the mesh and the paper (each facesOfNode of a paper vertex scans every
  /// face: a loop over the nodes took seconds at 25,000 vertices).
  std::vector<std::vector<int>> facesOfNodes(const Paper& paper) const;
};

/// Derives the edges from the triangles (and which paper edge each runs along); fails when
/// an edge has two triangles on one side or a triangle is not counter-clockwise.
Status linkMesh(CurvedMesh& mesh, const Paper& paper);

/// Node positions of the paper's current folded state, each face placed rigidly: a node on a
/// vertex takes the vertex's folded position, one on an edge the point between its end
/// vertices, one inside a face the face's best rigid pose (facePose) applied to it.
Positions placeNodes(const CurvedMesh& mesh, const Paper& paper);

/// Positions for the nodes of `to` from a deformed state of `from` (re-meshing after a fold
/// keeps the bend): each node is placed by the barycentric coordinates of the triangle of
/// `from` that holds it in the crease pattern, in the same paper face, where one does.
/// Nodes no triangle holds keep their position in `fallback`.
Positions transferNodes(const CurvedMesh& from, const Positions& from_positions, const CurvedMesh& to,
                        const Positions& fallback);

/// Writes the positions of the nodes on paper vertices back into the paper's folded
/// positions and re-measures the fold angles: the coarse view of a curved state.
void applyToPaper(const CurvedMesh& mesh, const Positions& positions, Paper& paper);

struct MeshQuality
{
  double min_angle = 0.0;   // smallest triangle corner in the crease pattern, radians
  double max_angle = 0.0;   // largest
  double min_edge = 0.0;    // shortest edge / spacing
  double max_edge = 0.0;    // longest edge / spacing
  double area = 0.0;        // summed rest area of the triangles
  double mean_radius_ratio = 0.0;  // mean of 2·inradius / circumradius (1 equilateral, 0 flat)
  double well_shaped = 0.0;        // share of triangles with every angle in 45°–75°
  int crossing_triangles = 0;  // triangles whose corners are not all in their face (must be 0)
};
MeshQuality meshQuality(const CurvedMesh& mesh, const Paper& paper);

}  // namespace virtual_origami::core
