#include "virtual_origami/core/answer_budget.h"

#include <algorithm>
#include <cmath>

namespace virtual_origami::core
{
namespace
{
/// How far a smaller figure moves the expectation: a spell of quick answers lowers it within
/// a few frames, a single one by a quarter of the difference.
constexpr double kFallRate = 0.25;
}  // namespace

AnswerBudget::AnswerBudget(double answer_seconds, double min_solve_seconds)
  : answer_seconds_(answer_seconds), min_solve_seconds_(min_solve_seconds)
{}

void AnswerBudget::setAnswerSeconds(double seconds)
{
  answer_seconds_ = seconds;
}

double AnswerBudget::expectedAfterSolve(size_t vertices) const
{
  return measured_ && vertices == vertices_ ? after_solve_ : 0.0;
}

double AnswerBudget::solveSeconds(double elapsed, size_t vertices) const
{
  const double left = answer_seconds_ - std::max(0.0, elapsed) - expectedAfterSolve(vertices);
  return std::isfinite(left) ? std::max(min_solve_seconds_, left) : min_solve_seconds_;
}

void AnswerBudget::record(double before, double solve, double total, size_t vertices)
{
  if (!std::isfinite(before) || !std::isfinite(solve) || !std::isfinite(total))
    return;
  const double measured = std::max(0.0, total - std::max(0.0, before) - std::max(0.0, solve));
  if (!measured_ || vertices != vertices_)
  {
    measured_ = true;
    vertices_ = vertices;
    after_solve_ = measured;
    return;
  }
  after_solve_ = measured >= after_solve_ ? measured : after_solve_ + kFallRate * (measured - after_solve_);
}

}  // namespace virtual_origami::core
