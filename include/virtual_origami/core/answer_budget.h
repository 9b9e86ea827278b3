// A preview's answer within a time budget: its solve gets what the rest of the answer leaves.
#pragma once

#include <cstddef>

namespace virtual_origami::core
{
/// The time budget of a whole answer (a fold slider's preview: the frame's solve, then its
/// figures, markers, publishing and the reply), shared out so that the answer, not the solve
/// alone, keeps to it. What an answer spends besides its solve is measured on the answers before
/// (they are alike: the same paper, one frame each) and kept back from the next solve's budget.
class AnswerBudget
{
public:
  /// `answer_seconds`: the whole answer's budget; `min_solve_seconds`: what a solve gets at the
  /// least (a frame must move, however late it starts).
  explicit AnswerBudget(double answer_seconds = 0.03, double min_solve_seconds = 0.001);

  void setAnswerSeconds(double seconds);
  double answerSeconds() const
  {
    return answer_seconds_;
  }

  /// The solve's budget when it starts `elapsed` seconds into an answer on a paper of `vertices`
  /// vertices: the answer's budget less the time gone and what the rest of the answer is
  /// expected to take after the solve; never below the minimum.
  double solveSeconds(double elapsed, size_t vertices) const;

  /// An answer done: the solve's budget was set `before` seconds into it, the solve took `solve`
  /// seconds, the whole answer `total`. What came after the solve is expected of the next: a
  /// larger figure at once (the next answer must not overrun as this one did), a smaller one
  /// gradually (one quick answer does not promise the next). A paper of another size starts
  /// the expectation again.
  void record(double before, double solve, double total, size_t vertices);

  /// What the rest of an answer on a paper of `vertices` vertices is expected to take after its
  /// solve (0 before any answer on a paper of that size).
  double expectedAfterSolve(size_t vertices) const;

private:
  double answer_seconds_;
  double min_solve_seconds_;
  double after_solve_ = 0.0;
  size_t vertices_ = 0;
  bool measured_ = false;
};

}  // namespace virtual_origami::core
