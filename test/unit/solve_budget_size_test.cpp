// A solve's time budget by the paper's size (core::budgetForSize, what spring_solver and
// paper_model's wait for it use): as configured up to 10,000 vertices, beyond growing as a sparse
// factorisation of a sheet's mesh does (the vertices to the power 1.5), where a rigid closure's
// step takes longer than the whole configured budget.
#include <gtest/gtest.h>

#include <cmath>

#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
TEST(SolveBudgetSize, AsConfiguredUpToTenThousandVerticesAndAsAFactorisationGrowsBeyond)
{
  for (size_t vertices : { size_t(0), size_t(1), size_t(1681), size_t(10000) })
    EXPECT_EQ(budgetForSize(3.0, vertices), 3.0) << vertices << " vertices";
  EXPECT_DOUBLE_EQ(budgetForSize(3.0, 40000), 24.0);    // 3 · 4^1.5
  EXPECT_DOUBLE_EQ(budgetForSize(3.0, 100000), 3.0 * std::pow(10.0, 1.5));  // 95 s
  // Growing with the paper, never below what was configured.
  double last = 0.0;
  for (size_t vertices = 5000; vertices <= 200000; vertices += 5000)
  {
    const double budget = budgetForSize(3.0, vertices);
    EXPECT_GE(budget, 3.0);
    EXPECT_GE(budget, last);
    last = budget;
  }
  // No budget (0) stays none.
  EXPECT_EQ(budgetForSize(0.0, 100000), 0.0);
}

}  // namespace virtual_origami::core
