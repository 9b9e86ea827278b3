// Crease drivers by name, for fold by assignment (nodes and benchmarks pick one by parameter).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "virtual_origami/core/assignment_fold.h"

namespace virtual_origami::core
{
/// "quasi_newton" (the default), "newton" (the exact reference) or "constant_lbfgs" (a matrix
/// that never changes, for comparison); nullptr for any other name.
std::unique_ptr<CreaseDriver> makeCreaseDriver(const std::string& name = "quasi_newton");

std::vector<std::string> creaseDriverNames();

}  // namespace virtual_origami::core
