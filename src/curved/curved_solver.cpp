#include "virtual_origami/curved/curved_solver.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <stdexcept>

#include <Eigen/LU>
#include <Eigen/QR>

#include "virtual_origami/curved/layered_start.h"
#include "virtual_origami/numerics/lbfgs_history.h"
#include "virtual_origami/numerics/solve_budget.h"

namespace virtual_origami::core
{
namespace
{
double largestNodeForce(const Eigen::VectorXd& g)
{
  double worst = 0.0;
  for (Eigen::Index i = 0; i + 2 < g.size(); i += 3)
    worst = std::max(worst, g.segment<3>(i).norm());
  return std::isfinite(g.sum()) ? worst : INFINITY;
}

void moveFree(Positions& x, const Positions& from, const Eigen::VectorXd& step, double alpha,
              const std::vector<int>& free_index)
{
  for (Eigen::Index v = 0; v < x.cols(); ++v)
    if (free_index[v] >= 0)
      x.col(v) = from.col(v) + alpha * step.segment<3>(3 * free_index[v]);
}

/// The rigid motions of the free nodes that leave every pinned node where it is and the
/// energy as it is (all of them when the paper floats; with weight or a table, only those
/// in the table's plane: shifts along x and y, turns about z), orthonormal columns over the
/// free coordinates at `x`. Two pins leave the turn about their line: no force resists it,
/// so a step's rounding along it is divided by nothing but the damping.
Eigen::MatrixXd freeMotions(const Positions& x, const std::vector<int>& free_index, int free_count,
                            bool in_plane_only)
{
  // Generators: translation t and rotation ω about the centroid c, u(p) = t + ω × (p − c).
  const Vec3 centre = x.rowwise().mean();
  std::vector<int> allowed = in_plane_only ? std::vector<int>{ 0, 1, 5 } : std::vector<int>{ 0, 1, 2, 3, 4, 5 };
  const auto motion = [&](int generator, const Vec3& p) -> Vec3 {
    if (generator < 3)
      return Vec3::Unit(generator);
    return Vec3::Unit(generator - 3).cross(p - centre);
  };
  std::vector<int> pinned;
  for (size_t v = 0; v < free_index.size(); ++v)
    if (free_index[v] < 0)
      pinned.push_back(static_cast<int>(v));
  const int m = static_cast<int>(allowed.size());
  Eigen::MatrixXd at_pins(3 * pinned.size(), m);
  for (size_t k = 0; k < pinned.size(); ++k)
    for (int j = 0; j < m; ++j)
      at_pins.block<3, 1>(3 * k, j) = motion(allowed[j], x.col(pinned[k]));
  // Combinations of the generators that vanish at every pin.
  Eigen::MatrixXd combos = Eigen::MatrixXd::Identity(m, m);
  if (!pinned.empty())
  {
    Eigen::FullPivLU<Eigen::MatrixXd> lu(at_pins);
    lu.setThreshold(1e-9);
    combos = lu.kernel();
    if (lu.rank() == m)
      return Eigen::MatrixXd(3 * free_count, 0);
  }
  Eigen::MatrixXd modes = Eigen::MatrixXd::Zero(3 * free_count, combos.cols());
  for (size_t v = 0; v < free_index.size(); ++v)
    if (const int f = free_index[v]; f >= 0)
      for (int j = 0; j < m; ++j)
      {
        const Vec3 u = motion(allowed[j], x.col(v));
        for (Eigen::Index c = 0; c < combos.cols(); ++c)
          modes.block<3, 1>(3 * f, c) += combos(j, c) * u;
      }
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(modes);
  return qr.householderQ() * Eigen::MatrixXd::Identity(modes.rows(), modes.cols());
}

/// Negative curvature of the energy (per unit move, over the stretch stiffness) smaller than
/// this is rounding: the free turn about two pins, a sheet lying flat.
constexpr double kNegligibleCurvature = 1e-11;
/// Relative rounding of the summed energy, below which a line search compares slopes instead.
constexpr double kEnergyRounding = 1e-10;
/// Conjugate-gradient iterations spent looking for a way down from a balance.
constexpr int kSaddleIterations = 6;

/// `v` less its part along the free rigid motions (orthonormal columns of `free_motions`).
void removeFreeMotions(const Eigen::MatrixXd& free_motions, Eigen::VectorXd& v)
{
  if (free_motions.cols() > 0)
    v -= free_motions * (free_motions.transpose() * v);
}

/// SolveLimits for the shared budget: the iteration cap is checked by the caller.
SolveLimits budgetLimits(const CurvedSolveOptions& options, int max_iterations)
{
  SolveLimits limits;
  limits.max_iterations = max_iterations;
  limits.max_seconds = options.max_seconds;
  return limits;
}

/// The test both methods make before each step, from the gradient at the current state: stop
/// on a non-finite state (diverged, with `nonfinite` as the message), at balance (converged)
/// or at the end of the budget; else count the step about to be taken.
bool stopBeforeStep(const Eigen::VectorXd& g, double energy, double force_scale, double tolerance,
                    const numerics::SolveBudget& budget, const char* nonfinite, CurvedReport& report)
{
  report.max_force = largestNodeForce(g) / force_scale;
  if (!std::isfinite(energy) || !std::isfinite(report.max_force))
  {
    report.diverged = true;
    report.message = nonfinite;
    return true;
  }
  if (report.max_force <= tolerance)
  {
    report.converged = true;
    return true;
  }
  if (budget.exhausted(report.iterations))
    return true;
  ++report.iterations;
  return false;
}
}  // namespace

Eigen::MatrixXd freeRigidMotions(const Positions& x, const std::vector<int>& free_index, int free_count,
                                 bool in_plane_only)
{
  return freeMotions(x, free_index, free_count, in_plane_only);
}

CurvedSolver::CurvedSolver(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material,
                           const ContactOptions& contact, const CurvedSolveOptions& options,
                           const Surroundings& surroundings)
  : mesh_(mesh)
  , material_(material)
  , terms_(curvedTerms(mesh, paper, material))
  , contact_(mesh, paper, material, contact)
  , options_(options)
  , surroundings_(surroundings)
{
  if (!(surroundings_.table_stiffness > 0))
    surroundings_.table_stiffness = contact_.stiffness();
  if (contact.barrier)
  {
    BarrierContactOptions barrier;
    // Half the lift between stacked layers (layered_start.h), unless given.
    barrier.activation =
        contact.barrier_activation > 0 ? contact.barrier_activation : 0.5 * LayeredStartOptions().gapFor(paper);
    barrier_ = std::make_unique<BarrierContact>(mesh, barrier);
    barrier_->setPush(contact.barrier_force * material.stretch * mesh.spacing);
  }
}

void CurvedSolver::restTermsAt(const Positions& x)
{
  core::restTermsAt(terms_, x);
  constant_free_.clear();  // a quasi-Newton constant matrix made with the old rests
}

void CurvedSolver::updateContact(const Positions& x)
{
  if (!barrier_)
  {
    contact_.update(x);
    return;
  }
  if (!barrier_started_)
  {
    barrier_->guardNearPairs(x, barrier_->activation());
    barrier_started_ = true;
  }
  // The pairs within the barrier's reach here; a step watches those its motion sweeps near
  // (lineSearch).
  barrier_->update(x, nullptr, barrier_->activation());
}

double CurvedSolver::energy(const Positions& x, const Assembly& out, CurvedEnergy* parts, double* contact) const
{
  const CurvedEnergy e = evaluateCurved(terms_, x, out);
  // The table is contact too, the weight a load: both count with contact in the report.
  const double c = (barrier_ ? barrier_->evaluate(x, out) : contact_.evaluate(x, out)) +
                   evaluateSurroundings(surroundings_, terms_.mass, x, out);
  if (parts)
    *parts = e;
  if (contact)
    *contact = c;
  return e.total() + c;
}

double CurvedSolver::lineSearch(const Positions& x, double e, const Eigen::VectorXd& g, Eigen::VectorXd& step,
                                int tries, double max_move, double worst_gap, const std::vector<int>& free_index,
                                Positions& trial, Eigen::VectorXd& trial_gradient) const
{
  const int free_count = static_cast<int>(g.size() / 3);
  double longest = 0.0;
  for (int i = 0; i < free_count; ++i)
    longest = std::max(longest, step.segment<3>(3 * i).norm());
  if (!std::isfinite(longest))
    return 0.0;
  if (longest > max_move)
    step *= max_move / longest;
  const double slope = g.dot(step);
  if (!(slope < 0))
    return 0.0;
  double alpha = 1.0;
  // The share of the allowed step: a step contact's collision check cuts short counts as
  // whole for the damping (it says nothing of how well the quadratic model fits).
  double allowed = 1.0;
  if (barrier_)
  {
    // No farther than contact's continuous collision check allows: no pair closes more than
    // most of its distance, so none passes through between the trials.
    Positions motion = Positions::Zero(3, x.cols());
    for (size_t v = 0; v < free_index.size(); ++v)
      if (free_index[v] >= 0)
        motion.col(v) = step.segment<3>(3 * free_index[v]);
    barrier_->update(x, &motion, barrier_->activation());
    alpha = barrier_->safeStep(x, motion);
    if (!(alpha > 0))
      return 0.0;
    allowed = alpha;
  }
  for (int k = 0; k < tries; ++k, alpha *= 0.5)
  {
    moveFree(trial, x, step, alpha, free_index);
    if (contact_.worstGap(trial) < std::min(0.0, worst_gap) - 0.5 * contact_.thickness())
      continue;
    const double moved = energy(trial, {});
    if (moved <= e + 1e-4 * alpha * slope)
      return alpha / allowed;
    // Near balance the energy's change falls below its rounding (a sum over every term)
    // while the forces are still above the tolerance: there the slope at the trial decides
    // (Hager and Zhang's approximate Wolfe condition: on a quadratic, Armijo's).
    if (std::abs(moved - e) <= kEnergyRounding * std::abs(e))
    {
      trial_gradient.setZero();
      energy(trial, { &free_index, &trial_gradient, nullptr });
      if (trial_gradient.dot(step) <= -(1 - 2e-4) * slope)
        return alpha / allowed;
    }
  }
  return 0.0;
}

double CurvedSolver::maxForce(const Positions& x_in, const std::vector<CurvedPin>& pins)
{
  Positions x = x_in;
  std::vector<char> fixed(mesh_.nodes.size(), 0);
  for (const CurvedPin& pin : pins)
  {
    fixed[pin.node] = 1;
    x.col(pin.node) = pin.position;
  }
  int free_count = 0;
  const std::vector<int> free_index = freeIndices(fixed, mesh_.nodes.size(), &free_count);
  updateContact(x);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * free_count);
  energy(x, { &free_index, &g, nullptr });
  return largestNodeForce(g) / (material_.stretch * mesh_.spacing);
}

