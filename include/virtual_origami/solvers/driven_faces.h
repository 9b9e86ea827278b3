// The energy a crease driver balances: stiff faces that keep their crease-pattern shape, and
// soft hinges pulled towards target fold angles. Scale-free per cell, so that the strain it
// leaves does not grow with the number of cells: each face counts its residuals over its own
// size squared, each hinge its length over its faces' size.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/positions.h"
#include "virtual_origami/solvers/rigid_faces.h"

namespace virtual_origami::core
{
/// A crease as a hinge: its axis a→b (Edge::vertices), one wing vertex on each side (the face
/// vertex farthest from the axis in the crease pattern; faces[0] is the left one).
struct Hinge
{
  int edge = -1;
  int a = -1, b = -1, left = -1, right = -1;
  double weight = 0.0;  // crease length over the mean size of its two faces
};

/// The signed fold angle of a hinge (FOLD sign, as measureFoldAngle) from its four points.
double hingeAngle(const Hinge& hinge, const Positions& x);

/// dθ/dx of the four points a, b, left, right (one column each).
Eigen::Matrix<double, 3, 4> hingeAngleGradient(const Hinge& hinge, const Positions& x);

/// The derivative of hingeAngleGradient at x along v: (∇²θ v) by point, as its columns.
Eigen::Matrix<double, 3, 4> hingeAngleGradientChange(const Hinge& hinge, const Positions& x, const Positions& v);

/// The faces and hinges of a paper, and the energy
///   E = ½ K Σ_f Σ_{v∈f} |(x_v − x̄_f) − R_f p̃_v|² / s_f² + ½ Σ_c w_c (θ_c − θ*_c)²
/// with R_f fitted per face, s_f² the face's mean squared radius, and only the hinges with a
/// finite target in the second sum. The facets of compliant faces (core/compliant_faces.h) are
/// hinges too, w_c scaled by kFacetBending, always driven to their own target. Positions are in
/// units of the sheet's scale inside.
class DrivenFaces
{
public:
  DrivenFaces(const Paper& paper, double face_stiffness);

  /// Targets per edge (NaN: free); a facet keeps its own. Angles are unwrapped against
  /// `reference` (per edge, the branch nearest it), so a crease at ±π stays on the side it is on.
  void setTargets(const std::vector<double>& targets);
  void setReference(const std::vector<double>& reference) { reference_ = reference; }

  struct Evaluation
  {
    double energy = 0.0;
    double face_energy = 0.0;
    double hinge_energy = 0.0;
  };
  struct Linearization;
  /// Energy at x (positions divided by scale()), and its gradient dE/dx when asked; and the
  /// Gauss–Newton linearisation at x when asked (as linearize(x), the faces' fits shared).
  Evaluation evaluate(const Positions& x, Positions* gradient = nullptr, Linearization* linearization = nullptr) const;

  /// The hinge term of the energy alone at x (no face fitted: a fraction of evaluate's cost).
  double hingeEnergy(const Positions& x) const;

  /// Unwrapped fold angle of every hinge's edge at x (NaN for edges that are no hinge).
  std::vector<double> angles(const Positions& x) const;

  /// The constant matrix: the face term with rotations frozen (a Laplacian per face) plus each
  /// driven hinge's stiffness along its flat-state gradient (Bergou et al. 2006 for a flat rest
  /// state), over the vertices with free_index ≥ 0. Scalar: the same for x, y and z.
  Eigen::SparseMatrix<double> constantMatrix(const std::vector<int>& free_index, int free_count) const;

  /// The Gauss–Newton matrix at x (3 rows per free vertex, lower triangle): each face's
  /// rotation eliminated as in the rigid Newton solver (so a mechanism's turns cost nothing),
  /// plus w_c ∇θ ∇θᵀ per driven hinge. Positive semidefinite; exact at a balanced state up to
  /// the hinges' curvature times their miss.
  Eigen::SparseMatrix<double> gaussNewtonMatrix(const Positions& x, const std::vector<int>& free_index,
                                                int free_count) const;
  /// The same matrix as entries (summed where they repeat), in an order that depends on the
  /// pattern alone: a caller that keeps where each lands refills the values without sorting.
  void gaussNewtonTriplets(const Positions& x, const std::vector<int>& free_index,
                           std::vector<Eigen::Triplet<double>>& out) const;

