// Shapes of curved paper: the mesh's nodes settle where the stretch, shear and bend forces
// and the layer contact balance around the pinned nodes. Two methods: the seed's (damped
// dynamics integrated by RK4, seed 002 §4.1), and a static Newton method (the exact Hessian,
// shifted by Levenberg–Marquardt damping until it is positive definite, and a line search)
// that reaches the same balance in tens of steps instead of thousands; and a quasi-Newton
// method (L-BFGS on one constant matrix, factorised once per mesh and pin set) that balances
// the same energy without a Hessian per solve.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "virtual_origami/curved/barrier_contact.h"
#include "virtual_origami/curved/contact.h"
#include "virtual_origami/curved/curved_forces.h"
#include "virtual_origami/numerics/spd_factorization.h"
#include "virtual_origami/curved/surroundings.h"

namespace virtual_origami::core
{
/// A node held at a position (a corner pulled by the hand, a fixed corner).
struct CurvedPin
{
  int node = -1;
  Vec3 position = Vec3::Zero();
};

enum class CurvedMethod
{
  Newton,  // static equilibrium directly
  Rk4,     // the seed: damped motion until it comes to rest
  /// Static equilibrium by L-BFGS (Liu, Bouaziz & Kavan 2017) whose initial inverse Hessian is
  /// one constant matrix: the terms' Hessian at the shape of the first solve with these pins
  /// (the flat or rigidly folded sheet: stretch and shear as springs, bending as at rest),
  /// factorised once and kept while the mesh and the pinned nodes stay, each node's block
  /// turned with the node's frame (stiffness warping: stiff along the sheet, soft across it,
  /// wherever the sheet has turned). A line search on the true energy (contact and
  /// surroundings included); the same balance test as Newton.
  QuasiNewton,
};

struct CurvedSolveOptions
{
  CurvedMethod method = CurvedMethod::Newton;
  /// Balanced when no free node feels more than tolerance × stretch × spacing: the force of
  /// one edge strained by `tolerance`.
  double tolerance = 1e-8;
  int max_iterations = 500;  // Newton iterations
  int max_steps = 200000;    // RK4 steps
  double max_seconds = 0.0;  // wall-time budget; 0: none
  /// Newton: Levenberg–Marquardt damping μ = damping·|∇E| / spacing; a step moves no node
  /// farther than max_step × the contact range, so contact sees every approach.
  double damping = 1e-2;
  double max_step = 0.4;
  /// Newton keeps stepping with an earlier factorisation (no new Hessian) while each step
  /// cuts the largest force by at least this factor; 0: a fresh Hessian every iteration.
  double modified_newton_rate = 0.5;
  /// Newton: conjugate-gradient iterations for the exact Hessian's step, preconditioned by
  /// the kept factorisation, before factorising anew.
  int krylov_iterations = 12;
  /// Newton: when the pins move on along the path of the last balanced solves, start from
  /// the shape carried on along its path; false: start from the given shape.
  bool predict = true;
  /// Newton: a balance reached where the Hessian showed negative curvature (a factorisation
  /// of it failed at a shift that is not rounding) is tested for a direction that lowers the
  /// energy, and left along it: paper at a saddle buckles or snaps, it does not stay there.
  bool leave_saddles = true;
  /// Newton, with leave_saddles: every balance is also tested directly, by a factorisation of
  /// the Hessian there shifted by the curvature counted as rounding, and left when that fails.
  /// Without the test a drag can stay on a branch for many pulls after it has lost stability
  /// (no factorisation fails while the kept one serves); with it, the sheet snaps within a
  /// pull or two. Costs a factorisation per solve, which on meshes of thousands of vertices
  /// about doubles a drag's solves; the factorisation then serves the next solve.
  bool check_stability = false;
  /// QuasiNewton: correction pairs kept by L-BFGS, and its iterations before the solve hands
  /// over to Newton (the snaps of a drag, where the constant matrix no longer resembles the
  /// Hessian); without hand_over the solve stops there unconverged.
  int lbfgs_memory = 8;
  int lbfgs_iterations = 200;
  bool hand_over = true;
  /// QuasiNewton: turn the constant matrix with each node's frame (stiffness warping); false:
  /// the matrix as made, stiff only along the sheet's first shape.
  bool warp = true;
  /// QuasiNewton: the constant matrix carries a membrane prestress of this strain (the
  /// out-of-plane stiffness of a sheet under tension, which the rest state lacks), as a share
  /// of each edge's stretch weight on its graph Laplacian. 1e-4, the strain of a curl: on the
  /// 10,000-vertex drag of curved_speed_bench 1.7 solves per CPU second, against 0.95 at 1e-5
  /// and 0.75 without (docs/CURVED.md).
  double lbfgs_prestress = 1e-4;
  /// QuasiNewton: instead of L-BFGS, Newton–Krylov: conjugate gradients on the exact Hessian
  /// (assembled each iteration), the turned constant matrix as their preconditioner, at most
  /// this many iterations per step; 0: L-BFGS.
  int constant_krylov_iterations = 0;
  /// RK4: the step (0: half the stability limit of the stiffest mode) and the
  /// mass-proportional damping rate (0: twice the first bending mode's frequency).
  double time_step = 0.0;
  double viscosity = 0.0;
};

struct CurvedReport
{
  bool converged = false;
  bool diverged = false;   // non-finite or exploding: the positions were rolled back
  bool refused = false;    // a pin off the sheet or not finite, or positions of another mesh: x untouched
  int iterations = 0;      // Newton or quasi-Newton iterations, or RK4 steps
  int factorizations = 0;  // Newton: sparse Cholesky factorisations (the rest reused one)
  int krylov_steps = 0;    // Newton: exact Hessian steps by preconditioned conjugate gradients
  int lbfgs_steps = 0;     // QuasiNewton: its own iterations (L-BFGS or Newton–Krylov); after a hand-over
                           // Newton's are in `iterations` too
  bool handed_over = false;  // QuasiNewton: L-BFGS did not balance within its iterations; Newton finished
  double max_force = 0.0;  // largest force on a free node, / (stretch × spacing)
  CurvedEnergy energy;
  double contact_energy = 0.0;
  int contacts = 0;        // watched node–triangle pairs at the end
  bool predicted = false;  // Newton started from the shape carried on along the drag
  int saddles_left = 0;    // Newton: balances that were saddles, left along negative curvature
  double time_step = 0.0;  // RK4
  double seconds = 0.0;
  std::string message;
};

/// The rigid motions of the free nodes that leave every pinned node where it is and the energy
/// as it is (all six for a floating sheet; with weight or a table, `in_plane_only`: those in the
/// table's plane), as orthonormal columns over the free coordinates at `x`. No force resists
/// them: a step's part along them is rounding over the damping.
Eigen::MatrixXd freeRigidMotions(const Positions& x, const std::vector<int>& free_index, int free_count,
                                 bool in_plane_only);

class CurvedSolver
{
public:
  /// `mesh` and `paper` must outlive the solver.
  CurvedSolver(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material = {},
               const ContactOptions& contact = {}, const CurvedSolveOptions& options = {},
               const Surroundings& surroundings = {});

