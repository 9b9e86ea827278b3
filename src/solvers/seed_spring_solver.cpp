#include "virtual_origami/solvers/seed_spring_solver.h"

#include <cmath>
#include <sstream>

#include "virtual_origami/numerics/solve_budget.h"

namespace virtual_origami::core
{
namespace
{
/// Zeroes the columns of fixed vertices: they neither move nor take part in a mode.
void clearFixed(Positions& m, const std::vector<int>& free_index)
{
  for (Eigen::Index v = 0; v < m.cols(); ++v)
    if (free_index[v] < 0)
      m.col(v).setZero();
}
}  // namespace

double seedStabilityLimit(const SeedSpringOptions& options)
{
  return 2.0 * (1.0 + options.velocity_carry) / (options.d * options.dt * options.dt);
}

double springStiffnessMax(const Paper& paper, const std::vector<char>& fixed, int iterations)
{
  const std::vector<Spring> springs = faceSprings(paper);
  const Positions x = foldedPositions(paper);
  const std::vector<int> free_index = freeIndices(fixed, paper.vertices.size());
  // A fixed start vector (determinism) with a component along every free direction.
  Positions v(3, x.cols());
  for (Eigen::Index i = 0; i < v.size(); ++i)
    v.data()[i] = 1.0 + 0.1 * std::sin(1.7 * static_cast<double>(i));
  clearFixed(v, free_index);
  double lambda = 0.0;
  Positions hv;
  for (int k = 0; k < iterations && v.norm() > 0; ++k)
  {
    v.normalize();
    springHessianProduct(springs, x, v, hv);
    clearFixed(hv, free_index);
    lambda = v.cwiseProduct(hv).sum();
    v = hv;
  }
  return lambda;
}

SeedSpringSolver::SeedSpringSolver(SeedSpringOptions options) : options_(options)
{
  limits_.max_iterations = 200000;
}

SolveReport SeedSpringSolver::solve(Paper& paper, const std::vector<char>& fixed)
{
  numerics::SolveBudget budget(limits_);
  SolveReport report;
  const std::vector<Spring> springs = faceSprings(paper);  // re-wired from the current faces
  const std::vector<int> free_index = freeIndices(fixed, paper.vertices.size());
  const double d = options_.d, dt = options_.dt, carry = options_.velocity_carry;

  const Positions start = foldedPositions(paper);
  Positions x = start, v = Positions::Zero(3, x.cols()), force;
  SpringState state = evaluateSprings(springs, x, &force);
  clearFixed(force, free_index);
  const double reference = std::max(state.energy, 1e-20 * paper.scale() * paper.scale());
  double previous = state.energy;
  int rising = 0;
  std::string why_diverged;
  while (true)
  {
    if (state.max_strain <= limits_.tolerance)
    {
      report.converged = true;
      break;
    }
    if (budget.exhausted(report.iterations))
      break;
    // Eq. 3 then eq. 4 (m = 1, k = 1, D = 0, g = 0).
    v = carry * v + d * dt * force;
    x += dt * v;
    ++report.iterations;
    state = evaluateSprings(springs, x, &force);
    clearFixed(force, free_index);
    const double total = state.energy + (carry > 0 ? 0.5 * v.squaredNorm() / d : 0.0);
    rising = carry == 0 && total > previous ? rising + 1 : 0;
    previous = total;
    if (!std::isfinite(total))
      why_diverged = "the positions became non-finite";
    else if (total > options_.divergence_growth * reference)
      why_diverged = "the spring energy grew past " + std::to_string(options_.divergence_growth) + " times its start";
    else if (rising >= options_.rising_window)
      why_diverged = "the spring energy rose " + std::to_string(rising) + " iterations in a row";
    if (!why_diverged.empty())
      break;
  }
  report.seconds = budget.seconds();
  std::ostringstream msg;
  if (!why_diverged.empty())
  {
    // Roll back: a diverged shape is never published.
    setFoldedPositions(paper, start);
    report.diverged = true;
    report.max_strain = evaluateSprings(springs, start).max_strain;
    msg << "seed spring scheme diverged after " << report.iterations << " iterations (" << why_diverged
        << "); its stability limit is a stiffness eigenvalue below " << seedStabilityLimit(options_) << ", here it is "
        << springStiffnessMax(paper, fixed) << "; rolled back";
    report.message = msg.str();
    return report;
  }
  setFoldedPositions(paper, x);
  report.max_strain = state.max_strain;
  if (!report.converged)
  {
    msg << "stopped after " << report.iterations << " iterations at max strain " << report.max_strain << " (tolerance "
        << limits_.tolerance << ")";
    report.message = msg.str();
  }
  return report;
}

}  // namespace virtual_origami::core