CurvedReport CurvedSolver::solve(Positions& x, const std::vector<CurvedPin>& pins)
{
  // A pin off the sheet (no such node) or at no finite point: refused before anything moves.
  for (const CurvedPin& pin : pins)
    if (pin.node < 0 || pin.node >= static_cast<int>(mesh_.nodes.size()) || !pin.position.allFinite())
    {
      CurvedReport refused;
      refused.refused = true;
      refused.message = pin.node < 0 || pin.node >= static_cast<int>(mesh_.nodes.size()) ?
                            "pinned node " + std::to_string(pin.node) + " is off the sheet (the mesh has " +
                                std::to_string(mesh_.nodes.size()) + " nodes)" :
                            "the pin of node " + std::to_string(pin.node) + " is not at a finite point";
      return refused;
    }
  if (x.cols() != static_cast<Eigen::Index>(mesh_.nodes.size()))
  {
    CurvedReport refused;
    refused.refused = true;
    refused.message = "the positions have " + std::to_string(x.cols()) + " columns for " +
                      std::to_string(mesh_.nodes.size()) + " nodes";
    return refused;
  }
  std::vector<char> fixed(mesh_.nodes.size(), 0);
  for (const CurvedPin& pin : pins)
    fixed[pin.node] = 1;
  int free_count = 0;
  const std::vector<int> free_index = freeIndices(fixed, mesh_.nodes.size(), &free_count);
  Positions start = x;
  for (const CurvedPin& pin : pins)
    start.col(pin.node) = pin.position;
  const bool is_static = options_.method != CurvedMethod::Rk4;
  const bool predicted = is_static && predict(x, pins, free_index, free_count);
  for (const CurvedPin& pin : pins)
    x.col(pin.node) = pin.position;
  const auto staticSolve = [&] {
    return options_.method == CurvedMethod::QuasiNewton ? quasiNewton(x, free_index, free_count) :
                                                          newton(x, free_index, free_count);
  };
  CurvedReport report = is_static ? staticSolve() : rk4(x, free_index, free_count);
  // Newton converges to any balance, a saddle too (a sheet pressed flat in its plane, a curl
  // carried on past where it buckles): where the solve met negative curvature (or, with
  // check_stability, where the Hessian at the balance is not positive definite), the balance
  // is tested, and a saddle is left downhill and the solve goes on (twice at most).
  // QuasiNewton's own balances (no Hessian factorised to fail): with check_stability, the
  // search for a way down runs at every balance, on the exact Hessian there with the turned
  // constant matrix as preconditioner, and finds one or not (no factorisation).
  const bool by_constant = options_.method == CurvedMethod::QuasiNewton && !report.handed_over;
  const auto unstable = [&] {
    if (!report.converged || !is_static || !options_.leave_saddles)
      return false;
    if (by_constant)
      return options_.check_stability;
    return negative_curvature_ || (options_.check_stability && unstableAt(x, free_index, free_count));
  };
  for (int left = 0; left < 2 && unstable(); ++left)
  {
    if (!leaveSaddle(x, free_index, free_count, by_constant))
      break;
    const CurvedReport before = report;
    report = staticSolve();
    report.iterations += before.iterations;
    report.factorizations += before.factorizations;
    report.krylov_steps += before.krylov_steps;
    report.lbfgs_steps += before.lbfgs_steps;
    report.handed_over = report.handed_over || before.handed_over;
    report.saddles_left = before.saddles_left + 1;
    path_.clear();  // another branch: the last balances no longer foretell this one
  }
  report.predicted = predicted;
  if (report.diverged)
  {
    x = start;
    updateContact(x);
  }
  // The path so far, for the next solve's prediction: only balanced shapes count.
  if (report.converged)
  {
    path_.push_back({ x, pins });
    if (path_.size() > 4)
      path_.erase(path_.begin());
  }
  else
    path_.clear();
  report.contacts = barrier_ ? barrier_->activePairs(x) : contact_.watchedPairs();
  return report;
}

