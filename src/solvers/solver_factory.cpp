#include "virtual_origami/solvers/solver_factory.h"

#include "virtual_origami/solvers/newton_solver.h"
#include "virtual_origami/solvers/rigid_kinematics_solver.h"
#include "virtual_origami/solvers/seed_spring_solver.h"
#include "virtual_origami/solvers/shape_matching_solver.h"

namespace virtual_origami::core
{
std::unique_ptr<ShapeSolver> makeSolver(const std::string& name)
{
  if (name == "seed_spring")
    return std::make_unique<SeedSpringSolver>();
  if (name == "shape_matching")
    return std::make_unique<ShapeMatchingSolver>();
  if (name == "newton")
    return std::make_unique<NewtonSolver>();
  if (name == "rigid_kinematics")
    return std::make_unique<RigidKinematicsSolver>();
  return nullptr;
}

std::vector<std::string> solverNames()
{
  return { "seed_spring", "shape_matching", "newton", "rigid_kinematics" };
}

}  // namespace virtual_origami::core