  /// The Gauss–Newton matrix at one state, kept as factors per face and hinge so that its
  /// product with a vector costs one pass over them (Newton–Krylov), never assembled.
  /// Flat arrays, no allocation per face: a 10,000-vertex pattern's linearisation is a
  /// preview frame's hot path.
  struct Linearization
  {
    Eigen::Matrix3Xd turned_rest;  // q_v = R_f p̃_v per face vertex, faces one after another
    std::vector<Eigen::Matrix3d> inertia_inverse;
    std::vector<Eigen::Matrix<double, 3, 4>> hinge_gradient;  // driven hinges, in order
    // For hessianProduct: per face the fitted frame Q (R_f's first two columns) and the
    // stretch S = Qᵀ M of the polar decomposition M = Q S (S's trace 0: a sliver face, taken
    // as in the Gauss–Newton matrix); per driven hinge its miss θ − θ*; and the state.
    std::vector<Eigen::Matrix<double, 3, 2>> frame;
    std::vector<Eigen::Matrix2d> stretch_inverse;
    std::vector<double> stretch_trace;
    std::vector<double> hinge_miss;
    Positions at;
  };
  Linearization linearize(const Positions& x) const;
  /// out = H v over every vertex (3 × V; entries of held vertices in v must be zero, and are
  /// left out of `out` by the caller).
  void gaussNewtonProduct(const Linearization& linearization, const Positions& v, Positions& out) const;
  /// out = ∇²E v, the energy's own Hessian: the Gauss–Newton matrix plus what it leaves out,
  /// the faces' residual stress (the derivative of each face's polar factor) and the hinges'
  /// curvature times their miss. Along a mechanism both are of the order of the hinges' own
  /// stiffness, so Newton steps with it converge quadratically where Gauss–Newton's converge
  /// linearly (at a ratio of about 0.1 on a Miura-ori folded part way). Indefinite away from
  /// a stable balance.
  void hessianProduct(const Linearization& linearization, const Positions& v, Positions& out) const;

  const std::vector<RigidFace>& faces() const { return faces_; }
  const std::vector<Hinge>& hinges() const { return hinges_; }
  double scale() const { return scale_; }
  double faceStiffness() const { return stiffness_; }

private:
  void prepare(Linearization& linearization) const;
  /// A hinge's fold angle at x on the branch nearest its reference.
  double unwrappedAngle(const Hinge& hinge, const Positions& x) const;
  /// Adds face f's block row of the Gauss–Newton matrix times v to out.
  void addFaceGaussNewtonProduct(size_t face, const Linearization& linearization, const Positions& v,
                                 Positions& out) const;
  /// Adds the driven hinges' w ∇θ ∇θᵀ v to out, and with `curvature` their w (θ − θ*) ∇²θ v.
  void addHingeProducts(const Linearization& linearization, const Positions& v, bool curvature,
                        Positions& out) const;
  void linearizeFace(size_t face, const Eigen::Matrix3d& rotation, const Positions& x,
                     Linearization& linearization) const;

  std::vector<RigidFace> faces_;
  std::vector<int> face_offset_;  // where each face's vertices start in Linearization::turned_rest
  std::vector<double> face_weight_;  // K / s_f²
  std::vector<Hinge> hinges_;
  std::vector<double> target_;       // per hinge, NaN when free
  std::vector<double> facet_target_;  // per hinge, a facet's own target (NaN for a crease)
  std::vector<double> reference_;    // per edge
  double scale_ = 1.0;
  double stiffness_ = 1.0;
  Eigen::Matrix2Xd crease_pattern_;
};

/// Best rotation of a face onto centred points: the closed-form polar factor of the 3 × 2
/// moment (fast), by SVD where the face is too thin for it (see fitRotation).
Eigen::Matrix3d fitFaceRotation(const RigidFace& face, const Positions& x, Eigen::Vector3d* mean);

}  // namespace virtual_origami::core
