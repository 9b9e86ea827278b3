// Solvers by name, so nodes and tools can pick one by parameter.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
/// "seed_spring", "shape_matching", "newton", "rigid_kinematics"; nullptr for any other name.
std::unique_ptr<ShapeSolver> makeSolver(const std::string& name);

/// Every name makeSolver knows, baseline first.
std::vector<std::string> solverNames();

}  // namespace virtual_origami::core