  /// Moves the free nodes of `x` (one column per mesh node) to balance, with the pinned nodes
  /// set to their positions first. Contact sides persist from one solve to the next, so a
  /// drag solved in small steps keeps every layer on its side; a pin must not jump through a
  /// layer between two solves (move it less than a mesh spacing at a time near other layers).
  /// On divergence `x` is left as it was given (pins applied) and the report says so. A pin of a
  /// node the mesh does not have, or at a point that is not finite, is refused (`refused`, with
  /// a message) and `x` left untouched.
  CurvedReport solve(Positions& x, const std::vector<CurvedPin>& pins);

  const CurvedTerms& terms() const
  {
    return terms_;
  }
  const LayerContact& contact() const
  {
    return contact_;
  }
  CurvedSolveOptions& options()
  {
    return options_;
  }

  /// Every term at rest in the shape `x` (restTermsAt): a layered start rests as drawn.
  void restTermsAt(const Positions& x);

  /// Largest force on a free node over (stretch × spacing), contact included.
  double maxForce(const Positions& x, const std::vector<CurvedPin>& pins);

private:
  /// Carries `x` (the last balance) on along the path of the last two solves, when the pins
  /// continue it; false when they do not (x untouched).
  bool predict(Positions& x, const std::vector<CurvedPin>& pins, const std::vector<int>& free_index, int free_count);
  /// Weight or a table: only motions in the table's plane leave the energy as it is.
  bool inPlaneOnly() const
  {
    return surroundings_.gravity != 0 || surroundings_.table;
  }
  CurvedReport newton(Positions& x, const std::vector<int>& free_index, int free_count);
  /// Newton's last resort: the exact Hessian (hessian_, gradient g) factorised with the damping
  /// `shift`, raised a hundredfold per try until it is positive definite and its step, taken by
  /// `search` (Armijo, up to 30 halvings), lowers the energy; that factorisation is kept.
  /// Returns the step length taken (0: none in 30 tries), `shift` the last one tried.
  double factorisedStep(const Eigen::VectorXd& g, const std::vector<int>& free_index,
                        const std::function<double(Eigen::VectorXd&, int)>& search, double& shift,
                        CurvedReport& report);
  /// The step of hessian_ + μI against gradient g by conjugate gradients preconditioned by the
  /// kept factorisation, orthogonal to `free_motions`, in at most `max_iterations`. Returns
  /// the factor by which the linear model cuts the largest force (1 at negative curvature, 0
  /// on failure); with `negative`, runs every iteration and gives the direction of negative
  /// curvature it stopped at.
  double conjugateGradients(const Eigen::VectorXd& g, double mu, const Eigen::MatrixXd& free_motions,
                            int max_iterations, Eigen::VectorXd& step, int* iterations,
                            Eigen::VectorXd* negative = nullptr,
                            const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>* precondition = nullptr) const;
  /// At a balance `x`: a direction of negative curvature of the Hessian there (conjugate
  /// gradients from a random start, the kept factorisation as preconditioner), and a move
  /// along it that lowers the energy. False, `x` untouched, when none is found.
  /// With `with_constant`, the turned constant matrix of QuasiNewton preconditions the search.
  bool leaveSaddle(Positions& x, const std::vector<int>& free_index, int free_count, bool with_constant = false);
  /// Each node's turn (3 × 3) from its frame where the constant matrix was made to its frame at
  /// x; empty without warp.
  std::vector<Eigen::Matrix3d> constantTurns(const Positions& x) const;
  /// The turned constant matrix's inverse applied to v (one back-substitution).
  Eigen::VectorXd constantInverse(const Eigen::VectorXd& v, const std::vector<Eigen::Matrix3d>& turns,
                                  const std::vector<int>& free_index) const;
  /// Whether the Hessian at balance `x`, shifted by the curvature counted as rounding, fails
  /// to factorise (negative curvature: a saddle to leave). On success the factorisation is
  /// kept for the next solve.
  bool unstableAt(const Positions& x, const std::vector<int>& free_index, int free_count);
  /// L-BFGS on the constant matrix (see CurvedMethod::QuasiNewton), then Newton if it stalls.
  CurvedReport quasiNewton(Positions& x, const std::vector<int>& free_index, int free_count);
  /// Factorises the constant matrix for these free nodes at shape `x` unless it is kept; false
  /// when no shift makes it positive definite.
  bool prepareConstantFactor(const Positions& x, const std::vector<int>& free_index, int free_count);
  CurvedReport rk4(Positions& x, const std::vector<int>& free_index, int free_count);
  /// Energy, gradient (into g) and Hessian (into hessian_) at x.
  double assembleHessian(const Positions& x, const std::vector<int>& free_index, int free_count, Eigen::VectorXd& g,
                         CurvedEnergy* parts = nullptr, double* contact = nullptr);
  /// Armijo's line search from x (energy e, gradient g) along `step`, first cut to move no node
  /// farther than max_move; at most `tries` halvings, none letting a watched pair cross over
  /// by more than half the thickness (worst_gap: the closest they are at x); where the
  /// energy's change is below its rounding, the slope at the trial decides. Leaves the point
  /// reached in `trial` and returns the step length taken, 0 when none lowers the energy.
  double lineSearch(const Positions& x, double e, const Eigen::VectorXd& g, Eigen::VectorXd& step, int tries,
                    double max_move, double worst_gap, const std::vector<int>& free_index, Positions& trial,
                    Eigen::VectorXd& trial_gradient) const;
  double energy(const Positions& x, const Assembly& out, CurvedEnergy* parts = nullptr,
                double* contact = nullptr) const;