bool CurvedSolver::predict(Positions& x, const std::vector<CurvedPin>& pins, const std::vector<int>& free_index,
                           int free_count)
{
  // A drag moves its pins a little at a time along a smooth path, and the balance moves
  // smoothly with them: when the pins go on along the path of the last balances, the shape
  // is carried on along its path too (the polynomial through the last two or three, in the
  // pins' travel), and Newton starts with an error of the step's second or third order
  // instead of its first (the pulled corner alone would stretch its edges by the whole step).
  if (!options_.predict || path_.size() < 2 || x.cols() != path_.back().x.cols() || x != path_.back().x)
    return false;
  for (const Balance& b : path_)
  {
    if (b.pins.size() != pins.size())
      return false;
    for (size_t k = 0; k < pins.size(); ++k)
      if (b.pins[k].node != pins[k].node)
        return false;
  }
  const auto travel = [&](const std::vector<CurvedPin>& from, const std::vector<CurvedPin>& to) {
    double squared = 0;
    for (size_t k = 0; k < pins.size(); ++k)
      squared += (to[k].position - from[k].position).squaredNorm();
    return std::sqrt(squared);
  };
  // The pins' travel along the path: 0 at the oldest balance.
  std::vector<double> at{ 0.0 };
  for (size_t k = 1; k < path_.size(); ++k)
    at.push_back(at.back() + travel(path_[k - 1].pins, path_[k].pins));
  const double step = travel(path_.back().pins, pins);
  if (!(step > 0))
    return false;
  // Lagrange's weights at travel `to` for the polynomial of `order` through the balances
  // ending at `last`; empty when two of them are at one point.
  const auto weights = [&](size_t order, size_t last, double to) {
    std::vector<double> weight(path_.size(), 0.0);
    for (size_t i = last - order; i <= last; ++i)
    {
      weight[i] = 1.0;
      for (size_t j = last - order; j <= last; ++j)
        if (j != i)
        {
          if (at[i] == at[j])
            return std::vector<double>();
          weight[i] *= (to - at[j]) / (at[i] - at[j]);
        }
    }
    return weight;
  };
  // The order that would have foreseen the last balance best from those before it (where the
  // path is erratic, near a snap, a higher order only amplifies the solves' own errors), as
  // long as it carries the pins to within a tenth of their step of where they are now.
  const size_t last = path_.size() - 1;
  size_t order = 1;
  double best = INFINITY;
  for (size_t k = 0; k <= 2 && k + 1 <= last && last >= 2; ++k)
  {
    const std::vector<double> w = weights(k, last - 1, at[last]);
    if (w.empty())
      continue;
    Positions hindcast = -path_[last].x;
    for (size_t i = 0; i < last; ++i)
      hindcast += w[i] * path_[i].x;
    const double missed = hindcast.colwise().squaredNorm().maxCoeff();
    if (missed < best)
    {
      best = missed;
      order = k;
    }
  }
  order = std::min(order, last);
  std::vector<double> weight;
  for (;; --order)
  {
    if (order == 0)
      return false;
    weight = weights(order, last, at[last] + step);
    if (weight.empty())
      continue;
    double missed = 0;
    for (size_t k = 0; k < pins.size(); ++k)
    {
      Vec3 guess = Vec3::Zero();
      for (size_t i = 0; i <= last; ++i)
        guess += weight[i] * path_[i].pins[k].position;
      missed += (guess - pins[k].position).squaredNorm();
    }
    if (std::sqrt(missed) <= 0.1 * step)
      break;
  }
  Positions motion = -x;
  for (size_t i = 0; i <= last; ++i)
    motion += weight[i] * path_[i].x;
  // Not along a free rigid motion: no force sets the sheet's turn about two pins, so the
  // path's drift there is rounding, and extrapolated it would grow with every solve.
  const Eigen::MatrixXd free_motions = freeMotions(x, free_index, free_count, inPlaneOnly());
  if (free_motions.cols() > 0)
  {
    Eigen::VectorXd free_motion(3 * free_count);
    for (size_t v = 0; v < free_index.size(); ++v)
      if (free_index[v] >= 0)
        free_motion.segment<3>(3 * free_index[v]) = motion.col(v);
    removeFreeMotions(free_motions, free_motion);
    for (size_t v = 0; v < free_index.size(); ++v)
      if (free_index[v] >= 0)
        motion.col(v) = free_motion.segment<3>(3 * free_index[v]);
  }
  // In moves no longer than one Newton step may make, contact looking after each (as after
  // each step): no node passes a layer unseen. A move that would carry a watched pair
  // across is not made, and the prediction ends there.
  const double longest = std::sqrt(motion.colwise().squaredNorm().maxCoeff());
  const int moves = static_cast<int>(std::ceil(longest / (options_.max_step * contact_.range())));
  for (int k = 0; k < moves; ++k)
  {
    updateContact(x);
    const double worst_gap = contact_.worstGap(x);
    const Positions next = x + motion / moves;
    if (contact_.worstGap(next) < std::min(0.0, worst_gap) - 0.5 * contact_.thickness())
      break;
    if (barrier_)
    {
      const Positions move = motion / moves;
      barrier_->update(x, &move, barrier_->activation());
      if (barrier_->safeStep(x, move) < 1.0)
        break;
    }
    x = next;
  }
  return true;
}

