// The paper model of seed 000 §3.1: vertices with a flat crease-pattern position and a
// folded position, edges that are boundary (one face) or crease (two faces), convex faces.
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products on Vec3

#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

/// FOLD `edges_assignment`.
enum class Assignment
{
  Boundary,    // B
  Mountain,    // M
  Valley,      // V
  Flat,        // F
  Unassigned,  // U
  Cut,         // C
};

char assignmentLetter(Assignment assignment);
std::optional<Assignment> assignmentFromLetter(const std::string& letter);

struct Vertex
{
  Vec2 crease_pattern = Vec2::Zero();  // never changes once the vertex exists
  Vec3 folded = Vec3::Zero();          // current position in the `paper` frame
};

struct Edge
{
  std::array<int, 2> vertices{ -1, -1 };
  Assignment assignment = Assignment::Boundary;
  /// Signed fold angle in radians, FOLD convention: positive valley, negative mountain.
  double fold_angle = 0.0;
  /// faces[0] lies left of vertices[0]→vertices[1] in the crease pattern, faces[1] right;
  /// -1 where there is none (a boundary edge). Derived by linkTopology().
  std::array<int, 2> faces{ -1, -1 };
  /// Added on reading a file only to make one of its concave faces convex (assignment F, flat):
  /// not a crease of the file. Writing joins the faces across it back into the file's face
  /// while it stays flat; creasing along it or turning about it makes it a crease.
  bool split = false;
  /// Where the crease is meant to go (FOLD sign), when a crease-pattern file said so with
  /// edges_foldAngle; folding by assignment drives it there (else ±π by its assignment).
  std::optional<double> target_angle;

  bool isCrease() const { return faces[0] >= 0 && faces[1] >= 0; }
  int otherVertex(int v) const { return vertices[0] == v ? vertices[1] : vertices[0]; }
  int otherFace(int f) const { return faces[0] == f ? faces[1] : faces[0]; }
};

struct Face
{
  /// Counter-clockwise in the crease pattern.
  std::vector<int> vertices;
  /// edges[i] joins vertices[i] and vertices[(i + 1) % n]. Derived by linkTopology().
  std::vector<int> edges;
};

/// FOLD `faceOrders` entry: `above` is +1 when `other` lies above `face` (on the side its
/// front normal points to), -1 when below, 0 when unknown.
struct FaceOrder
{
  int face = -1;
  int other = -1;
  int above = 0;
  bool operator==(const FaceOrder& o) const { return face == o.face && other == o.other && above == o.above; }
};

/// Plain value: copying it is how operations stay transactions (build a new one, then swap).
struct Paper
{
  std::vector<Vertex> vertices;
  std::vector<Edge> edges;
  std::vector<Face> faces;
  std::vector<FaceOrder> face_orders;
  /// Area of the sheet as made; creasing never changes it.
  double sheet_area = 0.0;

  /// An unfolded square sheet of side `size`, corner at the origin, in the z = 0 plane.
  static Paper square(double size = 1.0);

  /// Length scale of the sheet (square root of its area), for relative tolerances.
  double scale() const;

  Vec3 faceCentroid(int face) const;  // mean of the face's folded vertices (seed §3.3.2)
  /// Front normal of the folded face (the side that is +z in the crease pattern).
  Vec3 faceNormal(int face) const;
  double faceArea(int face) const;  // crease-pattern area
  /// The edge joining two vertices, or -1.
  int findEdge(int a, int b) const;
  /// The vertex at a crease-pattern point (within `tolerance`), or -1.
  int vertexAt(const Vec2& crease_pattern_point, double tolerance = 1e-12) const;
  /// Faces that use a vertex.
  std::vector<int> facesOfVertex(int vertex) const;

  bool operator==(const Paper& o) const;  // bit-exact
};

/// Derives Face::edges and Edge::faces from the face cycles; fails on an edge used by
/// more than two faces, twice in one direction, or missing from `edges`.
Status linkTopology(Paper& paper);

/// Breadth-first walk over the faces from `start` across creases (those `crossable` allows,
/// all when it is empty). `step(from, edge, to)` runs once for every face reached after
/// `start`, in walk order. Returns a flag per face: reached or not.
std::vector<char> walkFaces(const Paper& paper, int start, const std::function<void(int, int, int)>& step = {},
                            const std::function<bool(int)>& crossable = {});

/// Recomputes every crease's fold angle from the folded positions, taking the branch
/// nearest the previous value (so ±180° stays on the side it was folded to). A crease
/// folded past `assign_threshold` takes the assignment of its sign.
void updateFoldAngles(Paper& paper, double assign_threshold = 1e-6);

/// Signed dihedral of a crease from the folded positions, in (-π, π].
double measureFoldAngle(const Paper& paper, int edge);

}  // namespace virtual_origami::core
