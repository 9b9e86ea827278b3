// Layers must not pass through each other (SPEC §4.2). Each node is kept on its side of the
// triangles near it, at least `thickness` away, by a penalty ½·w·(t − g)² on its signed
// distance g. The side is taken when the pair first comes near and kept while it stays near;
// for layers that start coincident (a flat fold) it comes from the model's layer order.
#pragma once

#include <algorithm>
#include <array>
#include <map>
#include <utility>
#include <vector>

#include "virtual_origami/curved/curved_forces.h"

namespace virtual_origami::core
{
struct ContactOptions
{
  double thickness = 0.0;  // the gap kept between layers; 0: 1/1000 of the sheet's scale
  /// w; 0: 100 × stretch / spacing, a hundred times an edge's spring constant, so that the
  /// forces folding presses layers together with sink in a small part of the thickness.
  double stiffness = 0.0;
  /// How near (beyond the thickness) a node must come to a triangle to be watched; 0: one
  /// mesh spacing. Solvers limit each step to less than half of it, so no node can cross a
  /// layer between two looks.
  double range = 0.0;
  /// Pairs nearer than this in the crease pattern are left alone as neighbours on the sheet.
  /// 0 (the default) leaves alone only the triangles around the node itself: a node's
  /// projection falls inside a neighbouring triangle only where the sheet folds past 90°
  /// between them, and near the hinge of a 180° fold that is just what must be kept apart.
  /// Within one face, pairs nearer than √3 × the search's width (thickness + range + edge
  /// margin + skin: about 4.5 spacings) are always left alone: a face does not fold.
  double exclusion = 0.0;
  /// A node just beyond the sheet's edge still keeps to its side of the edge's triangle, up
  /// to this far out (0: half a mesh spacing): a layer lying flush with another's edge would
  /// otherwise slip under it between nodes.
  double edge_margin = 0.0;
  /// In place of the penalty on plane distances: incremental potential contact
  /// (barrier_contact.h), whose barrier no step can pass, on the true distances between the
  /// mesh's nodes and triangles and between its edges. Needs the layers apart to begin with
  /// (layered_start.h); pairs nearer than d̂ in the shape the first solve starts from (where a
  /// layered start's hinges meet at paper vertices) are kept from touching below the distance
  /// they start at (BarrierContact::guardNearPairs).
  bool barrier = false;
  double barrier_activation = 0.0;  // d̂: pairs nearer than this feel it (0: half the layered start's gap)
  /// The barrier's push at half its activation distance, × stretch × spacing (sets κ).
  double barrier_force = 1e-2;
};

/// +1 when face `a` lies on the front side of face `b`, −1 behind, 0 unknown: from the
/// paper's face orders, else from a crease between them folded to ±180° (valley: in front).
int layerSide(const Paper& paper, int a, int b);

class LayerContact
{
public:
  LayerContact(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material,
               const ContactOptions& options = {});

  /// Finds the node–triangle pairs in range at `x`, and the pairs of crossing edges (both
  /// kept a thickness apart: nodes alone let an edge dip under a ridge of a bent layer); a
  /// new pair takes its side from the geometry, or from the layer order when it lies within
  /// half the thickness. Pairs that left the range are forgotten.
  void update(const Positions& x);

  /// The pairs update() watches for, found at `x` (the costly part of an update: a grid of
  /// every triangle and edge), good while no node moves farther than half the skin from `at`.
  struct Candidates
  {
    std::vector<std::array<int, 2>> nodes;  // (node, triangle)
    std::vector<std::array<int, 2>> edges;  // (edge, edge), lower first
    Positions at;
  };
  /// Finds them without changing this contact (another thread may, meanwhile, update it).
  Candidates candidatesAt(const Positions& x) const;
  /// Whether update(x) would search anew (its candidates are not good for x).
  bool needsSearch(const Positions& x) const;
  /// How far some node at `x` has moved from where the candidates were found, less the motion
  /// common to all nodes (a translation), over the half skin it may move (above 1: update
  /// searches anew; infinity before any search).
  double skinUsed(const Positions& x) const;
  /// Takes candidates found elsewhere in place of the kept ones, when they are good for `x`
  /// and found nearer it than the kept ones; false (nothing changed) otherwise.
  bool adoptCandidates(Candidates&& found, const Positions& x);