CurvedReport CurvedSolver::newton(Positions& x, const std::vector<int>& free_index, int free_count)
{
  CurvedReport report;
  const numerics::SolveBudget budget(budgetLimits(options_, options_.max_iterations));
  const double force_scale = material_.stretch * mesh_.spacing;
  const double max_move = options_.max_step * contact_.range();
  const int n = 3 * free_count;
  Positions trial = x;
  Eigen::VectorXd g(n), g_trial(n);
  std::string stuck;
  // Three kinds of step, cheapest first. A factorisation of an earlier Hessian (this solve's
  // or an earlier one's, for the same free nodes) is a positive definite step matrix: its
  // steps descend, and near balance they converge nearly as fast as Newton's for a fraction
  // of the cost (no Hessian, no factorisation). When such a step falls short (cut back, or
  // the force falling by less than modified_newton_rate), the exact Hessian's Newton step is
  // found by conjugate gradients with that factorisation as preconditioner: a few
  // back-substitutions where a new factorisation costs ten. Only when that fails too (the
  // Hessian no longer positive definite, or too far from the old one to cut the force
  // tenfold) is the Hessian factorised anew, and at the next solve when they needed more
  // than half their iterations.
  const bool same_free = factor_free_ == free_index && factorization_.rows() == n;
  if (!same_free)
    factorization_.reset();
  // A kept factorisation that needed many conjugate-gradient iterations last time is renewed
  // now, and one whose own step fell short last time is not tried first.
  bool refresh = !factorization_.valid() || renew_factorization_;
  bool krylov = !stale_steps_help_;
  bool refresh_in_solve = false;  // a factorisation made in this solve
  double last_force = INFINITY;
  // Levenberg–Marquardt damping: falls while full steps succeed (towards Newton's quadratic
  // convergence), rises when they are cut back. A solve starts from where the last one left
  // it: a drag's next small pull needs about as little, and starting higher would damp the
  // soft bending modes for many iterations. The first solve starts in proportion to the force.
  double& mu = damping_mu_;
  if (!same_free)
    mu = -1.0;
  negative_curvature_ = false;
  while (true)
  {
    updateContact(x);
    // A solve that will start with the exact Hessian (no kept factorisation, or one whose own
    // steps fell short last time) assembles it with the first gradient: the shape a pull
    // starts from is seldom balanced already.
    const bool hessian_now = report.iterations == 0 && (refresh || krylov);
    g.setZero();
    double e = hessian_now ? assembleHessian(x, free_index, free_count, g, &report.energy, &report.contact_energy) :
                             energy(x, { &free_index, &g, nullptr }, &report.energy, &report.contact_energy);
    if (stopBeforeStep(g, e, force_scale, options_.tolerance, budget, "non-finite energy; rolled back", report))
      break;
    if (!(options_.modified_newton_rate > 0))
      refresh = true;
    else if (report.iterations > 1 && !(report.max_force <= options_.modified_newton_rate * last_force))
      krylov = true;
    last_force = report.max_force;
    const double worst_gap = contact_.worstGap(x);
    const Eigen::MatrixXd free_motions = freeMotions(x, free_index, free_count, inPlaneOnly());
    // Armijo's line search along `step` (lineSearch), at most `tries` halvings; the point it
    // reaches becomes x.
    const auto search = [&](Eigen::VectorXd& step, int tries) {
      // No force resists a free rigid motion: its part of the step is rounding over damping.
      removeFreeMotions(free_motions, step);
      const double alpha = lineSearch(x, e, g, step, tries, max_move, worst_gap, free_index, trial, g_trial);
      if (alpha > 0)
        std::swap(x, trial);
      return alpha;
    };
    if (!refresh && !krylov)
    {
      // The old factorisation's step: a full one, or close; else on to the exact Hessian.
      Eigen::VectorXd step = factorization_.solve(-g);
      const double alpha = search(step, 2);
      stale_steps_help_ = alpha == 1.0;
      if (alpha == 1.0)
        continue;
      krylov = true;
      if (alpha > 0)
        continue;
    }
    if (!hessian_now)
      e = assembleHessian(x, free_index, free_count, g);
    if (mu < 0)
      mu = options_.damping * g.norm() / mesh_.spacing;
    if (!refresh)
    {
      // The preconditioner is stale when conjugate gradients cannot cut the force tenfold: the
      // step they found is taken, and the next one factorises.
      Eigen::VectorXd step;
      int iterations = 0;
      const double cut = conjugateGradients(g, mu, free_motions, options_.krylov_iterations, step, &iterations);
      renew_factorization_ = iterations > options_.krylov_iterations / 2;
      if (cut > 0)
      {
        ++report.krylov_steps;
        const double alpha = search(step, 30);
        if (alpha > 0)
        {
          mu = alpha == 1.0 ? std::max(mu / 4, 1e-14 * material_.stretch) : mu * 4;
          refresh = cut < 10;
          continue;
        }
      }
    }
    // The exact Hessian, factorised. It may be indefinite away from balance: the damping
    // rises until the shifted matrix is positive definite and its step lowers the energy, a
    // hundredfold per try: a failed try costs a whole factorisation (the soft modes it fails on
    // come last in the ordering), and the shifts needed past a snap are 10³–10⁷ times the last.
    // A factorisation renewed for the conjugate gradients' sake (not because Newton's own
    // steps fail) starts at the last one's shift, below which the matrix is seldom positive
    // definite; the damping of the steps stays where the line search has it.
    const bool renewing = renew_factorization_ && !refresh_in_solve;
    double shift = renewing ? std::max(mu, factor_shift_) : mu;
    refresh = false;
    refresh_in_solve = true;
    krylov = false;
    const double last_alpha = factorisedStep(g, free_index, search, shift, report);
    if (last_alpha == 0)
    {
      stuck = "no step lowers the energy any further";
      break;
    }
    if (!renewing)
      mu = shift;
    mu = last_alpha == 1.0 ? std::max(mu / 4, 1e-14 * material_.stretch) : mu * 4;
  }
  report.seconds = budget.seconds();
  if (!report.converged && !report.diverged)
  {
    std::ostringstream msg;
    msg << (stuck.empty() ? "stopped" : stuck) << " after " << report.iterations << " iterations at force "
        << report.max_force << " (tolerance " << options_.tolerance << ")";
    report.message = msg.str();
  }
  return report;
}