  const CurvedMesh& mesh_;
  CurvedMaterial material_;
  CurvedTerms terms_;
  LayerContact contact_;
  /// With ContactOptions::barrier, the contact in place of contact_ (which then watches nothing).
  std::unique_ptr<BarrierContact> barrier_;
  bool barrier_started_ = false;  // the pairs near at the first solve's start are guarded
  /// Finds the pairs contact watches at x (the barrier's: those within its activation distance;
  /// lineSearch adds those a step sweeps near).
  void updateContact(const Positions& x);
  CurvedSolveOptions options_;
  Surroundings surroundings_;
  // Newton's Hessian and factorisation, kept across solves, and the free nodes it is for.
  Eigen::SparseMatrix<double> hessian_;
  numerics::SpdFactorization factorization_;
  std::vector<int> factor_free_;
  double damping_mu_ = -1.0;       // Newton's Levenberg–Marquardt shift where the last solve left it
  double factor_shift_ = 0.0;      // the shift of the kept factorisation
  bool renew_factorization_ = false;  // conjugate gradients needed many iterations with it
  bool stale_steps_help_ = true;      // its own step was a full one when last tried
  bool negative_curvature_ = false;   // the last Newton solve met it (see leave_saddles)
  unsigned saddle_seed_ = 1;          // the random starts of leaveSaddle, reproducible
  // QuasiNewton's constant matrix, factorised, and the free nodes it is for.
  numerics::SpdFactorization constant_factor_;
  std::vector<int> constant_free_;
  std::vector<Eigen::Matrix3d> constant_frames_;  // each node's frame where the matrix was made
  std::vector<int> frame_partner_;                // the neighbour whose edge sets a node's frame
  /// Each node's frame at x: its normal (the area-weighted one of its triangles) and the
  /// direction to frame_partner_ in its tangent plane, as the columns (tangent, bitangent, normal).
  std::vector<Eigen::Matrix3d> nodeFrames(const Positions& x) const;
  std::vector<int> pattern_free_;  // the free nodes hessian_'s pattern is for
  std::vector<std::array<int, 4>> pattern_groups_;
  /// The last three balanced shapes and their pins, oldest first.
  struct Balance
  {
    Positions x;
    std::vector<CurvedPin> pins;
  };
  std::vector<Balance> path_;
};

}  // namespace virtual_origami::core
