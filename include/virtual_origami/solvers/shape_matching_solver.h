// Projective dynamics with one rigid shape-matching constraint per face: alternate fitting
// each face's rotation (local) and placing the vertices closest to every fitted face at
// once (global, a constant sparse system factored once per solve).
#pragma once

#include <string>
#include <vector>

#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
struct ShapeMatchingOptions
{
  /// Weight of a proximal pull towards the previous iterate: keeps the global system regular
  /// when a part of the model touches no held vertex; the fixed point is unchanged.
  double proximal = 1e-8;
  /// Anderson acceleration over this many past iterates (0: plain local/global).
  int anderson = 5;
};

class ShapeMatchingSolver : public ShapeSolver
{
public:
  explicit ShapeMatchingSolver(ShapeMatchingOptions options = {});
  std::string name() const override
  {
    return "shape_matching";
  }
  SolveReport solve(Paper& paper, const std::vector<char>& fixed) override;

private:
  ShapeMatchingOptions options_;
};

}  // namespace virtual_origami::core