double CurvedSolver::factorisedStep(const Eigen::VectorXd& g, const std::vector<int>& free_index,
                                    const std::function<double(Eigen::VectorXd&, int)>& search, double& shift,
                                    CurvedReport& report)
{
  double alpha = 0;
  for (int attempt = 0; attempt < 30 && alpha == 0; ++attempt)
  {
    if (attempt > 0)
      shift *= 100;
    ++report.factorizations;
    if (!factorization_.factorize(hessian_, shift))
    {
      // Curvature below −shift somewhere; above kNegligibleCurvature it is the free turn's
      // rounding, not a saddle.
      negative_curvature_ = negative_curvature_ || shift >= kNegligibleCurvature * material_.stretch;
      continue;
    }
    factor_shift_ = shift;
    renew_factorization_ = false;
    stale_steps_help_ = true;
    factor_free_ = free_index;
    Eigen::VectorXd step = factorization_.solve(-g);
    alpha = search(step, 30);
  }
  return alpha;
}

bool CurvedSolver::prepareConstantFactor(const Positions& x, const std::vector<int>& free_index, int free_count)
{
  if (constant_free_ == free_index && constant_factor_.valid() && constant_factor_.rows() == 3 * free_count)
    return true;
  // The terms' Hessian alone, at the shape given (the flat or rigidly folded sheet, where
  // every measure is at rest: stretch and shear act as springs along the edges and corners,
  // bending as its quadratic model at rest). Contact comes and goes and the table pushes only
  // where the sheet touches it: both stay with the line search's true energy.
  Eigen::SparseMatrix<double> matrix = blockPattern(free_count, free_index, termGroups(terms_));
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * free_count);
  BlockHessian blocks{ &matrix };
  evaluateCurved(terms_, x, { &free_index, &g, nullptr, &blocks });
  if (options_.lbfgs_prestress > 0)
    for (const StretchTerm& term : terms_.stretch)
    {
      const int fi = free_index[term.i], fj = free_index[term.j];
      const Eigen::Matrix3d k = options_.lbfgs_prestress * term.weight * Eigen::Matrix3d::Identity();
      if (fi >= 0)
        blocks.add(fi, fi, k);
      if (fj >= 0)
        blocks.add(fj, fj, k);
      if (fi >= 0 && fj >= 0)
        blocks.add(std::max(fi, fj), std::min(fi, fj), Eigen::Matrix3d(-k));
    }
  // The free turn about two pins has no stiffness: the smallest shift counted as rounding,
  // raised where the shape given is bent and its Hessian not positive definite.
  double shift = kNegligibleCurvature * material_.stretch;
  for (int attempt = 0; attempt < 12; ++attempt, shift *= 100)
    if (constant_factor_.factorize(matrix, shift))
    {
      constant_free_ = free_index;
      constant_frames_ = nodeFrames(x);
      return true;
    }
  constant_free_.clear();
  return false;
}

std::vector<Eigen::Matrix3d> CurvedSolver::nodeFrames(const Positions& x) const
{
  const size_t nodes = mesh_.nodes.size();
  if (frame_partner_.size() != nodes)
  {
    auto& partner = const_cast<std::vector<int>&>(frame_partner_);
    partner.assign(nodes, -1);
    for (const MeshEdge& edge : mesh_.edges)
      for (int k = 0; k < 2; ++k)
        if (partner[edge.nodes[k]] < 0)
          partner[edge.nodes[k]] = edge.nodes[1 - k];
  }
  std::vector<Vec3> normal(nodes, Vec3::Zero());
  std::vector<Vec3> first(nodes, Vec3::Zero());  // a node's first triangle's normal
  for (const MeshTriangle& t : mesh_.triangles)
  {
    const Vec3 n = (x.col(t.nodes[1]) - x.col(t.nodes[0])).cross(x.col(t.nodes[2]) - x.col(t.nodes[0]));
    for (int node : t.nodes)
    {
      normal[node] += n;
      if (first[node].isZero())
        first[node] = n;
    }
  }
  std::vector<Eigen::Matrix3d> frames(nodes, Eigen::Matrix3d::Identity());
  for (size_t v = 0; v < nodes; ++v)
  {
    // A node on a crease folded flat has layers facing both ways: its triangles' normals
    // cancel, and one triangle's stands for them.
    Vec3 n = normal[v].norm() > 0.1 * first[v].norm() ? normal[v] : first[v];
    if (!(n.norm() > 0) || frame_partner_[v] < 0)
      continue;
    n.normalize();
    Vec3 t = x.col(frame_partner_[v]) - x.col(v);
    t -= t.dot(n) * n;
    if (!(t.norm() > 0))
      continue;
    t.normalize();
    frames[v].col(0) = t;
    frames[v].col(1) = n.cross(t);
    frames[v].col(2) = n;
  }
  return frames;
}

