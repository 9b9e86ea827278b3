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

/// What a driver's calls go on from (QuasiNewtonDriver::Setup's last frames), and the set-up
/// they were made on.
struct QuasiNewtonDriver::Frames
{
  const Setup* made_on = nullptr;
  Positions last, before_last, last_start;
  std::vector<double> last_target, before_last_target;
  bool last_balanced = true;
  bool last_continued = false;
  double last_face_energy = 0.0;
  double frame_step = 1.0;
  int frame_first_trials = 0;
};

void QuasiNewtonDriver::setFramesAside()
{
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!setup_)
    return;
  Setup& setup = *setup_;
  Frames now{ &setup,
              std::move(setup.last),
              std::move(setup.before_last),
              std::move(setup.last_start),
              std::move(setup.last_target),
              std::move(setup.before_last_target),
              setup.last_balanced,
              setup.last_continued,
              setup.last_face_energy,
              setup.frame_step,
              setup.frame_first_trials };
  if (!aside_)
    aside_ = std::make_unique<Frames>(std::move(now));
  const Frames none;
  setup.last = setup.before_last = setup.last_start = setup.prepared_start = Positions();
  setup.last_target.clear();
  setup.before_last_target.clear();
  setup.last_balanced = none.last_balanced;
  setup.last_continued = none.last_continued;
  setup.last_face_energy = none.last_face_energy;
  setup.frame_step = none.frame_step;
  setup.frame_first_trials = none.frame_first_trials;
  setup.gauss_newton.reset();
  setup.factor_frames.clear();
}

void QuasiNewtonDriver::putFramesBack()
{
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!aside_)
    return;
  std::unique_ptr<Frames> frames = std::move(aside_);
  if (!setup_ || setup_.get() != frames->made_on)
    return;  // a new set-up since (another pattern): the frames were of the old one
  Setup& setup = *setup_;
  setup.last = std::move(frames->last);
  setup.before_last = std::move(frames->before_last);
  setup.last_start = std::move(frames->last_start);
  setup.last_target = std::move(frames->last_target);
  setup.before_last_target = std::move(frames->before_last_target);
  setup.last_balanced = frames->last_balanced;
  setup.last_continued = frames->last_continued;
  setup.last_face_energy = frames->last_face_energy;
  setup.frame_step = frames->frame_step;
  setup.frame_first_trials = frames->frame_first_trials;
}

}  // namespace virtual_origami::core
