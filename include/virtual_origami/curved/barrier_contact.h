// Contact that no step can pass: incremental potential contact (Li et al. 2020) on the true
// distances between a mesh's nodes and triangles and between its edges. A pair nearer than the
// activation distance d̂ feels the barrier −κ·(d − d̂)²·ln(d/d̂), which grows without bound as
// the pair closes; a solver's step is cut short of the first time any pair would touch
// (continuous collision detection: when a node meets a triangle's plane, or two edges one
// plane, the roots of a cubic in the step), so a pair apart stays apart, and layers lying a
// hair apart can still slide along each other by steps much longer than their gap.
// Needs the layers apart to begin with (layered_start.h).
#pragma once

#include <array>
#include <unordered_map>
#include <vector>

#include "virtual_origami/curved/curved_forces.h"
#include "virtual_origami/curved/curved_mesh.h"

namespace virtual_origami::core
{
struct BarrierContactOptions
{
  double activation = 0.0;  // d̂; 0: 1/100 of the mesh spacing
  double stiffness = 1.0;   // κ
};

class BarrierContact
{
public:
  explicit BarrierContact(const CurvedMesh& mesh, const BarrierContactOptions& options = {});

  /// Watches every node–triangle and edge–edge pair sharing no node whose boxes at `x` (swept
  /// along `motion` to `x + motion`, when given) lie within `reach` of each other: with `reach`
  /// d̂, every pair within the barrier's reach anywhere along that motion.
  void update(const Positions& x, const Positions* motion, double reach);

  /// The barrier energy of the watched pairs (its gradient and a positive semidefinite
  /// Hessian into `out`); infinity when a watched pair touches or crossed.
  double evaluate(const Positions& x, const Assembly& out = {}) const;

  /// The largest share (≤ 1) of the motion from `x` to `x + motion` that brings no watched
  /// pair within `separation` × its distance at `x` of touching: 0.9 × the first time of
  /// contact along it, 1 when none meets.
  double safeStep(const Positions& x, const Positions& motion, double separation = 0.1) const;

  /// Pairs nearer than `distance` at `x` (a layered start's layers touch where several folds'
  /// hinges meet in one node) are kept from touching by a barrier of their own, active below
  /// the distance they start at; pairs that start touching are set aside for good.
  void guardNearPairs(const Positions& x, double distance);

  /// The nodes of each watched pair (node, triangle's three; or edge's two, edge's two).
  std::vector<std::array<int, 4>> pairNodes() const { return pairs_; }
  /// Watched pairs within the activation distance at `x`.
  int activePairs(const Positions& x) const;
  /// The nearest watched pair's distance at `x` (infinity with none).
  double minimumDistance(const Positions& x) const;
  double activation() const { return activation_; }
  double stiffness() const { return stiffness_; }
  /// κ such that the barrier pushes with `force` at half its activation distance.
  void setPush(double force);

private:
  /// Calls f(kind, nodes) for every pair sharing no node, not set aside, whose boxes at `x`
  /// (swept to `x + motion` when given) come within `reach`.
  template <class F>
  void forPairs(const Positions& x, const Positions* motion, double reach, F&& f) const;

  const CurvedMesh& mesh_;
  double activation_, stiffness_;
  std::vector<std::array<int, 4>> pairs_;
  std::vector<char> kinds_;  // 0: node–triangle, 1: edge–edge
  std::vector<double> reach_;  // per watched pair, its barrier's activation distance
  struct PairHash
  {
    size_t operator()(const std::array<int, 5>& p) const
    {
      size_t h = 0;
      for (int v : p)
        h = h * 1000003u + static_cast<size_t>(v);
      return h;
    }
  };
  std::unordered_map<std::array<int, 5>, double, PairHash> near_start_;  // pair → its start distance
};

/// The first time t in [0, 1] at which point p + t·dp meets triangle (a + t·da, b + t·db,
/// c + t·dc) within `tolerance`, or 2 when it does not.
double pointTriangleImpact(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& dp, const Vec3& da,
                           const Vec3& db, const Vec3& dc, double tolerance);
/// The same for segments (p, q) and (r, s).
double edgeEdgeImpact(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s, const Vec3& dp, const Vec3& dq,
                      const Vec3& dr, const Vec3& ds, double tolerance);

}  // namespace virtual_origami::core