std::vector<Eigen::Matrix3d> CurvedSolver::constantTurns(const Positions& x) const
{
  // Each node's turn from where the constant matrix was made: the matrix R·H·Rᵀ (R block
  // diagonal) has the inverse R·H⁻¹·Rᵀ, one back-substitution of the constant factor.
  if (!options_.warp)
    return {};
  std::vector<Eigen::Matrix3d> turns = nodeFrames(x);
  for (size_t v = 0; v < turns.size(); ++v)
    turns[v] *= constant_frames_[v].transpose();
  return turns;
}

Eigen::VectorXd CurvedSolver::constantInverse(const Eigen::VectorXd& v, const std::vector<Eigen::Matrix3d>& turns,
                                              const std::vector<int>& free_index) const
{
  Eigen::VectorXd q = v;
  const auto turn = [&](Eigen::VectorXd& u, bool back) {
    if (turns.empty())
      return;
    for (size_t node = 0; node < free_index.size(); ++node)
      if (const int f = free_index[node]; f >= 0)
        u.segment<3>(3 * f) = back ? Eigen::Vector3d(turns[node].transpose() * u.segment<3>(3 * f)) :
                                     Eigen::Vector3d(turns[node] * u.segment<3>(3 * f));
  };
  turn(q, true);
  Eigen::VectorXd r = constant_factor_.solve(q);
  turn(r, false);
  return r;
}

CurvedReport CurvedSolver::quasiNewton(Positions& x, const std::vector<int>& free_index, int free_count)
{
  CurvedReport report;
  negative_curvature_ = false;
  const numerics::SolveBudget budget(budgetLimits(options_, options_.lbfgs_iterations));
  const double force_scale = material_.stretch * mesh_.spacing;
  const double max_move = options_.max_step * contact_.range();
  const int n = 3 * free_count;
  // The correction pairs s = Δx, y = Δ∇E of this solve's last iterations, oldest first (kept
  // from one solve of a drag to the next they made no difference: 1.73 against 1.79 solves
  // per CPU second at 10,000 vertices).
  numerics::LbfgsHistory<Eigen::VectorXd> history(options_.lbfgs_memory);
  Positions trial = x;
  Eigen::VectorXd g(n), g_next(n), direction(n);
  std::string stuck;
  updateContact(x);
  g.setZero();
  double e = energy(x, { &free_index, &g, nullptr }, &report.energy, &report.contact_energy);
  while (!stopBeforeStep(g, e, force_scale, options_.tolerance, budget, "non-finite energy; rolled back", report))
  {
    // The constant matrix, made at the first step of the first solve with these free nodes
    // (not for a shape that is balanced already, nor for one that is not finite).
    if (!(constant_free_ == free_index && constant_factor_.valid() && constant_factor_.rows() == n))
    {
      ++report.factorizations;
      if (!prepareConstantFactor(x, free_index, free_count))
      {
        stuck = "the constant matrix is not positive definite at any shift tried";
        break;
      }
    }
    ++report.lbfgs_steps;
    const Eigen::MatrixXd free_motions = freeMotions(x, free_index, free_count, inPlaneOnly());
    const std::vector<Eigen::Matrix3d> turns = constantTurns(x);
    // L-BFGS's two loops, the constant factorisation as the initial inverse Hessian (its own
    // scale: it is a Hessian, not a guess at one to be rescaled).
    const auto lbfgsDirection = [&] {
      Eigen::VectorXd q = g;
      removeFreeMotions(free_motions, q);
      Eigen::VectorXd r =
          history.apply(q, [&](const Eigen::VectorXd& v) { return constantInverse(v, turns, free_index); });
      removeFreeMotions(free_motions, r);
      return Eigen::VectorXd(-r);
    };
    const double worst_gap = contact_.worstGap(x);
    // Armijo's line search on the true energy, as Newton's (lineSearch); the point reached is
    // left in `trial`.
    const auto search = [&](Eigen::VectorXd& step) {
      return lineSearch(x, e, g, step, 30, max_move, worst_gap, free_index, trial, g_next);
    };
    double alpha = 0.0;
    if (options_.constant_krylov_iterations > 0)
    {
      // Newton–Krylov: the exact Hessian's step by conjugate gradients, preconditioned by the
      // turned constant matrix (Steihaug's stop at negative curvature).
      e = assembleHessian(x, free_index, free_count, g);
      const std::function<Eigen::VectorXd(const Eigen::VectorXd&)> precondition = [&](const Eigen::VectorXd& v) {
        return constantInverse(v, turns, free_index);
      };
      int iterations = 0;
      const double mu = 1e-14 * material_.stretch;
      if (conjugateGradients(g, mu, free_motions, options_.constant_krylov_iterations, direction, &iterations, nullptr,
                             &precondition) > 0)
      {
        report.krylov_steps += 1;
        alpha = search(direction);
      }
      if (alpha == 0)
      {
        stuck = "no step lowers the energy any further";
        break;
      }
    }
    else
    {
      direction = lbfgsDirection();
      alpha = search(direction);
    }
    if (alpha == 0 && !history.empty())
    {
      // The pairs mislead (contact came, the shape moved far from where they were taken):
      // forget them, and step with the constant matrix alone.
      history.clear();
      direction = lbfgsDirection();
      alpha = search(direction);
    }
    if (alpha == 0)
    {
      stuck = "no step lowers the energy any further";
      break;
    }
    std::swap(x, trial);
    updateContact(x);
    g_next.setZero();
    e = energy(x, { &free_index, &g_next, nullptr }, &report.energy, &report.contact_energy);
    Eigen::VectorXd s_new = alpha * direction, y_new = g_next - g;
    removeFreeMotions(free_motions, y_new);
    g.swap(g_next);
    history.add(std::move(s_new), std::move(y_new));
  }
  if (!report.converged && !report.diverged && options_.hand_over)
  {
    // The constant matrix no longer resembles the Hessian (a snap, a sheet turned far from
    // where the matrix was taken): Newton finishes from here.
    CurvedReport lbfgs = report;
    lbfgs.seconds = budget.seconds();
    report = newton(x, free_index, free_count);
    report.iterations += lbfgs.iterations;
    report.factorizations += lbfgs.factorizations;
    report.lbfgs_steps = lbfgs.lbfgs_steps;
    report.handed_over = true;
    report.seconds += lbfgs.seconds;
    return report;
  }
  report.seconds = budget.seconds();
  if (!report.converged && !report.diverged)
  {
    std::ostringstream msg;
    msg << (stuck.empty() ? "stopped" : stuck) << " after " << report.iterations << " quasi-Newton iterations at force "
        << report.max_force << " (tolerance " << options_.tolerance << ")";
    report.message = msg.str();
  }
  return report;
}

