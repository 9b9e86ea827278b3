#include "virtual_origami/curved/curved_solver.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "virtual_origami/solvers/solve_budget.h"

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
                    const SolveBudget& budget, const char* nonfinite, CurvedReport& report)
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
}

double CurvedSolver::energy(const Positions& x, const Assembly& out, CurvedEnergy* parts, double* contact) const
{
  const CurvedEnergy e = evaluateCurved(terms_, x, out);
  // The table is contact too, the weight a load: both count with contact in the report.
  const double c = contact_.evaluate(x, out) + evaluateSurroundings(surroundings_, terms_.mass, x, out);
  if (parts)
    *parts = e;
  if (contact)
    *contact = c;
  return e.total() + c;
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
  contact_.update(x);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * free_count);
  energy(x, { &free_index, &g, nullptr });
  return largestNodeForce(g) / (material_.stretch * mesh_.spacing);
}

CurvedReport CurvedSolver::solve(Positions& x, const std::vector<CurvedPin>& pins)
{
  std::vector<char> fixed(mesh_.nodes.size(), 0);
  for (const CurvedPin& pin : pins)
  {
    fixed[pin.node] = 1;
    x.col(pin.node) = pin.position;
  }
  int free_count = 0;
  const std::vector<int> free_index = freeIndices(fixed, mesh_.nodes.size(), &free_count);
  const Positions start = x;
  CurvedReport report =
      options_.method == CurvedMethod::Newton ? newton(x, free_index, free_count) : rk4(x, free_index, free_count);
  if (report.diverged)
  {
    x = start;
    contact_.update(x);
  }
  report.contacts = contact_.watchedPairs();
  return report;
}

CurvedReport CurvedSolver::newton(Positions& x, const std::vector<int>& free_index, int free_count)
{
  CurvedReport report;
  const SolveBudget budget(budgetLimits(options_, options_.max_iterations));
  const double force_scale = material_.stretch * mesh_.spacing;
  const double max_move = options_.max_step * contact_.range();
  const int n = 3 * free_count;
  Positions trial = x;
  Eigen::VectorXd g(n);
  std::string stuck;
  // A factorisation of an earlier Hessian (this solve's or the last one's, for the same free
  // nodes) is a positive definite step matrix: its steps descend, and near balance they
  // converge nearly as fast as Newton's for a fraction of the cost (no Hessian, no
  // factorisation). It is used while the last step, fresh or not, cut the largest force by
  // modified_newton_rate; where Newton itself crawls (far from balance, contact coming in)
  // every step is fresh.
  const bool same_free = factor_free_ == free_index && factorization_.rows() == n;
  if (!same_free)
    factorization_.reset();
  bool refresh = !factorization_.valid();
  double last_force = INFINITY;
  // Levenberg–Marquardt damping: falls while full steps succeed (towards Newton's quadratic
  // convergence), rises when they are cut back. A solve starts from where the last one left
  // it: a drag's next small pull needs about as little, and starting higher would damp the
  // soft bending modes for many iterations. The first solve starts in proportion to the force.
  double& mu = damping_mu_;
  if (!same_free)
    mu = -1.0;
  while (true)
  {
    contact_.update(x);
    g.setZero();
    double e = energy(x, { &free_index, &g, nullptr }, &report.energy, &report.contact_energy);
    if (stopBeforeStep(g, e, force_scale, options_.tolerance, budget, "non-finite energy; rolled back", report))
      break;
    if (!(options_.modified_newton_rate > 0) ||
        (report.iterations > 1 && !(report.max_force <= options_.modified_newton_rate * last_force)))
      refresh = true;
    last_force = report.max_force;
    const double worst_gap = contact_.worstGap(x);
    // Armijo's line search along `step`, no watched pair crossing over (by more than half the
    // thickness, which the penalty then pushes back: a penalty alone can be outweighed by a
    // large step). Returns the step length taken, 0 when none lowers the energy.
    const auto search = [&](Eigen::VectorXd& step) {
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
      for (int k = 0; k < 30; ++k, alpha *= 0.5)
      {
        moveFree(trial, x, step, alpha, free_index);
        if (contact_.worstGap(trial) < std::min(0.0, worst_gap) - 0.5 * contact_.thickness())
          continue;
        if (energy(trial, {}) <= e + 1e-4 * alpha * slope)
        {
          std::swap(x, trial);
          return alpha;
        }
      }
      return 0.0;
    };
    if (!refresh)
    {
      Eigen::VectorXd step = factorization_.solve(-g);
      const double alpha = search(step);
      refresh = alpha < 1.0;
      if (alpha > 0)
        continue;
    }
    // A fresh exact Hessian, factorised.
    refresh = false;
    e = assembleHessian(x, free_index, free_count, g);
    if (mu < 0)
      mu = options_.damping * g.norm() / mesh_.spacing;
    double last_alpha = 0;
    // The Hessian is exact and may be indefinite away from balance: the damping rises until
    // the shifted matrix is positive definite and its step lowers the energy.
    for (int attempt = 0; attempt < 30 && last_alpha == 0; ++attempt)
    {
      if (attempt > 0)
        mu *= 10;
      ++report.factorizations;
      if (!factorization_.factorize(hessian_, mu))
        continue;
      factor_free_ = free_index;
      Eigen::VectorXd step = factorization_.solve(-g);
      last_alpha = search(step);
    }
    if (last_alpha == 0)
    {
      stuck = "no step lowers the energy any further";
      break;
    }
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

double CurvedSolver::assembleHessian(const Positions& x, const std::vector<int>& free_index, int free_count,
                                     Eigen::VectorXd& g)
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
    const double e = energy(x, { &free_index, &g, nullptr, &blocks });
    if (blocks.missing == 0)
      return e;
    if (round > 0)
      throw std::logic_error("curved solver: a Hessian block outside the terms and contacts");
    const std::vector<std::array<int, 4>> contacts = contact_.pairNodes();
    pattern_groups_.insert(pattern_groups_.end(), contacts.begin(), contacts.end());
    hessian_ = blockPattern(free_count, free_index, pattern_groups_);
  }
}

CurvedReport CurvedSolver::rk4(Positions& x, const std::vector<int>& free_index, int free_count)
{
  CurvedReport report;
  const SolveBudget budget(budgetLimits(options_, options_.max_steps));
  const double force_scale = material_.stretch * mesh_.spacing;
  const int n = 3 * free_count;
  Eigen::VectorXd inv_mass(n);
  for (size_t v = 0; v < free_index.size(); ++v)
    if (free_index[v] >= 0)
      inv_mass.segment<3>(3 * free_index[v]).setConstant(1.0 / terms_.mass[v]);

  contact_.update(x);
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
    contact_.update(x);
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
