#include "virtual_origami/solvers/quasi_newton_driver.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/CholmodSupport>

#include "virtual_origami/core/face_springs.h"
#include "virtual_origami/core/positions.h"
#include "virtual_origami/numerics/spd_factorization.h"
#include "virtual_origami/solvers/driven_faces.h"
#include "virtual_origami/numerics/lbfgs_history.h"
#include "virtual_origami/numerics/solve_budget.h"

namespace virtual_origami::core
{
namespace
{
// CHOLMOD's supernodal factor (its own choice of ordering): against Eigen's simplicial one with
// AMD, half the set-up and less than half the back-substitution on a 10,000-vertex pattern.
using Factor = Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>;

/// Free vertices' coordinates as one matrix, a row per free vertex (the layout of the solves).
Eigen::MatrixX3d gather(const Positions& x, const std::vector<int>& free_vertices)
{
  Eigen::MatrixX3d out(free_vertices.size(), 3);
  for (size_t i = 0; i < free_vertices.size(); ++i)
    out.row(static_cast<Eigen::Index>(i)) = x.col(free_vertices[i]).transpose();
  return out;
}

/// The six rigid motions of the sheet at x over the free vertices (every vertex free), made
/// orthonormal once per state: the energy does not see them, so without an anchor they are
/// only rounding noise the shift of the matrix would blow up into a drift, and every step is
/// cleared of them.
class RigidMotions
{
public:
  RigidMotions(const Positions& x, const std::vector<int>& free)
  {
    const Eigen::Index n = static_cast<Eigen::Index>(free.size());
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (int v : free)
      centre += x.col(v);
    centre /= static_cast<double>(n);
    for (int axis = 0; axis < 6; ++axis)
    {
      Eigen::MatrixX3d b(n, 3);
      for (Eigen::Index i = 0; i < n; ++i)
      {
        const Eigen::Vector3d unit = Eigen::Vector3d::Unit(axis % 3);
        b.row(i) = (axis < 3 ? unit : unit.cross(x.col(free[i]) - centre)).transpose();
      }
      for (const Eigen::MatrixX3d& c : basis_)
        b -= numerics::innerProduct(c, b) * c;
      const double norm = std::sqrt(numerics::innerProduct(b, b));
      if (norm > 1e-12)
        basis_.push_back(b / norm);
    }
  }

  void remove(Eigen::MatrixX3d& step) const
  {
    for (const Eigen::MatrixX3d& c : basis_)
      step -= numerics::innerProduct(c, step) * c;
  }

private:
  std::vector<Eigen::MatrixX3d> basis_;
};

bool driven(double target)
{
  return std::isfinite(target);
}
}  // namespace

struct QuasiNewtonDriver::AssemblyPlan
{
  std::mutex mutex;
  std::vector<std::pair<int, int>> entries;  // the (row, column) of each entry it was made for
  std::vector<int> slots;
  Eigen::SparseMatrix<double> pattern;  // compressed

  bool matches(const std::vector<Eigen::Triplet<double>>& triplets) const
  {
    if (triplets.size() != entries.size())
      return false;
    for (size_t k = 0; k < triplets.size(); ++k)
      if (triplets[k].row() != entries[k].first || triplets[k].col() != entries[k].second)
        return false;
    return true;
  }
};

/// What stays while the pattern, the held vertices and the set of driven creases stay: the
/// energy's faces and hinges, and the factorised constant matrix. Also the last frames, for
/// the prediction.
struct QuasiNewtonDriver::Setup
{
  std::vector<std::vector<int>> face_vertices;
  std::vector<Vec2> crease_pattern;
  std::vector<char> fixed;
  std::vector<char> driven_edges;
  std::vector<Spring> springs;  // the faces' vertex pairs, for the strain reported
  DrivenFaces energy;
  std::vector<int> free_index, free_vertices;
  Eigen::SparseMatrix<double> constant_matrix;  // until it is factorised
  Factor factor;  // the constant matrix
  bool constant_tried = false, factored = false;
  int free_count = 0;
  numerics::SpdFactorization gauss_newton;  // the lagged or exact matrix, 3 rows per free vertex
  // Each face's fitted frame where gauss_newton was factorised (Lagged: how far they turned since).
  std::vector<Eigen::Matrix<double, 3, 2>> factor_frames;
  Eigen::SparseMatrix<double> gauss_newton_matrix;
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<int> slots;  // where each of the triplets lands among the matrix's values
  double factor_seconds = 0.0;  // wall time the last factorisation took
  double restore_seconds = 0.0;  // wall time the last restoring step took
  double evaluate_seconds = 0.0;  // wall time the last energy pass of a line search took
  // The last two frames this driver returned (as in the paper) and their targets, and where
  // the last one started.
  Positions last, before_last, last_start;
  std::vector<double> last_target, before_last_target;
  bool last_balanced = true;  // whether the last frame reached balance within its budget
  bool last_continued = false;  // the last frame went on from the one before it
  double last_face_energy = 0.0;  // the face term of the energy at the last frame