bool CurvedSolver::unstableAt(const Positions& x, const std::vector<int>& free_index, int free_count)
{
  updateContact(x);
  Eigen::VectorXd g(3 * free_count);
  assembleHessian(x, free_index, free_count, g);
  // On failure the shift rises a hundredfold until the factorisation succeeds: leaving the
  // saddle needs it as the preconditioner of its search, and the next solve as its own.
  double shift = kNegligibleCurvature * material_.stretch;
  bool unstable = false;
  for (int attempt = 0; attempt < 12; ++attempt, shift *= 100)
  {
    if (factorization_.factorize(hessian_, shift))
    {
      factor_free_ = free_index;
      factor_shift_ = shift;
      renew_factorization_ = false;
      stale_steps_help_ = true;
      return unstable;
    }
    unstable = true;
  }
  return true;
}

bool CurvedSolver::leaveSaddle(Positions& x, const std::vector<int>& free_index, int free_count, bool with_constant)
{
  if (with_constant ? !(constant_factor_.valid() && constant_free_ == free_index) :
                      !(factorization_.valid() && factor_free_ == free_index))
    return false;
  updateContact(x);
  Eigen::VectorXd g(3 * free_count);
  const double e = assembleHessian(x, free_index, free_count, g);
  const Eigen::MatrixXd free_motions = freeMotions(x, free_index, free_count, inPlaneOnly());
  // Conjugate gradients on H·u = r for a random r: the kept factorisation (positive definite)
  // magnifies the soft modes, the unstable one among them, so a search direction with
  // negative curvature turns up within a few iterations when there is one.
  std::mt19937 random(saddle_seed_++);
  std::normal_distribution<double> normal;
  Eigen::VectorXd r(g.size());
  for (Eigen::Index i = 0; i < r.size(); ++i)
    r[i] = normal(random);
  Eigen::VectorXd step, downhill;
  int iterations = 0;
  const std::vector<Eigen::Matrix3d> turns = with_constant ? constantTurns(x) : std::vector<Eigen::Matrix3d>();
  const std::function<Eigen::VectorXd(const Eigen::VectorXd&)> constant = [&](const Eigen::VectorXd& v) {
    return constantInverse(v, turns, free_index);
  };
  conjugateGradients(r, 0.0, free_motions, kSaddleIterations, step, &iterations, &downhill,
                     with_constant ? &constant : nullptr);
  if (downhill.size() == 0 || !(downhill.dot(hessian_.selfadjointView<Eigen::Lower>() * downhill) <
                                -kNegligibleCurvature * material_.stretch * downhill.squaredNorm()))
    return false;
  // Along it either way (the energy is even in the move to second order), from a Newton
  // step's longest move down by halves, to the lower energy; no watched pair crossing over.
  double longest = 0.0;
  for (int i = 0; i < free_count; ++i)
    longest = std::max(longest, downhill.segment<3>(3 * i).norm());
  downhill *= options_.max_step * contact_.range() / longest;
  const double worst_gap = contact_.worstGap(x);
  Positions trial = x, best = x;
  double lowest = e;
  for (int k = 0; k < 12 && lowest == e; ++k, downhill *= 0.5)
    for (const double side : { 1.0, -1.0 })
    {
      moveFree(trial, x, downhill, side, free_index);
      if (contact_.worstGap(trial) < std::min(0.0, worst_gap) - 0.5 * contact_.thickness())
        continue;
      const double moved = energy(trial, {});
      if (moved < lowest)
      {
        lowest = moved;
        best = trial;
      }
    }
  if (!(lowest < e))
    return false;
  x = best;
  return true;
}

double CurvedSolver::conjugateGradients(const Eigen::VectorXd& g, double mu, const Eigen::MatrixXd& free_motions,
                                        int max_iterations, Eigen::VectorXd& step, int* iterations,
                                        Eigen::VectorXd* negative,
                                        const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>* precondition) const
{
  const auto apply = [&](const Eigen::VectorXd& v) {
    return precondition ? (*precondition)(v) : factorization_.solve(v);
  };
  // (H + μI)·step = −g by preconditioned conjugate gradients, the kept factorisation as the
  // preconditioner, within the complement of the free rigid motions (H is singular on them).
  // Stops where the linear model leaves half the tolerance (a tenth of the largest force when
  // that is below it already, a hundredth when far above: there the model is only good for a
  // step, and a tighter solve spent up to krylov_iterations back-substitutions on each), at
  // negative curvature (Steihaug: the step so far, or the preconditioned force when there is
  // none, still descends), or after max_iterations; every iterate lowers the quadratic
  // model, so each is a descent step. Looking for negative curvature (`negative` given: the
  // direction that has it, when one turns up) there is no goal: every iteration runs.
  Eigen::VectorXd r = -g;
  removeFreeMotions(free_motions, r);
  const double start = largestNodeForce(r);
  const double scale = material_.stretch * mesh_.spacing;
  const double tolerance = options_.tolerance * scale;
  const double goal =
      negative ? 0.0 : std::max(1e-2 * start, start > tolerance ? 0.5 * tolerance : 0.1 * start);
  step = Eigen::VectorXd::Zero(g.size());
  Eigen::VectorXd z = apply(r);
  removeFreeMotions(free_motions, z);
  Eigen::VectorXd d = z;
  double rz = r.dot(z);
  double left = start;
  for (int k = 0; k < max_iterations && left > goal; ++k)
  {
    *iterations = k + 1;
    const Eigen::VectorXd hd = hessian_.selfadjointView<Eigen::Lower>() * d + mu * d;
    const double curvature = d.dot(hd);
    if (!(curvature > 0) || !(rz > 0))
    {
      const bool found = std::isfinite(curvature) && rz > 0;
      if (k == 0)
        step = d;
      if (negative && found)
        *negative = d;
      return found ? 1.0 : 0.0;
    }
    const double a = rz / curvature;
    step += a * d;
    r -= a * hd;
    left = largestNodeForce(r);
    if (left <= goal)
      break;
    z = apply(r);
    removeFreeMotions(free_motions, z);
    const double rz_next = r.dot(z);
    d = z + (rz_next / rz) * d;
    rz = rz_next;
  }
  return std::isfinite(left) && left > 0 ? start / left : (left == 0 ? INFINITY : 0.0);
}

