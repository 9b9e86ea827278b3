// The anytime stopping rule every solver shares: an iteration count and a wall-time budget.
#pragma once

#include <chrono>

#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::numerics
{
class SolveBudget
{
public:
  explicit SolveBudget(const core::SolveLimits& limits) : limits_(limits), start_(std::chrono::steady_clock::now())
  {}

  /// True once `iterations` reach the limit or the time budget is spent.
  bool exhausted(int iterations) const
  {
    if (iterations >= limits_.max_iterations)
      return true;
    return limits_.max_seconds > 0 && seconds() >= limits_.max_seconds;
  }

  double seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

private:
  core::SolveLimits limits_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace virtual_origami::numerics
