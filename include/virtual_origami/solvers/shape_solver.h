// The interface every rigid-face solver implements: restore face shapes around held vertices.
#pragma once

#include <string>
#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami
{
struct SolveReport
{
  bool converged = false;
  bool diverged = false;  // NaN or growing energy: the caller must roll back
  int iterations = 0;
  double max_strain = 0.0;
  std::string message;
};

class ShapeSolver
{
public:
  virtual ~ShapeSolver() = default;
  virtual std::string name() const = 0;
  /// Moves the vertices not in `fixed` (one flag per vertex) so that every face regains
  /// its crease-pattern shape. May leave `paper` anywhere when it reports divergence.
  virtual SolveReport solve(Paper& paper, const std::vector<char>& fixed) = 0;
};

}  // namespace virtual_origami
