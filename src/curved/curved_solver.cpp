#include "virtual_origami/curved/curved_solver.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/SparseCholesky>

#include "virtual_origami/solvers/solve_budget.h"

namespace virtual_origami::core
{
namespace
{
using SparseMatrix = Eigen::SparseMatrix<double>;

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

bool samePattern(const SparseMatrix& a, const SparseMatrix& b)
{
  return a.rows() == b.rows() && a.nonZeros() == b.nonZeros() &&
         std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
}

/// SolveLimits for the shared budget: the iteration cap is checked by the caller.
SolveLimits budgetLimits(const CurvedSolveOptions& options, int max_iterations)
{
  SolveLimits limits;
  limits.max_iterations = max_iterations;
  limits.max_seconds = options.max_seconds;
  return limits;
}
}  // namespace

CurvedSolver::CurvedSolver(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material,
                           const ContactOptions& contact, const CurvedSolveOptions& options)
  : mesh_(mesh)
  , material_(material)
  , terms_(curvedTerms(mesh, paper, material))
  , contact_(mesh, paper, material, contact)
  , options_(options)
{
}

double CurvedSolver::energy(const Positions& x, const Assembly& out, CurvedEnergy* parts, double* contact) const
{
  const CurvedEnergy e = evaluateCurved(terms_, x, out);
  const double c = contact_.evaluate(x, out);
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
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd g(n);
  Eigen::SimplicialLDLT<SparseMatrix>& solver = factorization_;
  std::string stuck;
  // Levenberg–Marquardt damping: starts in proportion to the force, falls while full steps
  // succeed (towards Newton's quadratic convergence), rises when they are cut back.
  double mu = 0.0;
  while (true)
  {
    contact_.update(x);
    g.setZero();
    triplets.clear();
    const double e = energy(x, { &free_index, &g, &triplets }, &report.energy, &report.contact_energy);
    report.max_force = largestNodeForce(g) / force_scale;
    if (!std::isfinite(e) || !std::isfinite(report.max_force))
    {
      report.diverged = true;
      report.message = "non-finite energy; rolled back";
      break;
    }
    if (report.max_force <= options_.tolerance)
    {
      report.converged = true;
      break;
    }
    if (budget.exhausted(report.iterations))
      break;
    ++report.iterations;
    SparseMatrix hessian(n, n);
    hessian.setFromTriplets(triplets.begin(), triplets.end());
    if (report.iterations == 1)
      mu = options_.damping * g.norm() / mesh_.spacing;
    double last_alpha = 0;
    const double worst_gap = contact_.worstGap(x);
    bool accepted = false;
    // The Hessian is exact and may be indefinite away from balance: the damping rises until
    // the shifted matrix is positive definite and its step lowers the energy.
    for (int attempt = 0; attempt < 30 && !accepted; ++attempt)
    {
      if (attempt > 0)
        mu *= 10;
      SparseMatrix damped = hessian;
      for (int i = 0; i < n; ++i)
        damped.coeffRef(i, i) += mu;
      // The ordering and elimination tree depend on the pattern alone, which changes only
      // when contact pairs come or go: analyse it once, then only factorise.
      if (!samePattern(damped, pattern_))
      {
        solver.analyzePattern(damped);
        pattern_ = damped;
      }
      solver.factorize(damped);
      if (solver.info() != Eigen::Success || !(solver.vectorD().minCoeff() > 0))
        continue;
      Eigen::VectorXd step = solver.solve(-g);
      double longest = 0.0;
      for (int i = 0; i < free_count; ++i)
        longest = std::max(longest, step.segment<3>(3 * i).norm());
      if (!std::isfinite(longest))
        continue;
      if (longest > max_move)
        step *= max_move / longest;
      const double slope = g.dot(step);
      if (!(slope < 0))
        continue;
      double alpha = 1.0;
      for (int k = 0; k < 30; ++k, alpha *= 0.5)
      {
        moveFree(trial, x, step, alpha, free_index);
        // A penalty alone can be outweighed by a large step: no watched pair may cross over
        // (by more than half the thickness, which the penalty then pushes back).
        if (contact_.worstGap(trial) < std::min(0.0, worst_gap) - 0.5 * contact_.thickness())
          continue;
        if (energy(trial, {}) <= e + 1e-4 * alpha * slope)
        {
          std::swap(x, trial);
          last_alpha = alpha;
          accepted = true;
          break;
        }
      }
    }
    if (!accepted)
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
    report.max_force = largestNodeForce(g) / force_scale;
    if (!std::isfinite(report.max_force))
    {
      report.diverged = true;
      report.message = "rk4 produced non-finite forces; rolled back";
      break;
    }
    if (report.max_force <= options_.tolerance)
    {
      report.converged = true;
      break;
    }
    if (budget.exhausted(report.iterations))
      break;
    ++report.iterations;
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
