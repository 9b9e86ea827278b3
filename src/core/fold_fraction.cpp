#include "virtual_origami/core/fold_fraction.h"

#include <algorithm>
#include <cmath>

#include "virtual_origami/core/assignment_fold.h"

namespace virtual_origami::core
{
double foldFraction(const Paper& paper)
{
  const std::vector<double> targets = creaseTargets(paper);
  double fit = 0.0, norm = 0.0;
  for (size_t e = 0; e < targets.size(); ++e)
    if (std::isfinite(targets[e]))
    {
      fit += paper.edges[e].fold_angle * targets[e];
      norm += targets[e] * targets[e];
    }
  return norm > 0 ? std::clamp(fit / norm, -1.0, 1.0) : 0.0;
}

bool hasDrivenCreases(const Paper& paper)
{
  const std::vector<double> targets = creaseTargets(paper);
  return std::any_of(targets.begin(), targets.end(), [](double t) { return std::isfinite(t); });
}

}  // namespace virtual_origami::core