  Setup(const Paper& paper, const std::vector<char>& held, const std::vector<double>& target, double stiffness,
        std::shared_ptr<numerics::SpdFactorization::SharedAnalysis> analysis)
    : crease_pattern(creasePattern(paper)), fixed(held), driven_edges(drivenEdges(paper, target)),
      springs(faceSprings(paper)), energy(paper, stiffness)
  {
    gauss_newton.shareAnalysis(std::move(analysis));
    for (const Face& face : paper.faces)
      face_vertices.push_back(face.vertices);
    free_index = freeIndices(fixed, paper.vertices.size(), &free_count);
    for (size_t v = 0; v < free_index.size(); ++v)
      if (free_index[v] >= 0)
        free_vertices.push_back(static_cast<int>(v));
    energy.setTargets(target);
    constant_matrix = energy.constantMatrix(free_index, free_count);
    // Nothing held: the energy has the rigid motions as null space. A shift far below the
    // faces' stiffness makes the matrix definite without steering the steps.
    const bool anchored = std::any_of(fixed.begin(), fixed.end(), [](char c) { return c != 0; });
    double shift = 0.0;
    for (int k = 0; k < constant_matrix.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(constant_matrix, k); it; ++it)
        if (it.row() == it.col())
          shift = std::max(shift, it.value());
    shift *= anchored ? 1e-12 : 1e-8;
    for (int i = 0; i < free_count; ++i)
      constant_matrix.coeffRef(i, i) += shift;
  }

  /// The constant matrix factorised at its first use: a commit or a turn whose steps are all
  /// taken whole needs none (its analysis and factorisation are 30 ms on 10,000 vertices).
  bool factorConstant()
  {
    if (!constant_tried)
    {
      constant_tried = true;
      factor.cholmod().print = 0;  // not definite is answered by the callers, not printed
      {
        const std::unique_lock<std::mutex> blas = numerics::lockBlas();
        factor.compute(constant_matrix);
      }
      factored = factor.info() == Eigen::Success;
      constant_matrix = Eigen::SparseMatrix<double>();
    }
    return factored;
  }

  /// The constant matrix's solve; zero where it is not definite (no step from it).
  Eigen::MatrixX3d solveConstant(const Eigen::MatrixX3d& rhs)
  {
    if (!factorConstant())
      return Eigen::MatrixX3d::Zero(rhs.rows(), 3);
    const std::unique_lock<std::mutex> blas = numerics::lockBlas();
    return factor.solve(rhs);
  }

  bool matches(const Paper& paper, const std::vector<char>& held, const std::vector<double>& target) const
  {
    if (held != fixed || paper.faces.size() != face_vertices.size() || creasePattern(paper) != crease_pattern ||
        drivenEdges(paper, target) != driven_edges)
      return false;
    for (size_t f = 0; f < paper.faces.size(); ++f)
      if (paper.faces[f].vertices != face_vertices[f])
        return false;
    return true;
  }

  static std::vector<Vec2> creasePattern(const Paper& paper)
  {
    std::vector<Vec2> c;
    c.reserve(paper.vertices.size());
    for (const Vertex& v : paper.vertices)
      c.push_back(v.crease_pattern);
    return c;
  }

