#include "virtual_origami/solvers/crease_driver_factory.h"

#include "virtual_origami/solvers/quasi_newton_driver.h"

namespace virtual_origami::core
{
std::unique_ptr<CreaseDriver> makeCreaseDriver(const std::string& name)
{
  QuasiNewtonOptions options;
  if (name == "quasi_newton")
    options.hessian = DriverHessian::Lagged;
  else if (name == "newton")
    options.hessian = DriverHessian::Exact;
  else if (name == "constant_lbfgs")
    options.hessian = DriverHessian::Constant;
  else
    return nullptr;
  return std::make_unique<QuasiNewtonDriver>(options);
}

std::vector<std::string> creaseDriverNames()
{
  return { "quasi_newton", "newton", "constant_lbfgs" };
}

}  // namespace virtual_origami::core
