// What the crease-driver tests compare against: the closed-form state where the driver's crease
// springs balance, found by a one-dimensional search over a rigid family's parameter.
#pragma once

#include <cmath>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/driven_faces.h"

namespace virtual_origami::core::test
{
/// Golden-section minimum of a unimodal f on [a, b], to rounding.
template <class F>
double minimise(F f, double a, double b)
{
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double c = b - ratio * (b - a), d = a + ratio * (b - a);
  for (int k = 0; k < 200 && b - a > 1e-14; ++k)
  {
    if (f(c) < f(d))
      b = d;
    else
      a = c;
    c = b - ratio * (b - a);
    d = a + ratio * (b - a);
  }
  return (a + b) / 2;
}

/// The hinge weight of each edge as the drivers weigh it (0 where there is no hinge).
inline std::vector<double> hingeWeights(const Paper& paper)
{
  const DrivenFaces faces(paper, 1.0);
  std::vector<double> w(paper.edges.size(), 0.0);
  for (const Hinge& h : faces.hinges())
    w[h.edge] = h.weight;
  return w;
}

/// The straight-crease angle ρ in [0, rho_max] of the rigid Miura-ori (miuraFoldAngles) where
/// the driver's crease springs, pulled to `fraction` of their targets, balance: the rigid state
/// a commit should reach.
inline double miuraBalanceRho(const Tessellation& t, int columns, int rows, double gamma, double fraction,
                              double rho_max)
{
  const std::vector<double> w = hingeWeights(t.paper);
  const auto energy = [&](double rho) {
    const std::vector<double> angles = miuraFoldAngles(t.paper, columns, rows, gamma, rho);
    double sum = 0.0;
    for (size_t e = 0; e < angles.size(); ++e)
      if (t.paper.edges[e].isCrease())
        sum += w[e] * std::pow(angles[e] - fraction * t.target_fold_angle[e], 2);
    return sum;
  };
  return minimise(energy, 0.0, rho_max);
}
}  // namespace virtual_origami::core::test