double CurvedSolver::assembleHessian(const Positions& x, const std::vector<int>& free_index, int free_count,
                                     Eigen::VectorXd& g, CurvedEnergy* parts, double* contact)
{
  // The pattern covers the terms and every contact pair seen so far for these free nodes, so
  // it (and the factorisation's analysis) stays put while contacts come and go.
  if (pattern_free_ != free_index)
  {
    pattern_groups_ = termGroups(terms_);
    hessian_ = blockPattern(free_count, free_index, pattern_groups_);
    pattern_free_ = free_index;
  }
  for (int round = 0;; ++round)
  {
    hessian_.coeffs().setZero();
    g.setZero();
    BlockHessian blocks{ &hessian_ };
    const double e = energy(x, { &free_index, &g, nullptr, &blocks }, parts, contact);
    if (blocks.missing == 0)
      return e;
    if (round > 0)
      throw std::logic_error("curved solver: a Hessian block outside the terms and contacts");
    const std::vector<std::array<int, 4>> contacts = barrier_ ? barrier_->pairNodes() : contact_.pairNodes();
    pattern_groups_.insert(pattern_groups_.end(), contacts.begin(), contacts.end());
    hessian_ = blockPattern(free_count, free_index, pattern_groups_);
  }
}

CurvedReport CurvedSolver::rk4(Positions& x, const std::vector<int>& free_index, int free_count)
{
  CurvedReport report;
  const numerics::SolveBudget budget(budgetLimits(options_, options_.max_steps));
  const double force_scale = material_.stretch * mesh_.spacing;
  const int n = 3 * free_count;
  Eigen::VectorXd inv_mass(n);
  for (size_t v = 0; v < free_index.size(); ++v)
    if (free_index[v] >= 0)
      inv_mass.segment<3>(3 * free_index[v]).setConstant(1.0 / terms_.mass[v]);

  updateContact(x);
  double dt = options_.time_step;
  if (!(dt > 0))
  {
    // Gershgorin bound on the stiffest mode of M⁻¹H (contact as it is at the start); RK4 is
    // stable up to ω·dt ≈ 2.8.
    std::vector<Eigen::Triplet<double>> triplets;
    Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
    energy(x, { &free_index, &g, &triplets });
    Eigen::VectorXd row_sum = Eigen::VectorXd::Zero(n);
    for (const auto& t : triplets)
      row_sum[t.row()] += std::abs(t.value());
    const double omega2 = (row_sum.array() * inv_mass.array()).maxCoeff();
    dt = 0.5 * 2.8 / std::sqrt(omega2);
  }
  report.time_step = dt;
  double c = options_.viscosity;
  if (!(c > 0))
  {
    // The first free bending mode of a sheet of side L: ω ≈ 2π²·√(q/ρ)/L².
    double area = 0;
    for (size_t t = 0; t < mesh_.triangles.size(); ++t)
      area += mesh_.restArea(static_cast<int>(t));
    c = 2 * 2 * M_PI * M_PI * std::sqrt(material_.bend / material_.density) / area;
  }
  double sheet_area = 0;
  for (size_t t = 0; t < mesh_.triangles.size(); ++t)
    sheet_area += mesh_.restArea(static_cast<int>(t));
  const double sheet_size = std::sqrt(sheet_area);

  Eigen::VectorXd v = Eigen::VectorXd::Zero(n), g(n);
  Positions xs = x;
  const auto acceleration = [&](const Positions& at, const Eigen::VectorXd& vel) {
    g.setZero();
    energy(at, { &free_index, &g, nullptr });
    return Eigen::VectorXd(-g.cwiseProduct(inv_mass) - c * vel);
  };
  const double start_energy = energy(x, {});
  while (true)
  {
    updateContact(x);
    // k1 from the current state also gives the force to test for balance.
    const Eigen::VectorXd a1 = acceleration(x, v);
    if (stopBeforeStep(g, 0.0, force_scale, options_.tolerance, budget, "rk4 produced non-finite forces; rolled back",
                       report))
      break;
    const Eigen::VectorXd v1 = v;
    moveFree(xs, x, v1, dt / 2, free_index);
    const Eigen::VectorXd v2 = v + dt / 2 * a1;
    const Eigen::VectorXd a2 = acceleration(xs, v2);
    moveFree(xs, x, v2, dt / 2, free_index);
    const Eigen::VectorXd v3 = v + dt / 2 * a2;
    const Eigen::VectorXd a3 = acceleration(xs, v3);
    moveFree(xs, x, v3, dt, free_index);
    const Eigen::VectorXd v4 = v + dt * a3;
    const Eigen::VectorXd a4 = acceleration(xs, v4);
    const Eigen::VectorXd dx = dt / 6 * (v1 + 2 * v2 + 2 * v3 + v4);
    v += dt / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    for (Eigen::Index node = 0; node < x.cols(); ++node)
      if (free_index[node] >= 0)
        x.col(node) += dx.segment<3>(3 * free_index[node]);
    // Damped motion never carries a node across the sheet in one step: one that does is
    // blowing up (caught before its coordinates overflow the contact grid).
    if (!dx.allFinite() || !v.allFinite() || dx.cwiseAbs().maxCoeff() > sheet_size)
    {
      report.diverged = true;
      report.message = "rk4 diverged (a node jumped farther than the sheet's size in one step); rolled back";
      break;
    }
    if (report.iterations % 100 == 0)
    {
      const double e = energy(x, {});
      if (!std::isfinite(e) || e > 1e6 * std::max(start_energy, 1e-30) + 1.0)
      {
        report.diverged = true;
        report.message = "rk4 diverged (energy grew a millionfold); rolled back";
        break;
      }
    }
  }
  if (!report.diverged)
    energy(x, {}, &report.energy, &report.contact_energy);
  report.seconds = budget.seconds();
  if (!report.converged && !report.diverged)
  {
    std::ostringstream msg;
    msg << "stopped after " << report.iterations << " steps of " << dt << " at force " << report.max_force
        << " (tolerance " << options_.tolerance << ")";
    report.message = msg.str();
  }
  return report;
}

}  // namespace virtual_origami::core