  static std::vector<char> drivenEdges(const Paper& paper, const std::vector<double>& target)
  {
    std::vector<char> out(paper.edges.size(), 0);
    for (size_t e = 0; e < out.size() && e < target.size(); ++e)
      out[e] = driven(target[e]) ? 1 : 0;
    return out;
  }
};

QuasiNewtonDriver::QuasiNewtonDriver(QuasiNewtonOptions options)
  : options_(options), analysis_(numerics::SpdFactorization::makeSharedAnalysis()), assembly_(std::make_shared<AssemblyPlan>())
{
  face_stiffness_ = options.face_stiffness;
  limits_.tolerance = 1e-9;
  limits_.max_iterations = 2000;
}

QuasiNewtonDriver::~QuasiNewtonDriver() = default;

std::string QuasiNewtonDriver::name() const
{
  switch (options_.hessian)
  {
    case DriverHessian::Constant:
      return "constant_lbfgs";
    case DriverHessian::Exact:
      return "newton";
    default:
      return "quasi_newton";
  }
}

std::unique_ptr<CreaseDriver> QuasiNewtonDriver::clone() const
{
  auto copy = std::make_unique<QuasiNewtonDriver>(options_);
  copy->analysis_ = analysis_;
  copy->assembly_ = assembly_;
  copy->setLimits(limits_);
  copy->setFaceStiffness(face_stiffness_);
  return copy;
}

SolveReport QuasiNewtonDriver::drive(Paper& paper, const std::vector<double>& target, const std::vector<char>& fixed)
{
  const std::lock_guard<std::mutex> lock(mutex_);
  numerics::SolveBudget budget(limits_);
  SolveReport report;
  if (!setup_ || !setup_->matches(paper, fixed, target) || setup_->energy.faceStiffness() != face_stiffness_)
    setup_ = std::make_unique<Setup>(paper, fixed, target, face_stiffness_, analysis_);
  Setup& s = *setup_;
  DrivenFaces& energy = s.energy;
  energy.setTargets(target);
  std::vector<double> reference(paper.edges.size());
  for (size_t e = 0; e < paper.edges.size(); ++e)
    reference[e] = paper.edges[e].fold_angle;
  energy.setReference(reference);

  const Positions start = foldedPositions(paper);
  const double scale = energy.scale();
  Positions x = start / scale;
  const std::vector<Spring>& springs = s.springs;
  const bool constant_unfactored = !s.constant_tried;
  const bool constant_refused =
      !s.free_vertices.empty() && options_.hessian == DriverHessian::Constant && !s.factorConstant();
  report.factorizations += constant_unfactored && s.constant_tried ? 1 : 0;
  if (s.free_vertices.empty() || constant_refused)
  {
    report.max_strain = springStrain(springs, start).max;
    report.converged = s.free_vertices.empty();
    report.message = s.free_vertices.empty() ? "every vertex is held" : "the constant matrix is not definite";
    report.seconds = budget.seconds();
    return report;
  }

  const std::vector<int>& free = s.free_vertices;
  const bool anchored = std::any_of(fixed.begin(), fixed.end(), [](char c) { return c != 0; });
  // Start from a prediction along the motion when this is the frame after the last two (the
  // last went on from the one before it: a new slide's second frame has no motion to go by).
  const bool continues = s.last.cols() == x.cols() && s.last == start;
  // A frame whose budget cannot pay for a factorisation of the Gauss–Newton matrix, going on
  // from the last frame along its motion: its steps come from the subspace of that motion and
  // the constant matrix's conjugate directions (subspaceStep below), no factorisation used.
  const bool motion_known = s.last_start.cols() == x.cols() && s.last_start != s.last;
  const bool subspace_frame = options_.hessian == DriverHessian::Lagged && options_.subspace_frames &&
                              (motion_known || s.gauss_newton.valid()) && limits_.max_seconds > 0 &&
                              limits_.max_seconds < options_.subspace_below_seconds;
  const bool predicts = options_.predict && !subspace_frame && continues &&
                        s.last_continued && s.before_last.cols() == x.cols() && s.last_target.size() == target.size();
  // The energy where the frame starts: a prediction needs only its value, whose face term is
  // the last frame's (the same positions); the full pass (with the gradient) is paid for only
  // where the frame goes on from there.
  Positions gradient;
  DrivenFaces::Evaluation now;
  bool start_evaluated = false;
  // What an energy pass and a back-substitution cost here: a frame's budget is spent only on
  // work that ends within it (the last step's line search and the report come after).
  double evaluate_seconds = 0.0;
  // A subspace frame linearises where it starts in the same pass (the faces' fits shared).
  DrivenFaces::Linearization start_linearization;
  bool start_linearized = false;
  const auto evaluateStart = [&]() {
    const double evaluate_from = budget.seconds();
    now = energy.evaluate(x, &gradient, subspace_frame ? &start_linearization : nullptr);
    start_linearized = subspace_frame;
    evaluate_seconds = budget.seconds() - evaluate_from;
    // The line search's passes do not linearise: budget them as the last plain pass took.
    if (subspace_frame && s.evaluate_seconds > 0)
      evaluate_seconds = s.evaluate_seconds;
    start_evaluated = true;
  };
  if (predicts)
  {
    now.face_energy = s.last_face_energy;
    now.hinge_energy = energy.hingeEnergy(x);
    now.energy = now.face_energy + now.hinge_energy;
  }
  else
    evaluateStart();
  double solve_seconds = 0.0;
  // A frame stopped by its budget ends with a restoring step (restore_final_faces): kept room.
  double final_reserve = 0.0;
  const auto fits = [&](double work) {
    return limits_.max_seconds <= 0 ||
           budget.seconds() + work + 2 * evaluate_seconds + final_reserve < limits_.max_seconds;
  };
  // The last frame's own motion, where this frame goes on from it: the direction a mechanism
  // is turning in (see followMotion below).
  Eigen::MatrixX3d motion;
  // A subspace frame that starts a slide goes by the last motion this driver made elsewhere on
  // the pattern: the mechanism turns much the same way there, and the Galerkin step says how far.
  if ((continues || subspace_frame) && s.last_start.cols() == x.cols())
    motion = gather(s.last - s.last_start, free) / scale;
  // A subspace frame's rigid motions, made once where it starts (they only keep the steps from
  // drifting the floating sheet: a frame's small motion does not change them measurably).
  std::optional<RigidMotions> frame_rigid;
  // The constant matrix's solve, counted (and its factorisation, where this frame makes it).
  const auto solveConstant = [&](const Eigen::MatrixX3d& rhs) {
    const bool unfactored = !s.constant_tried;
    Eigen::MatrixX3d solved = s.solveConstant(rhs);
    report.factorizations += unfactored ? 1 : 0;
    report.back_substitutions += s.factored ? 1 : 0;
    return solved;
  };
  // One step of the constant matrix from `at` (rotations fitted, the faces' shapes restored),
  // taken where it lowers the energy: what a linear step along turning faces stretched, taken
  // out for about one back-substitution.
  const auto restoreFaces = [&](Positions& at, Positions& at_gradient, DrivenFaces::Evaluation& at_energy) {
    const numerics::SolveBudget clock(SolveLimits{});
    Eigen::MatrixX3d restore = -solveConstant(gather(at_gradient, free));
    if (frame_rigid)
      frame_rigid->remove(restore);
    else if (!anchored)
      RigidMotions(at, free).remove(restore);
    for (double length = 1.0; length >= 0.25; length *= 0.5)
    {
      Positions restored = at, restored_gradient;
      for (size_t i = 0; i < free.size(); ++i)
        restored.col(free[i]) += length * restore.row(static_cast<Eigen::Index>(i)).transpose();
      const DrivenFaces::Evaluation better = energy.evaluate(restored, &restored_gradient);
      if (better.energy < at_energy.energy)
      {
        at = std::move(restored);
        at_gradient = std::move(restored_gradient);
        at_energy = better;
        break;
      }
    }
    s.restore_seconds = clock.seconds();
  };
  if (predicts)
  {
    double step_now = 0.0, step_before = 0.0;
    for (size_t e = 0; e < target.size(); ++e)
      if (driven(target[e]) && driven(s.last_target[e]) && driven(s.before_last_target[e]))
      {
        step_now += std::pow(target[e] - s.last_target[e], 2);
        step_before += std::pow(s.last_target[e] - s.before_last_target[e], 2);
      }
    if (step_before > 0)
    {
      const double ratio = std::min(2.0, std::sqrt(step_now / step_before));
      Positions predicted = x + (ratio / scale) * (s.last - s.before_last);
      for (size_t v = 0; v < s.free_index.size(); ++v)
        if (s.free_index[v] < 0)
          predicted.col(static_cast<Eigen::Index>(v)) = x.col(static_cast<Eigen::Index>(v));
      Positions predicted_gradient;
      const double evaluate_from = budget.seconds();
      DrivenFaces::Evaluation guess = energy.evaluate(predicted, &predicted_gradient);
      evaluate_seconds = budget.seconds() - evaluate_from;
      // Carried on straight, every turning face stretches by about half its turn squared (a
      // 1 % step of a Miura-ori: 5e-4). Where that costs more than the step gains (a large
      // sheet), or where the last frame ran out of budget before balance (a slide's frames: the
      // strain they keep would pile up), one step of the constant matrix (rotations fitted, the
      // faces' shapes restored) takes it out for about one back-substitution. Not otherwise: a
      // frame solved to balance starts better from the straight prediction.
      if (options_.restore_predicted_faces && (!(guess.energy < now.energy) || !s.last_balanced))
        restoreFaces(predicted, predicted_gradient, guess);
      if (guess.energy < now.energy)
      {
        x = std::move(predicted);
        gradient = std::move(predicted_gradient);
        now = guess;
        start_evaluated = true;
      }
    }
  }
  if (!start_evaluated)
    evaluateStart();

  // The Gauss–Newton matrix at x; nothing held, its null space (rigid motions) is shifted away
  // by far less than the faces' stiffness, and a failed factorisation (a degenerate face) is
  // retried with more.
  const auto refactor = [&]() {
    const numerics::SolveBudget clock(SolveLimits{});
    const auto timed = [&](bool ok) {
      s.factor_seconds = clock.seconds();
      return ok;
    };
    energy.gaussNewtonTriplets(x, s.free_index, s.triplets);
    Eigen::SparseMatrix<double>& m = s.gauss_newton_matrix;
    if (s.slots.size() != s.triplets.size())
    {
      AssemblyPlan& plan = *assembly_;
      const std::lock_guard<std::mutex> planning(plan.mutex);
      if (!plan.matches(s.triplets))
      {
        plan.pattern.resize(3 * s.free_count, 3 * s.free_count);
        plan.pattern.setFromTriplets(s.triplets.begin(), s.triplets.end());
        plan.pattern.makeCompressed();
        plan.slots.resize(s.triplets.size());
        plan.entries.resize(s.triplets.size());
        const int* rows = plan.pattern.innerIndexPtr();
        for (size_t k = 0; k < s.triplets.size(); ++k)
        {
          const int begin = plan.pattern.outerIndexPtr()[s.triplets[k].col()];
          const int end = plan.pattern.outerIndexPtr()[s.triplets[k].col() + 1];
          plan.slots[k] = static_cast<int>(std::lower_bound(rows + begin, rows + end, s.triplets[k].row()) - rows);
          plan.entries[k] = { s.triplets[k].row(), s.triplets[k].col() };
        }
      }
      m = plan.pattern;
      s.slots = plan.slots;
    }
    double* values = m.valuePtr();
    std::fill(values, values + m.nonZeros(), 0.0);
    for (size_t k = 0; k < s.triplets.size(); ++k)
      values[s.slots[k]] += s.triplets[k].value();
    double largest = 0.0;
    for (int k = 0; k < m.outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(m, k); it; ++it)
        if (it.row() == it.col())
          largest = std::max(largest, it.value());
    for (double shift = largest * (anchored ? 1e-12 : 1e-9); shift <= largest; shift *= 100)
    {
      ++report.factorizations;
      if (s.gauss_newton.factorize(m, shift))
        return timed(true);
    }
    return timed(false);
  };
  const auto precondition = [&](const Eigen::MatrixX3d& q) -> Eigen::MatrixX3d {
    if (options_.hessian == DriverHessian::Constant || !s.gauss_newton.valid())
      return solveConstant(q);
    ++report.back_substitutions;
    const Eigen::MatrixX3d qt = q;  // row per vertex: flattened row-major it is 3i + axis
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> rows = qt;
    const Eigen::VectorXd solved =
        s.gauss_newton.solve(Eigen::Map<const Eigen::VectorXd>(rows.data(), rows.size()));
    return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(solved.data(), rows.rows(), 3);
  };
  bool refresh = !subspace_frame && options_.hessian != DriverHessian::Constant &&
                 (options_.hessian == DriverHessian::Exact || !s.gauss_newton.valid());

  Eigen::MatrixX3d g = gather(gradient, free);
  numerics::LbfgsHistory<Eigen::MatrixX3d> history(options_.memory);
  // A fresh factorisation; the curvature pairs gathered against the old one go with it.
  const auto refactorAfresh = [&]() {
    if (refactor())
      history.clear();
  };
  // L-BFGS: the two-loop recursion with the factorised matrix's inverse as the initial Hessian.
  const auto lbfgsStep = [&]() -> Eigen::MatrixX3d { return -history.apply(g, precondition); };
  // Newton–Krylov: the Gauss–Newton system at x solved by conjugate gradients, preconditioned
  // by the kept factorisation (the matrix of a nearby state, so a few iterations do).
  bool krylov_slow = false;
  bool krylov_cut = false;  // the budget ended the last step's conjugate gradients
  Positions spread = Positions::Zero(3, x.cols()), product;
  // Newton–Krylov steps multiply by the energy's own Hessian (exact_hessian) once the steps
  // converge (two whole steps in a row, neither shortened nor restored, the second less than
  // half the first). Far from a balance it is indefinite, and near-singular along a mechanism
  // starting to turn, where Gauss–Newton's convex model takes the better steps (a turn from the
  // flat sheet). A step it gives that is not taken whole hands back to Gauss–Newton for the
  // rest of the frame. Subspace frames multiply by the Gauss–Newton matrix (their Galerkin
  // model must be convex).
  bool exact_products = false, exact_refused = false, last_whole = false;
  const bool exact_allowed = options_.exact_hessian && !subspace_frame;
  const auto multiply = [&](const DrivenFaces::Linearization& l, const Eigen::MatrixX3d& v) {
    for (size_t i = 0; i < free.size(); ++i)
      spread.col(free[i]) = v.row(static_cast<Eigen::Index>(i)).transpose();
    if (exact_products)
      energy.hessianProduct(l, spread, product);
    else
      energy.gaussNewtonProduct(l, spread, product);
    return gather(product, free);
  };
  Eigen::MatrixX3d step_product;  // H times the step newtonKrylovStep returned
  const auto newtonKrylovStep = [&](const DrivenFaces::Linearization& l, const RigidMotions* rigid) -> Eigen::MatrixX3d {
    Eigen::MatrixX3d r = -g;
    if (rigid)
      rigid->remove(r);
    Eigen::MatrixX3d d = Eigen::MatrixX3d::Zero(r.rows(), 3);
    step_product = Eigen::MatrixX3d::Zero(r.rows(), 3);
    const double solve_from = budget.seconds();
    Eigen::MatrixX3d z = precondition(r);
    solve_seconds = budget.seconds() - solve_from;
    if (rigid)
      rigid->remove(z);
    Eigen::MatrixX3d p = z;
    const Eigen::MatrixX3d first = z;
    double rz = numerics::innerProduct(r, z);
    const double goal = options_.krylov_tolerance * std::sqrt(numerics::innerProduct(r, r));
    krylov_slow = true;
    krylov_cut = false;
    for (int k = 0; k < options_.krylov_iterations; ++k)
    {
      const Eigen::MatrixX3d ap = multiply(l, p);
      const double curvature = numerics::innerProduct(p, ap);
      if (!(curvature > 0))
      {
        // The Hessian is not positive along p (away from a stable balance): the steps so far
        // descend; with none yet, the kept matrix's own step does.
        if (k == 0)
        {
          d = p;
          step_product = ap;
        }
        break;
      }
      const double a = rz / curvature;
      d += a * p;
      step_product += a * ap;
      r -= a * ap;
      if (std::sqrt(numerics::innerProduct(r, r)) <= goal)
      {
        krylov_slow = k + 1 > options_.krylov_iterations / 2;
        break;
      }
      // Anytime: a frame's budget spent, the step so far serves (each iteration improves it).
      if (!fits(solve_seconds))
      {
        krylov_cut = true;
        break;
      }
      z = precondition(r);
      if (rigid)
        rigid->remove(z);
      const double rz_next = numerics::innerProduct(r, z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
    }
    // A trust region for the exact Hessian: a step ten times the kept matrix's own says
    // the Hessian is near singular here (a mechanism starting to turn): the kept matrix's step
    // serves, and Gauss–Newton the rest of the frame.
    if (exact_products && d.cwiseAbs().maxCoeff() > 10.0 * first.cwiseAbs().maxCoeff())
    {
      exact_products = false;
      exact_refused = true;
      d = first;
      step_product = multiply(l, d);
    }
    return d;
  };
  // The Newton–Krylov step d and the last frame's motion m as one Galerkin step over both: the
  // step a·d + b·m that the Gauss–Newton model at x prefers. A matrix kept from another state
  // calls a mechanism's present turn stiff, so its steps fall ever further behind the balance
  // along the turn (a slide's frames lag, then snap back through stretched faces); the motion
  // is that turn, and the model says how far along it to go, for one product more.
  const auto followMotion = [&](const DrivenFaces::Linearization& l, const RigidMotions* rigid,
                                Eigen::MatrixX3d& direction) {
    Eigen::MatrixX3d m = motion;
    if (rigid)
      rigid->remove(m);
    const Eigen::MatrixX3d hm = multiply(l, m);
    Eigen::Matrix2d model;
    model << numerics::innerProduct(direction, step_product), numerics::innerProduct(direction, hm), numerics::innerProduct(m, step_product),
        numerics::innerProduct(m, hm);
    const Eigen::Vector2d slope(-numerics::innerProduct(g, direction), -numerics::innerProduct(g, m));
    // Only where the two directions are independent under the model (m may be d again).
    if (!(model(0, 0) > 0 && model(1, 1) > 0 &&
          model.determinant() > 1e-6 * model(0, 0) * model(1, 1)))
      return;
    const Eigen::Vector2d c = model.llt().solve(slope);
    if (c.allFinite())
      direction = c(0) * direction + c(1) * m;
  };
  // A frame's step without the Gauss–Newton factorisation: the Galerkin step of the
  // Gauss–Newton model over the last frame's motion and conjugate directions of the constant
  // matrix (conjugate gradients augmented by the motion). The constant matrix calls a
  // mechanism's turn stiff, the motion is that turn; the matrix restores what the motion's
  // linear step stretches. Each direction costs one back-substitution of the constant
  // (scalar) factor and one product, a fifth of a back-substitution of the kept one.
  double subspace_add_seconds = 0.0;
  const auto subspaceStep = [&](const DrivenFaces::Linearization& l, const RigidMotions* rigid) -> Eigen::MatrixX3d {
    const double step_from = budget.seconds();
    Eigen::MatrixX3d r = -g;
    if (rigid)
      rigid->remove(r);
    const double goal = options_.krylov_tolerance * std::sqrt(numerics::innerProduct(r, r));
    std::vector<Eigen::MatrixX3d> basis, basis_product;  // H-orthonormal u_i and H u_i
    Eigen::MatrixX3d step = Eigen::MatrixX3d::Zero(r.rows(), 3);
    step_product = Eigen::MatrixX3d::Zero(r.rows(), 3);
    const auto add = [&](Eigen::MatrixX3d v) {
      if (rigid)
        rigid->remove(v);
      Eigen::MatrixX3d hv = multiply(l, v);
      const double before = numerics::innerProduct(v, hv);
      for (size_t i = 0; i < basis.size(); ++i)
      {
        const double c = numerics::innerProduct(basis_product[i], v);
        v -= c * basis[i];
        hv -= c * basis_product[i];
      }
      const double norm2 = numerics::innerProduct(v, hv);
      if (!(norm2 > 1e-10 * before))
        return;
      const double norm = std::sqrt(norm2);
      basis.push_back(v / norm);
      basis_product.push_back(hv / norm);
      const double c = numerics::innerProduct(basis.back(), r);
      step += c * basis.back();
      step_product += c * basis_product.back();
      r -= c * basis_product.back();
    };
    // A slide's first frame (not going on from the last, its motion from elsewhere on the
    // path): the kept matrix's step as well, which points along the turn the balance takes
    // here, if too short.
    if (motion.size() > 0)
      add(motion);
    if (!continues && s.gauss_newton.valid())
      add(precondition(r));
    krylov_cut = false;
    for (int k = 0; k < options_.subspace_directions; ++k)
    {
      if (std::sqrt(numerics::innerProduct(r, r)) <= goal)
        break;
      if (k > 0 && !fits(subspace_add_seconds))
      {
        krylov_cut = true;
        break;
      }
      const double add_from = budget.seconds();
      add(solveConstant(r));
      subspace_add_seconds = budget.seconds() - add_from;
    }
    solve_seconds = budget.seconds() - step_from;  // what the next iteration's step will cost
    return step;
  };
  // A factorisation is paid for only where the budget has room for it (twice what the last
  // one took): in a preview frame the kept matrix serves until it fails outright.
  const auto roomForFactor = [&]() {
    return limits_.max_seconds <= 0 || limits_.max_seconds - budget.seconds() > 2 * s.factor_seconds;
  };
  // How far the faces turned since the kept matrix was factorised, as K·δ² for the face that
  // turned most (δ its turn in radians, K the face stiffness): what that matrix's face term
  // charges along the mechanism's present turn, against the hinges' stiffness (about 1).
  const auto turnedSinceFactor = [&](const DrivenFaces::Linearization& l) -> double {
    if (s.factor_frames.size() != l.frame.size())
      return INFINITY;
    double largest = 0.0;
    for (size_t f = 0; f < l.frame.size(); ++f)
      largest = std::max(largest, (l.frame[f] - s.factor_frames[f]).squaredNorm());
    return energy.faceStiffness() * largest;
  };
  bool frames_pending = false;
  Positions trial = x, trial_gradient;
  std::string stuck;
  bool diverged = !std::isfinite(now.energy);
  const double tolerance = limits_.tolerance;
  double last_step = INFINITY;
  if (options_.restore_final_faces && limits_.max_seconds > 0)
    final_reserve = s.restore_seconds;
  bool stopped_by_limits = false;
  while (!diverged)
  {
    // Out of budget: stop before paying for a direction. A direction once paid for is taken
    // (the first always: a frame must move), even when computing it spent the budget.
    if (budget.exhausted(report.iterations) && (report.iterations > 0 || limits_.max_iterations <= 0))
    {
      stopped_by_limits = true;
      break;
    }
    if (report.iterations > 0 && !fits(solve_seconds + evaluate_seconds))
    {
      stopped_by_limits = true;
      break;
    }
    if (refresh)
    {
      refresh = false;
      frames_pending = true;
      refactorAfresh();
    }
    Eigen::MatrixX3d direction;
    if (subspace_frame && !anchored && !frame_rigid)
      frame_rigid.emplace(x, free);
    const std::optional<RigidMotions> rigid =
        anchored || subspace_frame ? std::nullopt : std::make_optional<RigidMotions>(x, free);
    if (subspace_frame)
    {
      if (!start_linearized)
        start_linearization = energy.linearize(x);
      start_linearized = false;  // x moves on
      direction = subspaceStep(start_linearization, frame_rigid ? &*frame_rigid : nullptr);
    }
    else if (options_.hessian == DriverHessian::Lagged)
    {
      const DrivenFaces::Linearization linearization = energy.linearize(x);
      if (frames_pending)
      {
        s.factor_frames = linearization.frame;
        frames_pending = false;
      }
      else if (options_.refactor_turn > 0 && s.gauss_newton.valid() && roomForFactor() &&
               turnedSinceFactor(linearization) > options_.refactor_turn)
      {
        refactorAfresh();
        s.factor_frames = linearization.frame;
      }
      direction = newtonKrylovStep(linearization, rigid ? &*rigid : nullptr);
      if (options_.follow_motion && motion.size() > 0)
        followMotion(linearization, rigid ? &*rigid : nullptr, direction);
    }
    else
      direction = lbfgsStep();
    const RigidMotions* drift = rigid ? &*rigid : (frame_rigid ? &*frame_rigid : nullptr);
    if (drift)
      drift->remove(direction);
    // Balanced when the step the model predicts moves nothing measurably. A Newton–Krylov step
    // the budget cut short (one or two iterations on a matrix kept from another state) can be
    // small far from balance: it does not tell.
    const double step_size = direction.cwiseAbs().maxCoeff();
    // Newton steps on the energy's own Hessian that stopped shrinking within ten times the
    // tolerance: a degenerate balance (the Hessian singular along a mechanism there, where
    // Newton only halves its distance per step) or the rounding floor. Balanced as far as it goes.
    const bool stalled = exact_products && step_size <= 10 * tolerance && step_size >= 0.5 * last_step;
    if ((step_size <= tolerance || stalled) && !krylov_cut)
    {
      report.converged = true;
      break;
    }
    ++report.iterations;
    double slope = numerics::innerProduct(g, direction);
    if (!(slope < 0))
    {
      // Curvature pairs gone stale: restart from the matrix alone.
      history.clear();
      direction = -precondition(g);
      if (drift)
        drift->remove(direction);
      slope = numerics::innerProduct(g, direction);
      if (!(slope < 0))
      {
        stuck = "no descent direction";
        break;
      }
    }
    double step_length = 1.0;
    bool accepted = false;
    bool restored = false;  // the accepted trial is a restored one, off the line
    DrivenFaces::Evaluation next;
    for (int k = 0; k < options_.max_line_search; ++k, step_length *= 0.5)
    {
      trial = x;
      for (size_t i = 0; i < free.size(); ++i)
        trial.col(free[i]) += step_length * direction.row(static_cast<Eigen::Index>(i)).transpose();
      const double evaluate_from = budget.seconds();
      next = energy.evaluate(trial, &trial_gradient);
      s.evaluate_seconds = budget.seconds() - evaluate_from;
      if (next.energy <= now.energy + options_.armijo * step_length * slope)
      {
        accepted = true;
        break;
      }
      // A long linear step along turning faces stretches them (by about half the turn squared)
      // and fails on that alone: with the faces restored it may still be the step to take.
      if (options_.restore_trial_faces && !subspace_frame)
      {
        restoreFaces(trial, trial_gradient, next);
        if (next.energy <= now.energy + options_.armijo * step_length * slope)
        {
          accepted = true;
          restored = true;
          break;
        }
      }
    }
    if (!accepted)
    {
      // Near balance the energy's change drowns in its rounding; the gradient still tells:
      // take the full step when it leaves a smaller gradient.
      trial = x;
      for (size_t i = 0; i < free.size(); ++i)
        trial.col(free[i]) += direction.row(static_cast<Eigen::Index>(i)).transpose();
      next = energy.evaluate(trial, &trial_gradient);
      const double rounding = 1e-12 * std::max(1.0, std::abs(now.energy));
      if (next.energy <= now.energy + rounding && gather(trial_gradient, free).norm() < g.norm())
      {
        accepted = true;
        step_length = 1.0;
      }
    }
    if (!accepted)
    {
      // A fresh matrix may still find a way down.
      if (options_.hessian == DriverHessian::Lagged && !subspace_frame && !history.empty())
      {
        refresh = true;
        continue;
      }
      // Within a hundred times the tolerance the rest is rounding: balanced as far as it goes.
      report.converged = step_size <= 100 * tolerance;
      stuck = "no step lowers the energy any further";
      break;
    }
    const Eigen::MatrixX3d g_next = gather(trial_gradient, free);
    Eigen::MatrixX3d step =
        restored ? Eigen::MatrixX3d(gather(trial - x, free)) : Eigen::MatrixX3d(step_length * direction);
    if (options_.hessian != DriverHessian::Exact)
      history.add(std::move(step), g_next - g);
    // The kept matrix pays while the steps shrink fast; when they stop, factor afresh. Not
    // for slow conjugate gradients in a Newton step that shrank the step a hundredfold: the
    // next step, converging quadratically, is the last or nearly.
    const bool room = roomForFactor();
    const bool quadratic = exact_products && step_size < 0.01 * last_step;
    if (options_.hessian == DriverHessian::Exact ||
        (options_.hessian == DriverHessian::Lagged && room && !subspace_frame &&
         ((krylov_slow && !quadratic) || (!exact_products && step_size > options_.refresh_ratio * last_step))))
      refresh = true;
    const bool whole = step_length == 1.0 && !restored;
    if (exact_products && !whole)
      exact_refused = true;
    exact_products = exact_allowed && !exact_refused && whole && last_whole && step_size < 0.5 * last_step;
    last_whole = whole;
    last_step = step_size;
    std::swap(x, trial);
    g = g_next;
    now = next;
    diverged = !std::isfinite(now.energy);
  }
  // Stopped by its limits short of balance (a preview frame): the last step was linear along
  // turning faces.
  if (options_.restore_final_faces && stopped_by_limits && !diverged && !report.converged)
  {
    Positions x_gradient = Positions::Zero(3, x.cols());
    for (size_t i = 0; i < free.size(); ++i)
      x_gradient.col(free[i]) = g.row(static_cast<Eigen::Index>(i)).transpose();
    restoreFaces(x, x_gradient, now);
    // A subspace frame that still shows strain above `restore_strain` (a slide's second frame,
    // whose motion to follow came from a frame without one) restores once more.
    if (subspace_frame && springStrain(springs, x * scale).max > options_.restore_strain)
      restoreFaces(x, x_gradient, now);
  }
  report.seconds = budget.seconds();
  if (diverged)
  {
    setFoldedPositions(paper, start);
    report.diverged = true;
    report.max_strain = springStrain(springs, start).max;
    report.message = name() + " produced non-finite positions; rolled back";
    return report;
  }
  const Positions result = x * scale;
  setFoldedPositions(paper, result);
  report.max_strain = springStrain(springs, result).max;
  if (!report.converged)
    report.message = stuck.empty() ? "stopped before balance" : stuck;
  s.before_last = s.last;
  s.before_last_target = s.last_target;
  s.last_start = start;
  s.last = result;
  s.last_target = target;
  s.last_continued = continues;
  s.last_face_energy = now.face_energy;
  s.last_balanced = report.converged;
  return report;
}

}  // namespace virtual_origami::core
