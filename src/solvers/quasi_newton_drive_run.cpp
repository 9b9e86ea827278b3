#include "quasi_newton_drive_run.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace virtual_origami::core
{
QuasiNewtonDriver::DriveRun::DriveRun(QuasiNewtonDriver& driver, Paper& paper, const std::vector<double>& target,
                                      const std::vector<char>& fixed)
  : driver_(driver)
  , options_(driver.options_)
  , limits_(driver.limits_)
  , budget_(limits_)
  , setup_(prepare(driver, paper, target, fixed))
  , energy_(setup_.energy)
  , paper_(paper)
  , target_(target)
  , fixed_(fixed)
  , free_(setup_.free_vertices)
  , history_(options_.memory)
{
  energy_.setTargets(target);
  std::vector<double> reference(paper.edges.size());
  for (size_t e = 0; e < paper.edges.size(); ++e)
    reference[e] = paper.edges[e].fold_angle;
  energy_.setReference(reference);
  start_ = foldedPositions(paper);
  scale_ = energy_.scale();
  x_ = start_ / scale_;
}

QuasiNewtonDriver::Setup& QuasiNewtonDriver::DriveRun::prepare(QuasiNewtonDriver& driver, const Paper& paper,
                                                               const std::vector<double>& target,
                                                               const std::vector<char>& fixed)
{
  std::unique_ptr<Setup>& setup = driver.setup_;
  if (!setup || !setup->matches(paper, fixed, target) || setup->energy.faceStiffness() != driver.face_stiffness_)
    setup = std::make_unique<Setup>(paper, fixed, target, driver.face_stiffness_, driver.analysis_);
  return *setup;
}

SolveReport QuasiNewtonDriver::DriveRun::run()
{
  if (nothingToSolve())
    return unsolved();
  planFrame();
  start();
  while (!diverged_ && iterate())
  {}
  // Stopped by its limits short of balance (a preview frame): the last step was linear along
  // turning faces.
  if (options_.restore_final_faces && stopped_by_limits_ && !diverged_ && !report_.converged)
    restoreFinalFaces();
  return finish();
}

/// The constant matrix factorised and, for a lagged driver without a kept factorisation, the
/// Gauss–Newton matrix at the paper's state, as a first frame's refresh would make it (its
/// faces' frames recorded for refactor_turn). A kept factorisation stays: the frames going on
/// from it are the driver's own. The energy pass a budgeted frame's line search is planned by is
/// timed too.
void QuasiNewtonDriver::DriveRun::prepareFirstFrame()
{
  if (free_.empty())
    return;
  setup_.factorConstant();
  if (options_.hessian != DriverHessian::Lagged || setup_.gauss_newton.valid())
    return;
  anchored_ = std::any_of(fixed_.begin(), fixed_.end(), [](char c) { return c != 0; });
  if (!refactor())
    return;
  setup_.factor_frames = energy_.linearize(x_).frame;
  setup_.prepared_start = start_;
  const double evaluate_from = budget_.seconds();
  energy_.evaluate(x_, &gradient_);
  setup_.evaluate_seconds = budget_.seconds() - evaluate_from;
}

/// Every vertex held, or a constant driver whose matrix is not definite (it is factorised here,
/// at its first use, and counted).
bool QuasiNewtonDriver::DriveRun::nothingToSolve()
{
  const bool constant_unfactored = !setup_.constant_tried;
  const bool constant_refused =
      !free_.empty() && options_.hessian == DriverHessian::Constant && !setup_.factorConstant();
  report_.factorizations += constant_unfactored && setup_.constant_tried ? 1 : 0;
  return free_.empty() || constant_refused;
}

SolveReport QuasiNewtonDriver::DriveRun::unsolved()
{
  report_.max_strain = springStrain(setup_.springs, start_).max;
  report_.converged = free_.empty();
  report_.message = free_.empty() ? "every vertex is held" : "the constant matrix is not definite";
  report_.seconds = budget_.seconds();
  return report_;
}

void QuasiNewtonDriver::DriveRun::planFrame()
{
  anchored_ = std::any_of(fixed_.begin(), fixed_.end(), [](char c) { return c != 0; });
  continues_ = setup_.last.cols() == x_.cols() && setup_.last == start_;
  const bool motion_known = setup_.last_start.cols() == x_.cols() && setup_.last_start != setup_.last;
  // The set-up's first frame is the same whether prepare made its factorisation or it makes it
  // itself (a subspace frame without a motion to go by lags the slide after it).
  first_frame_ = setup_.last.cols() == 0;
  subspace_frame_ = options_.hessian == DriverHessian::Lagged && options_.subspace_frames && !first_frame_ &&
                    (motion_known || setup_.gauss_newton.valid()) && limits_.max_seconds > 0 &&
                    limits_.max_seconds < options_.subspace_below_seconds;
  predicts_ = options_.predict && !subspace_frame_ && continues_ && setup_.last_continued &&
              setup_.before_last.cols() == x_.cols() && setup_.last_target.size() == target_.size();
  exact_allowed_ = options_.exact_hessian && !subspace_frame_;
  // A subspace frame that starts a slide goes by the last motion this driver made elsewhere on
  // the pattern: the mechanism turns much the same way there, and the Galerkin step says how far.
  if ((continues_ || subspace_frame_) && setup_.last_start.cols() == x_.cols())
    motion_ = gather(setup_.last - setup_.last_start) / scale_;
}

/// The energy where the frame starts: a prediction needs only its value, whose face term is
/// the last frame's (the same positions); the full pass (with the gradient) is paid for only
/// where the frame goes on from there.
void QuasiNewtonDriver::DriveRun::start()
{
  if (predicts_)
  {
    now_.face_energy = setup_.last_face_energy;
    now_.hinge_energy = energy_.hingeEnergy(x_);
    now_.energy = now_.face_energy + now_.hinge_energy;
    predict();
  }
  else
    evaluateStart();
  if (!start_evaluated_)
    evaluateStart();
  // A first frame takes prepare's factorisation only where it was made at this very state.
  const bool prepared_here =
      first_frame_ && setup_.prepared_start.cols() == x_.cols() && setup_.prepared_start == start_;
  refresh_ =
      !subspace_frame_ && options_.hessian != DriverHessian::Constant &&
      (options_.hessian == DriverHessian::Exact || !setup_.gauss_newton.valid() || (first_frame_ && !prepared_here));
  g_ = gather(gradient_);
  spread_ = Positions::Zero(3, x_.cols());
  diverged_ = !std::isfinite(now_.energy);
  if (options_.restore_final_faces && limits_.max_seconds > 0)
    final_reserve_ = setup_.restore_seconds;
}

void QuasiNewtonDriver::DriveRun::evaluateStart()
{
  const double evaluate_from = budget_.seconds();
  now_ = energy_.evaluate(x_, &gradient_, subspace_frame_ ? &start_linearization_ : nullptr);
  start_linearized_ = subspace_frame_;
  evaluate_seconds_ = budget_.seconds() - evaluate_from;
  // The line search's passes do not linearise: budget them as the last plain pass took.
  if (subspace_frame_ && setup_.evaluate_seconds > 0)
    evaluate_seconds_ = setup_.evaluate_seconds;
  start_evaluated_ = true;
}

/// The last two frames' motion carried on, as far as the targets moved against theirs (at most
/// twice), where it lowers the energy.
void QuasiNewtonDriver::DriveRun::predict()
{
  double step_now = 0.0, step_before = 0.0;
  for (size_t e = 0; e < target_.size(); ++e)
    if (driven(target_[e]) && driven(setup_.last_target[e]) && driven(setup_.before_last_target[e]))
    {
      step_now += std::pow(target_[e] - setup_.last_target[e], 2);
      step_before += std::pow(setup_.last_target[e] - setup_.before_last_target[e], 2);
    }
  if (!(step_before > 0))
    return;
  const double ratio = std::min(2.0, std::sqrt(step_now / step_before));
  Positions predicted = x_ + (ratio / scale_) * (setup_.last - setup_.before_last);
  for (size_t v = 0; v < setup_.free_index.size(); ++v)
    if (setup_.free_index[v] < 0)
      predicted.col(static_cast<Eigen::Index>(v)) = x_.col(static_cast<Eigen::Index>(v));
  Positions predicted_gradient;
  const double evaluate_from = budget_.seconds();
  DrivenFaces::Evaluation guess = energy_.evaluate(predicted, &predicted_gradient);
  evaluate_seconds_ = budget_.seconds() - evaluate_from;
  // Carried on straight, every turning face stretches by about half its turn squared (a
  // 1 % step of a Miura-ori: 5e-4). Where that costs more than the step gains (a large
  // sheet), or where the last frame ran out of budget before balance (a slide's frames: the
  // strain they keep would pile up), one step of the constant matrix (rotations fitted, the
  // faces' shapes restored) takes it out for about one back-substitution. Not otherwise: a
  // frame solved to balance starts better from the straight prediction.
  if (options_.restore_predicted_faces && (!(guess.energy < now_.energy) || !setup_.last_balanced))
    restoreFaces(predicted, predicted_gradient, guess);
  if (guess.energy < now_.energy)
  {
    x_ = std::move(predicted);
    gradient_ = std::move(predicted_gradient);
    now_ = guess;
    start_evaluated_ = true;
  }
}

/// One iteration: a direction, a line search along it, the step taken. False when the frame
/// ends (balanced, out of budget, or stuck).
bool QuasiNewtonDriver::DriveRun::iterate()
{
  // Out of budget: stop before paying for a direction. A direction once paid for is taken
  // (the first always: a frame must move), even when computing it spent the budget.
  if ((budget_.exhausted(report_.iterations) && (report_.iterations > 0 || limits_.max_iterations <= 0)) ||
      (report_.iterations > 0 && !fits(solve_seconds_ + evaluate_seconds_)))
  {
    stopped_by_limits_ = true;
    return false;
  }
  if (refresh_)
  {
    refresh_ = false;
    frames_pending_ = true;
    refactorAfresh();
  }
  Eigen::MatrixX3d step = direction();
  const RigidMotions* drift = step_rigid_ ? &*step_rigid_ : (frame_rigid_ ? &*frame_rigid_ : nullptr);
  if (drift)
    drift->remove(step);
  // Balanced when the step the model predicts moves nothing measurably. A Newton–Krylov step
  // the budget cut short (one or two iterations on a matrix kept from another state) can be
  // small far from balance: it does not tell.
  const double step_size = step.cwiseAbs().maxCoeff();
  // Newton steps on the energy's own Hessian that stopped shrinking within ten times the
  // tolerance: a degenerate balance (the Hessian singular along a mechanism there, where
  // Newton only halves its distance per step) or the rounding floor. Balanced as far as it goes.
  const double tolerance = limits_.tolerance;
  const bool stalled = exact_products_ && step_size <= 10 * tolerance && step_size >= 0.5 * last_step_;
  if ((step_size <= tolerance || stalled) && !krylov_cut_)
  {
    report_.converged = true;
    return false;
  }
  ++report_.iterations;
  double slope = 0.0;
  if (!descends(step, slope, drift))
  {
    stuck_ = "no descent direction";
    return false;
  }
  const Trial trial = lineSearch(step, slope);
  if (!trial.accepted)
  {
    // A fresh matrix may still find a way down.
    if (options_.hessian == DriverHessian::Lagged && !subspace_frame_ && !history_.empty())
    {
      refresh_ = true;
      return true;
    }
    // Within a hundred times the tolerance the rest is rounding: balanced as far as it goes.
    report_.converged = step_size <= 100 * tolerance;
    stuck_ = "no step lowers the energy any further";
    return false;
  }
  take(step, trial, step_size);
  return true;
}

/// The step the frame's kind of driver proposes at x (before the rigid motions are cleared).
Eigen::MatrixX3d QuasiNewtonDriver::DriveRun::direction()
{
  if (subspace_frame_ && !anchored_ && !frame_rigid_)
    frame_rigid_.emplace(x_, free_);
  step_rigid_.reset();
  if (!anchored_ && !subspace_frame_)
    step_rigid_.emplace(x_, free_);
  const RigidMotions* rigid = step_rigid_ ? &*step_rigid_ : nullptr;
  if (subspace_frame_)
  {
    if (!start_linearized_)
      start_linearization_ = energy_.linearize(x_);
    start_linearized_ = false;  // x moves on
    return subspaceStep(start_linearization_, frame_rigid_ ? &*frame_rigid_ : nullptr);
  }
  if (options_.hessian != DriverHessian::Lagged)
    return lbfgsStep();
  const DrivenFaces::Linearization linearization = energy_.linearize(x_);
  if (frames_pending_)
  {
    setup_.factor_frames = linearization.frame;
    frames_pending_ = false;
  }
  else if (options_.refactor_turn > 0 && setup_.gauss_newton.valid() && roomForFactor() &&
           turnedSinceFactor(linearization) > options_.refactor_turn)
  {
    refactorAfresh();
    setup_.factor_frames = linearization.frame;
  }
  Eigen::MatrixX3d step = newtonKrylovStep(linearization, rigid);
  if (options_.follow_motion && motion_.size() > 0)
    followMotion(linearization, rigid, step);
  return step;
}

/// Whether `direction` descends (its slope along the gradient below 0); where it does not, the
/// curvature pairs have gone stale and the matrix's own step is tried instead.
bool QuasiNewtonDriver::DriveRun::descends(Eigen::MatrixX3d& direction, double& slope, const RigidMotions* drift)
{
  slope = numerics::innerProduct(g_, direction);
  if (slope < 0)
    return true;
  history_.clear();
  direction = -precondition(g_);
  if (drift)
    drift->remove(direction);
  slope = numerics::innerProduct(g_, direction);
  return slope < 0;
}

/// Backtracking (Armijo) along `direction`; near balance, the full step where it leaves a
/// smaller gradient.
QuasiNewtonDriver::DriveRun::Trial QuasiNewtonDriver::DriveRun::lineSearch(const Eigen::MatrixX3d& direction,
                                                                           double slope)
{
  Trial out;
  const bool remember = options_.remember_frame_step && subspace_frame_;
  if (remember)
    out.step_length = setup_.frame_step;
  for (int k = 0; k < options_.max_line_search; ++k, out.step_length *= 0.5)
  {
    trial_ = x_;
    moveFree(trial_, out.step_length, direction);
    const double evaluate_from = budget_.seconds();
    out.energy = energy_.evaluate(trial_, &trial_gradient_);
    setup_.evaluate_seconds = budget_.seconds() - evaluate_from;
    if (out.energy.energy <= now_.energy + options_.armijo * out.step_length * slope)
    {
      out.accepted = true;
      if (remember)
        rememberFrameStep(k, out.step_length);
      return out;
    }
    // A long linear step along turning faces stretches them (by about half the turn squared)
    // and fails on that alone: with the faces restored it may still be the step to take. So
    // too in a subspace frame: a 10,000-vertex slide in 5 % steps took a quarter of each step
    // and its previews fell behind the handle (the last, at 100 %, fitted 70–85 %).
    if (options_.restore_trial_faces)
    {
      restoreFaces(trial_, trial_gradient_, out.energy);
      if (out.energy.energy <= now_.energy + options_.armijo * out.step_length * slope)
      {
        out.accepted = true;
        out.restored = true;
        if (remember)
          rememberFrameStep(k, out.step_length);
        return out;
      }
    }
  }
  // Near balance the energy's change drowns in its rounding; the gradient still tells:
  // take the full step when it leaves a smaller gradient.
  trial_ = x_;
  moveFree(trial_, 1.0, direction);
  out.energy = energy_.evaluate(trial_, &trial_gradient_);
  const double rounding = 1e-12 * std::max(1.0, std::abs(now_.energy));
  if (out.energy.energy <= now_.energy + rounding && gather(trial_gradient_).norm() < g_.norm())
  {
    out.accepted = true;
    out.step_length = 1.0;
  }
  return out;
}

/// A subspace frame's line search took `length` at its trial `k` (0: the first): the next frame
/// starts there, and back towards the whole step after frames that took their first trial.
void QuasiNewtonDriver::DriveRun::rememberFrameStep(int k, double length)
{
  if (k > 0)
  {
    setup_.frame_step = length;
    setup_.frame_first_trials = 0;
  }
  else if (++setup_.frame_first_trials >= options_.frame_step_growth_frames && setup_.frame_step < 1.0)
  {
    setup_.frame_step = std::min(1.0, 2.0 * setup_.frame_step);
    setup_.frame_first_trials = 0;
  }
}

/// Moves to the accepted trial: the curvature pair recorded, and whether to factorise afresh or
/// go on to the energy's own Hessian decided from how the step went.
void QuasiNewtonDriver::DriveRun::take(const Eigen::MatrixX3d& direction, const Trial& trial, double step_size)
{
  const Eigen::MatrixX3d g_next = gather(trial_gradient_);
  Eigen::MatrixX3d step =
      trial.restored ? Eigen::MatrixX3d(gather(trial_ - x_)) : Eigen::MatrixX3d(trial.step_length * direction);
  if (options_.hessian != DriverHessian::Exact)
    history_.add(std::move(step), g_next - g_);
  // The kept matrix pays while the steps shrink fast; when they stop, factor afresh. Not
  // for slow conjugate gradients in a Newton step that shrank the step a hundredfold: the
  // next step, converging quadratically, is the last or nearly.
  const bool room = roomForFactor();
  const bool quadratic = exact_products_ && step_size < 0.01 * last_step_;
  if (options_.hessian == DriverHessian::Exact ||
      (options_.hessian == DriverHessian::Lagged && room && !subspace_frame_ &&
       ((krylov_slow_ && !quadratic) || (!exact_products_ && step_size > options_.refresh_ratio * last_step_))))
    refresh_ = true;
  const bool whole = trial.step_length == 1.0 && !trial.restored;
  last_restored_ = trial.restored;
  if (exact_products_ && !whole)
    exact_refused_ = true;
  exact_products_ = exact_allowed_ && !exact_refused_ && whole && last_whole_ && step_size < 0.5 * last_step_;
  last_whole_ = whole;
  last_step_ = step_size;
  std::swap(x_, trial_);
  g_ = g_next;
  now_ = trial.energy;
  diverged_ = !std::isfinite(now_.energy);
}

void QuasiNewtonDriver::DriveRun::restoreFinalFaces()
{
  Positions x_gradient = Positions::Zero(3, x_.cols());
  for (size_t i = 0; i < free_.size(); ++i)
    x_gradient.col(free_[i]) = g_.row(static_cast<Eigen::Index>(i)).transpose();
  // A last step taken with its faces restored has had that step already.
  if (!last_restored_)
    restoreFaces(x_, x_gradient, now_);
  // A subspace frame that still shows strain above `restore_strain` (a slide's second frame,
  // whose motion to follow came from a frame without one) restores once more.
  if (subspace_frame_ && springStrain(setup_.springs, x_ * scale_).max > options_.restore_strain)
    restoreFaces(x_, x_gradient, now_);
}

/// The paper set to the result (or rolled back where it diverged), the report completed, and
/// the frame kept for the next one's prediction.
SolveReport QuasiNewtonDriver::DriveRun::finish()
{
  report_.seconds = budget_.seconds();
  if (diverged_)
  {
    setFoldedPositions(paper_, start_);
    report_.diverged = true;
    report_.max_strain = springStrain(setup_.springs, start_).max;
    report_.message = driver_.name() + " produced non-finite positions; rolled back";
    return report_;
  }
  const Positions result = x_ * scale_;
  setFoldedPositions(paper_, result);
  report_.max_strain = springStrain(setup_.springs, result).max;
  if (!report_.converged)
    report_.message = stuck_.empty() ? "stopped before balance" : stuck_;
  setup_.before_last = setup_.last;
  setup_.before_last_target = setup_.last_target;
  setup_.last_start = start_;
  setup_.last = result;
  setup_.last_target = target_;
  setup_.last_continued = continues_;
  setup_.last_face_energy = now_.face_energy;
  setup_.last_balanced = report_.converged;
  return report_;
}

Eigen::MatrixX3d QuasiNewtonDriver::DriveRun::gather(const Positions& x) const
{
  Eigen::MatrixX3d out(free_.size(), 3);
  for (size_t i = 0; i < free_.size(); ++i)
    out.row(static_cast<Eigen::Index>(i)) = x.col(free_[i]).transpose();
  return out;
}

void QuasiNewtonDriver::DriveRun::moveFree(Positions& x, double length, const Eigen::MatrixX3d& step) const
{
  for (size_t i = 0; i < free_.size(); ++i)
    x.col(free_[i]) += length * step.row(static_cast<Eigen::Index>(i)).transpose();
}

}  // namespace virtual_origami::core
