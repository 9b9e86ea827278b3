#include "virtual_origami/solvers/quasi_newton_driver.h"

#include "quasi_newton_drive_run.h"
#include "quasi_newton_setup.h"

namespace virtual_origami::core
{
QuasiNewtonDriver::QuasiNewtonDriver(QuasiNewtonOptions options)
  : options_(options)
  , analysis_(numerics::SpdFactorization::makeSharedAnalysis())
  , assembly_(std::make_shared<AssemblyPlan>())
{
  face_stiffness_ = options.face_stiffness;
  limits_.tolerance = 1e-9;
  limits_.max_iterations = 2000;
}

QuasiNewtonDriver::~QuasiNewtonDriver() = default;

std::string QuasiNewtonDriver::name() const
{
  switch (options_.hessian)
  {
    case DriverHessian::Constant:
      return "constant_lbfgs";
    case DriverHessian::Exact:
      return "newton";
    default:
      return "quasi_newton";
  }
}

std::unique_ptr<CreaseDriver> QuasiNewtonDriver::clone() const
{
  auto copy = std::make_unique<QuasiNewtonDriver>(options_);
  copy->analysis_ = analysis_;
  copy->assembly_ = assembly_;
  copy->setLimits(limits_);
  copy->setFaceStiffness(face_stiffness_);
  return copy;
}

SolveReport QuasiNewtonDriver::drive(Paper& paper, const std::vector<double>& target, const std::vector<char>& fixed)
{
  const std::lock_guard<std::mutex> lock(mutex_);
  return DriveRun(*this, paper, target, fixed).run();
}

void QuasiNewtonDriver::prepare(const Paper& paper, const std::vector<double>& target, const std::vector<char>& fixed)
{
  const std::lock_guard<std::mutex> lock(mutex_);
  Paper copy = paper;  // a call's run works on a paper; this one moves nothing
  DriveRun(*this, copy, target, fixed).prepareFirstFrame();
}

}  // namespace virtual_origami::core
