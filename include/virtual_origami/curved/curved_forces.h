// The forces of curved paper (seed 002 ch. 3) as energies over the mesh: stretch
// f = k(l − l0) on edges, shear f = p(θ − θ0) on triangle corners, bend f = q(φ − φ0) on the
// dihedral of triangle pairs, none across creases. Each term is ½·w·(g − g0)² of one
// measure g; its force −w(g − g0)∇g points the way the seed draws it (Fig. 3.2–3.4), and
// being a gradient it neither drifts nor spins the sheet. Weights come from the rest
// triangles, so one set of moduli means the same paper at every mesh resolution.
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "virtual_origami/curved/curved_mesh.h"

namespace virtual_origami::core
{
/// Moduli of the paper, SI for a sheet in metres (defaults suit a sheet of scale ~1).
struct CurvedMaterial
{
  double stretch = 1.0;  // k: in-plane stiffness (force per unit strain); paper barely stretches
  double shear = 0.1;    // p: resistance to changing corner angles, per unit area
  /// q: bending stiffness (moment per unit curvature). Paper bends easily: q/k = 1e-6 of the
  /// sheet's scale² keeps the stretch of a curl near 1e-4 while it bends freely.
  double bend = 1e-6;
  /// Hinges on a crease turn freely (seed 002 §3.4); a crease with memory pulls towards its
  /// recorded fold angle with this times `bend`.
  double crease = 0.0;
  /// Faces kept coarse and flat (§4.3, curved_faces 0) bend this many times stiffer.
  double flat_face = 1e4;
  double density = 1.0;  // mass per area, for the dynamics and the weight (kg/m² in SI)
  /// The paper's thickness (m) when the moduli come from a physical paper (paper_material.h);
  /// 0: not given. A mesh finer than this is refused (see checkThicknessAgainstSpacing).
  double thickness = 0.0;
  /// Bending per triangle as a thin plate (plate_bending.h) of Poisson ratio `poisson_ratio`,
  /// `bend` its D, instead of one spring per hinge. Off: the seed's hinges.
  bool plate_bending = false;
  double poisson_ratio = 0.0;
  /// Plate bending: the jump of the curvature between neighbouring triangles costs this times
  /// the plate's energy of the jump (nothing for a uniform curvature), so that the sheet cannot
  /// trade curvature between triangles for mesh-scale wrinkles.
  double plate_smoothing = 0.0;
};

struct StretchTerm
{
  int i = -1, j = -1;
  double rest = 0.0, weight = 0.0;
};
/// The angle at corner `o` of a triangle, between its sides to `i` and `j`.
struct ShearTerm
{
  int o = -1, i = -1, j = -1;
  double rest = 0.0, weight = 0.0;
};
/// The signed dihedral on hinge a→b (FOLD sign: positive valley) between the triangle with
/// `left` (left of a→b in the crease pattern) and the one with `right`.
struct BendTerm
{
  int a = -1, b = -1, left = -1, right = -1;
  double rest = 0.0, weight = 0.0;
  bool crease = false;
};

/// Bending as a plate (plate_bending.h): ½·θᵀ·W·θ over the dihedrals θ of a few hinges (minus
/// their rest angles) — one triangle's curvature, or the jump of it between two triangles.
struct PlateTerm
{
  std::vector<std::array<int, 4>> hinges;  // each as hingeAngle takes it: a, b, left, right
  std::vector<double> rest;
  Eigen::MatrixXd weight;
  std::vector<int> nodes;  // every node of its hinges, once
};

struct CurvedTerms
{
  std::vector<StretchTerm> stretch;
  std::vector<ShearTerm> shear;
  std::vector<BendTerm> bend;
  std::vector<PlateTerm> plate;  // with plate_bending, in place of the non-crease bend terms
  std::vector<double> mass;  // lumped: a third of each adjacent triangle's rest area × density
};

/// The terms of a mesh: weights w = k·(2/√3)·A/l0² for an edge with adjacent rest area A,
/// p·A for each corner of a triangle of area A, q·(√3/2)·|e|²/(A_left + A_right) for a
/// hinge (each equals the modulus on an equilateral mesh). Crease hinges get crease·q
/// towards their edge's recorded fold angle, or no term at all when `crease` is 0.
CurvedTerms curvedTerms(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material);

/// Energy of each kind at `x`.
struct CurvedEnergy
{
  double stretch = 0.0, shear = 0.0, bend = 0.0;
  double total() const { return stretch + shear + bend; }
};

/// A Hessian assembled straight into a sparse matrix (no triplets to sort): its lower
/// triangle of 3 × 3 blocks (blockPattern; the Cholesky factorisation reads no more, and
/// products go through selfadjointView<Lower>), and a block the pattern lacks is counted in
/// `missing` (the caller then grows the pattern and assembles again).
struct BlockHessian
{
  Eigen::SparseMatrix<double>* matrix = nullptr;
  int missing = 0;