  /// Penalty energy of the watched pairs (and its derivatives into `out`).
  double evaluate(const Positions& x, const Assembly& out = {}) const;

  int watchedPairs() const { return static_cast<int>(pairs_.size() + edge_pairs_.size()); }
  /// The four nodes each watched pair couples (node and triangle, or two edges).
  std::vector<std::array<int, 4>> pairNodes() const;
  /// Watched pairs closer than the thickness (pressing).
  int touching(const Positions& x) const;
  /// The smallest gap of a watched pair on its own side (negative: crossed over); infinity
  /// with none.
  double worstGap(const Positions& x) const;
  double thickness() const { return thickness_; }
  double stiffness() const { return stiffness_; }
  double range() const { return range_; }

private:
  struct Pair
  {
    int node = -1, triangle = -1;
    int side = 0;  // which side of the triangle's front the node keeps to
  };
  /// Two mesh edges that cross (seen along n = a × b) with `side` the sign of a's offset
  /// along n: catches a layer's edge slipping under another's ridge between nodes.
  struct EdgePair
  {
    int a = -1, b = -1;
    int side = 0;
  };
  /// skinUsed() for candidates found at `at`.
  double skinUsedFrom(const Positions& at, const Positions& x) const;
  /// Rebuilds the candidate pairs from a grid, at `x`.
  void findCandidates(const Positions& x);
  int sideFor(int node, int triangle, double signed_distance) const;
  /// Whether `node` lies in paper face `face` (on its inside or its boundary).
  bool inFace(int node, int face) const
  {
    return std::find(node_faces_[node].begin(), node_faces_[node].end(), face) != node_faces_[node].end();
  }
  int edgeSideFor(int a, int b, double signed_distance, const Vec3& normal, const Positions& x) const;

  const CurvedMesh& mesh_;
  const Paper& paper_;
  double thickness_, stiffness_, range_, exclusion_, edge_margin_;
  /// Candidate pairs are found within reach + skin and kept until some node has moved half
  /// the skin: most updates then test only them, not the whole mesh.
  double skin_;
  std::vector<std::array<int, 2>> candidates_;       // (node, triangle)
  std::vector<std::array<int, 2>> edge_candidates_;  // (edge, edge), lower first
  Positions candidates_at_;
  std::vector<std::array<char, 3>> open_side_;  // per triangle: the side opposite corner k is the sheet's edge
  std::vector<std::vector<int>> node_faces_;
  std::vector<int> edge_face_;     // per mesh edge, the paper face it lies inside (−1 on a crease)
  std::vector<Vec2> edge_middle_;  // per mesh edge, its middle in the crease pattern
  std::vector<Pair> pairs_;
  std::map<std::pair<int, int>, int> sides_;  // (node, paper face) → side, while near
  std::vector<EdgePair> edge_pairs_;
  std::map<std::pair<int, int>, int> edge_sides_;  // (edge, edge) → side, while near
};

/// (mesh edge, triangle) pairs where the edge passes through a triangle it shares no node
/// with (strictly, beyond `tolerance` on both sides of its plane): none when no layer went
/// through another.
std::vector<std::array<int, 2>> findPenetrations(const CurvedMesh& mesh, const Positions& x, double tolerance);
inline int countPenetrations(const CurvedMesh& mesh, const Positions& x, double tolerance)
{
  return static_cast<int>(findPenetrations(mesh, x, tolerance).size());
}

/// Whether two triangles p and q cross: an edge of one passes through the inside of the other,
/// its ends beyond `tolerance` on both sides of the other's plane. Triangles that only touch,
/// or lie flat on each other within the tolerance (layers of a flat fold), do not cross.
bool trianglesCross(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& q0, const Vec3& q1, const Vec3& q2,
                    double tolerance);

/// Pairs of mesh triangles with no node in common that cross (trianglesCross), each pair
/// once, lower index first: none when no layer went through another.
std::vector<std::array<int, 2>> findTriangleCrossings(const CurvedMesh& mesh, const Positions& x, double tolerance);
inline int countTriangleCrossings(const CurvedMesh& mesh, const Positions& x, double tolerance)
{
  return static_cast<int>(findTriangleCrossings(mesh, x, tolerance).size());
}

}  // namespace virtual_origami::core
