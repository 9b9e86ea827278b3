// The newton solver keeps its last two set-ups (a turn's held face beside a fold's closure around
// none) and can be readied ahead of a solve (ShapeSolver::prepare): solves around alternating held
// vertices end exactly where a fresh solver's end.
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/newton_solver.h"

namespace virtual_origami::core
{
namespace
{
Paper perturbedMiura(unsigned seed)
{
  Paper paper = miuraTessellationFolded(5, 5, 1.0, 1.0, 1.1, 1.0).value().paper;
  std::srand(seed);
  std::vector<char> corner(paper.vertices.size(), 0);
  for (int v : paper.faces.front().vertices)
    corner[v] = 1;
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    if (!corner[v])  // the corner face is held by some solves: it keeps its shape
      paper.vertices[v].folded += 1e-3 * paper.scale() * Vec3::Random();
  return paper;
}

SolveLimits exactLimits()
{
  SolveLimits limits;
  limits.tolerance = 1e-10;  // spring_solver's
  limits.max_iterations = 200;
  return limits;
}

TEST(NewtonSetups, SolvesAroundAlternatingHeldVerticesEndWhereAFreshSolversEnd)
{
  const Paper shape = perturbedMiura(3);
  std::vector<char> corner(shape.vertices.size(), 0), none(shape.vertices.size(), 0);
  for (int v : shape.faces.front().vertices)
    corner[v] = 1;
  NewtonSolver kept;
  kept.setLimits(exactLimits());
  kept.prepare(shape, none);
  for (int round = 0; round < 3; ++round)
    for (const std::vector<char>* held : { &corner, &none })
    {
      Paper by_kept = perturbedMiura(10 + round), by_fresh = by_kept;
      NewtonSolver fresh;
      fresh.setLimits(exactLimits());
      const SolveReport a = kept.solve(by_kept, *held);
      const SolveReport b = fresh.solve(by_fresh, *held);
      ASSERT_TRUE(a.converged) << a.message;
      ASSERT_TRUE(b.converged) << b.message;
      EXPECT_GT(a.iterations, 0);
      EXPECT_EQ(a.iterations, b.iterations);
      for (size_t v = 0; v < by_kept.vertices.size(); ++v)
        ASSERT_EQ(by_kept.vertices[v].folded, by_fresh.vertices[v].folded) << "round " << round << ", vertex " << v;
    }
}
}  // namespace
}  // namespace virtual_origami::core