  /// Adds `block` at block row fk, block column fl (free node indices).
  template <class Block>
  void add(int fk, int fl, const Block& block)
  {
    const int* outer = matrix->outerIndexPtr();
    const int* inner = matrix->innerIndexPtr();
    const int column = 3 * fl;
    const int* begin = inner + outer[column];
    const int* end = inner + outer[column + 1];
    const int* at = std::lower_bound(begin, end, 3 * fk);
    if (at == end || *at != 3 * fk)
    {
      ++missing;
      return;
    }
    // The three columns of a block column share their rows: the block sits at the same
    // offset in each.
    const long offset = at - begin;
    double* values = matrix->valuePtr();
    for (int c = 0; c < 3; ++c)
    {
      double* v = values + outer[column + c] + offset;
      v[0] += block(0, c);
      v[1] += block(1, c);
      v[2] += block(2, c);
    }
  }
};

/// The pattern of 3 × 3 blocks over `free_count` free nodes coupling every two free nodes of
/// each group (and each node with itself), lower block triangle only: zero values, ready for
/// BlockHessian.
Eigen::SparseMatrix<double> blockPattern(int free_count, const std::vector<int>& free_index,
                                         const std::vector<std::array<int, 4>>& groups);

/// The node groups the terms couple (an edge, a triangle, a hinge; unused slots −1).
std::vector<std::array<int, 4>> termGroups(const CurvedTerms& terms);

/// Where the gradient and Hessian go: one 3-row block per free node, indexed by `free_index`
/// (−1 for a held node, whose rows and columns are dropped), as triplets or into a
/// BlockHessian.
struct Assembly
{
  const std::vector<int>* free_index = nullptr;
  Eigen::VectorXd* gradient = nullptr;                 // += ∇E over the free nodes
  std::vector<Eigen::Triplet<double>>* hessian = nullptr;  // += the Hessian (see addTerm)
  BlockHessian* blocks = nullptr;                           // or += it here

  bool wantsHessian() const { return hessian || blocks; }
  template <class Block>
  void addBlock(int fk, int fl, const Block& block) const
  {
    if (blocks)
      blocks->add(fk, fl, block);
    else
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          hessian->emplace_back(3 * fk + r, 3 * fl + c, block(r, c));
  }
};

/// Adds a gradient, one column per node of `nodes`, to `out` (held nodes dropped).
template <int K>
void addGradient(const std::array<int, K>& nodes, const Eigen::Matrix<double, 3, K>& gradient, const Assembly& out)
{
  if (out.gradient)
    for (int k = 0; k < K; ++k)
      if (const int f = (*out.free_index)[nodes[k]]; f >= 0)
        out.gradient->segment<3>(3 * f) += gradient.col(k);
}

/// Adds a Hessian over `nodes` (3K × 3K, node by node) to `out` (held nodes dropped).
template <int K>
void addHessian(const std::array<int, K>& nodes, const Eigen::Matrix<double, 3 * K, 3 * K>& hessian,
                const Assembly& out)
{
  for (int k = 0; k < K; ++k)
    if (const int fk = (*out.free_index)[nodes[k]]; fk >= 0)
      for (int l = 0; l < K; ++l)
        if (const int fl = (*out.free_index)[nodes[l]]; fl >= 0 && (fk >= fl || !out.blocks))
          out.addBlock(fk, fl, hessian.template block<3, 3>(3 * k, 3 * l));
}

/// Adds ½·w·r² to the returned energy and its derivatives to `out`, for a measure with
/// residual r and gradient `grad` (one column per node of `nodes`). With the measure's second
/// derivatives `curvature` (3K × 3K), the matrix is the term's exact Hessian w(∇g∇gᵀ + r∇²g),
/// indefinite in places (a compressed edge, a bent hinge); without, Gauss–Newton's w∇g∇gᵀ.
/// Thin paper needs the exact one: its bending stiffness is smaller than the compressive
/// terms that clamping or Gauss–Newton would drop, and Newton would crawl.
template <int K>
double addTerm(const std::array<int, K>& nodes, double weight, double residual, const Eigen::Matrix<double, 3, K>& grad,
               const Assembly& out, const Eigen::Matrix<double, 3 * K, 3 * K>* curvature = nullptr)
{
  addGradient<K>(nodes, weight * residual * grad, out);
  if (out.wantsHessian())
  {
    const Eigen::Map<const Eigen::Matrix<double, 3 * K, 1>> g(grad.data());
    Eigen::Matrix<double, 3 * K, 3 * K> h = weight * g * g.transpose();
    if (curvature)
      h += weight * residual * *curvature;
    addHessian<K>(nodes, h, out);
  }
  return 0.5 * weight * residual * residual;
}

CurvedEnergy evaluateCurved(const CurvedTerms& terms, const Positions& x, const Assembly& out = {});

/// Every stretch, shear and bend term at rest in the shape `x` (a bend's rest angle the
/// dihedral there, on the branch nearest the rest it had): a folded model drawn with its
/// layers apart (layered_start.h) rests as drawn, its creases and the strips beside them
/// remembering their shape. Plate terms are left as they are.
void restTermsAt(CurvedTerms& terms, const Positions& x);

/// The measures, their gradients with respect to the nodes (columns in argument order) and
/// their second derivatives (rows and columns node by node, x y z each).
double cornerAngle(const Vec3& o, const Vec3& i, const Vec3& j, Eigen::Matrix<double, 3, 3>* grad = nullptr,
                   Eigen::Matrix<double, 9, 9>* curvature = nullptr);
double hingeAngle(const Vec3& a, const Vec3& b, const Vec3& left, const Vec3& right,
                  Eigen::Matrix<double, 3, 4>* grad = nullptr, Eigen::Matrix<double, 12, 12>* curvature = nullptr);

}  // namespace virtual_origami::core
