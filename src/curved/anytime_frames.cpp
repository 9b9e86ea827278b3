#include "virtual_origami/curved/anytime_frames.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>

#include "virtual_origami/curved/paper_material.h"

namespace virtual_origami::core
{
namespace
{
double wallNow()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double threadCpuNow()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// A factor's tag: the frame whose shown state it was made at, and whether M/h² is in it.
long factorTag(long frame, bool inertial)
{
  return 2 * (frame + 1) + (inertial ? 1 : 0);
}
long taggedFrame(long tag)
{
  return tag / 2 - 1;
}
bool taggedInertial(long tag)
{
  return tag % 2 == 1;
}

/// Kami (15-cm origami paper): the sheet whose bending time scale the inertial frames of a
/// paper without physical units borrow.
constexpr double kKamiSide = 0.15;

double pinTravel(const std::vector<CurvedPin>& from, const std::vector<CurvedPin>& to)
{
  double squared = 0.0;
  for (size_t k = 0; k < from.size() && k < to.size(); ++k)
    squared += (to[k].position - from[k].position).squaredNorm();
  return std::sqrt(squared);
}
}  // namespace

AnytimeFrames::AnytimeFrames(const CurvedMesh& mesh, const Paper& paper, const CurvedMaterial& material,
                             const ContactOptions& contact, const AnytimeFrameOptions& options,
                             const Surroundings& surroundings)
  : mesh_(mesh)
  , paper_(paper)
  , material_(material)
  , contact_options_(contact)
  , options_(options)
  , surroundings_(surroundings)
  , terms_(curvedTerms(mesh, paper, material))
  , contact_(mesh, paper, material, contact)
{
  if (!(surroundings_.table_stiffness > 0))
    surroundings_.table_stiffness = contact_.stiffness();
  double area = 0.0;
  for (size_t t = 0; t < mesh_.triangles.size(); ++t)
    area += mesh_.restArea(static_cast<int>(t));
  // Inertia matters only against bending in a frame of 1/30 s: a paper without units gets the
  // density that gives it kami's bending frequencies, ω ~ √(q/ρ)/L² (L the sheet's size).
  density_ = options_.density;
  if (!(density_ > 0))
  {
    density_ = material_.density;
    if (!(material_.thickness > 0) || !(density_ > 0))
    {
      const PaperMaterial kami = *paperPreset("kami");
      const double side = std::sqrt(area);
      density_ = material_.bend * kami.areal_density / bendingStiffness(kami) * std::pow(kKamiSide / side, 4);
    }
  }
  mass_.assign(mesh_.nodes.size(), 0.0);
  for (size_t t = 0; t < mesh_.triangles.size(); ++t)
    for (int node : mesh_.triangles[t].nodes)
      mass_[node] += density_ * mesh_.restArea(static_cast<int>(t)) / 3.0;
  if (options_.background)
    thread_ = std::thread([this] { backgroundLoop(); });
}

AnytimeFrames::~AnytimeFrames()
{
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  made_.notify_all();
  if (thread_.joinable())
    thread_.join();
}

Status AnytimeFrames::start(const Positions& x, const std::vector<CurvedPin>& pins)
{
  if (x.cols() != static_cast<Eigen::Index>(mesh_.nodes.size()) || !x.allFinite())
    return failure("the positions have " + std::to_string(x.cols()) + " columns for " +
                   std::to_string(mesh_.nodes.size()) + " nodes, or are not finite");
  std::vector<char> fixed(mesh_.nodes.size(), 0);
  for (const CurvedPin& pin : pins)
  {
    if (pin.node < 0 || pin.node >= static_cast<int>(mesh_.nodes.size()) || !pin.position.allFinite())
      return failure("the pin of node " + std::to_string(pin.node) + " is off the sheet or not at a finite point");
    fixed[pin.node] = 1;
  }
  // The thread makes no factor while no frame has asked for one: the free nodes change safely.
  waitForFactor(last_request_);
  free_index_ = freeIndices(fixed, mesh_.nodes.size(), &free_count_);
  pinned_.clear();
  for (const CurvedPin& pin : pins)
    pinned_.push_back(pin.node);
  x_ = x;
  for (const CurvedPin& pin : pins)
    x_.col(pin.node) = pin.position;
  x_before_ = Positions();
  older_ = Positions();
  pins_ = pins;
  pins_before_.clear();
  velocity_ = Eigen::VectorXd::Zero(3 * free_count_);
  inertial_ = false;
  hessian_ = blockPattern(free_count_, free_index_, termGroups(terms_));
  contact_.update(x_);
  frame_ = 0;
  last_request_ = 0;
  step_h_ = options_.time_step;
  makeFactor(x_, 0, step_h_, options_.static_shift_limit);
  started_ = true;
  return success();
}

double AnytimeFrames::forceOf(const Eigen::VectorXd& g) const
{
  double worst = 0.0;
  for (Eigen::Index i = 0; i + 2 < g.size(); i += 3)
    worst = std::max(worst, g.segment<3>(i).norm());
  return std::isfinite(g.sum()) ? worst / (material_.stretch * mesh_.spacing) : INFINITY;
}

double AnytimeFrames::energy(const Positions& x, Eigen::VectorXd* gradient)
{
  return objective(x, nullptr, gradient, nullptr);
}

double AnytimeFrames::objective(const Positions& x, const Positions* y, Eigen::VectorXd* gradient,
                                Eigen::VectorXd* static_gradient)
{
  if (gradient)
    gradient->setZero(3 * free_count_);
  const Assembly out{ &free_index_, gradient, nullptr };
  double e = evaluateCurved(terms_, x, out).total() + contact_.evaluate(x, out) +
             evaluateSurroundings(surroundings_, terms_.mass, x, out);
  if (static_gradient && gradient)
    *static_gradient = *gradient;
  if (y)
  {
    // Implicit Euler's inertia: ½·Σ m/h²·|x − y|², y where the nodes would coast to.
    const double over_h2 = 1.0 / (step_h_ * step_h_);
    for (size_t v = 0; v < free_index_.size(); ++v)
      if (const int f = free_index_[v]; f >= 0)
      {
        const Vec3 d = x.col(v) - y->col(v);
        e += 0.5 * mass_[v] * over_h2 * d.squaredNorm();
        if (gradient)
          gradient->segment<3>(3 * f) += mass_[v] * over_h2 * d;
      }
  }
  return e;
}

void AnytimeFrames::makeFactor(const Positions& x, long frame, double h, double static_limit, bool static_only)
{
  const double cpu_start = threadCpuNow();
  // The terms' Hessian (weight and table in; contact not: its pairs belong to the frames'
  // thread, and a matrix without it only makes the steps near contact shorter, which the
  // residual check sees).
  hessian_.coeffs().setZero();
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * free_count_);
  BlockHessian blocks{ &hessian_ };
  const Assembly out{ &free_index_, &g, nullptr, &blocks };
  evaluateCurved(terms_, x, out);
  evaluateSurroundings(surroundings_, terms_.mass, x, out);
  // Levenberg–Marquardt's shift where the shown state is off balance (its Hessian indefinite
  // by a little: a compressed edge): static_limit at once. Where that fails, no smaller shift
  // succeeds (A + s·I is positive definite for every s above some value, none below), and each
  // try costs a whole factorisation (at 10,000 vertices three tries were a third of a second,
  // ten frames, in which the frames corrected with an older factor).
  bool made = factor_.factorize(hessian_, std::max(options_.static_shift, static_limit) * material_.stretch,
                                factorTag(frame, false));
  ++factorizations_;
  // Past a snap the inertial matrix needs a shift too; each failed try costs a factorisation,
  // so the ladder starts a hundredth below where it last succeeded.
  double shift = std::max(options_.static_shift * material_.stretch, 1e-2 * inertial_shift_);
  if (!made && !static_only)
  {
    // Negative curvature beyond rounding: the sheet buckles or snaps here. With the paper's
    // mass over the frame time squared the matrix is the implicit Euler step's.
    const double over_h2 = 1.0 / (h * h);
    for (size_t v = 0; v < free_index_.size(); ++v)
      if (const int f = free_index_[v]; f >= 0)
        blocks.add(f, f, Eigen::Matrix3d(mass_[v] * over_h2 * Eigen::Matrix3d::Identity()));
    for (int attempt = 0; attempt < 12 && !made; ++attempt, shift *= 100)
    {
      made = factor_.factorize(hessian_, shift, factorTag(frame, true));
      ++factorizations_;
      if (made)
        inertial_shift_ = shift;
    }
  }
  factor_cpu_ = factor_cpu_ + (threadCpuNow() - cpu_start);
}

void AnytimeFrames::keepFactorAt(const Positions& x, long tag_frame)
{
  waitForFactor(last_request_);
  makeFactor(x, tag_frame, step_h_, options_.static_shift_limit);
}

void AnytimeFrames::backgroundLoop()
{
  while (true)
  {
    Request request;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return has_request_ || stop_; });
      if (stop_)
        return;
      request = std::move(request_);
      has_request_ = false;
    }
    if (request.search_contact)
    {
      // The contact search the frames would otherwise stall on, ahead of their need.
      const double cpu_start = threadCpuNow();
      auto found = std::make_unique<LayerContact::Candidates>(contact_.candidatesAt(request.x));
      factor_cpu_ = factor_cpu_ + (threadCpuNow() - cpu_start);
      const std::lock_guard<std::mutex> lock(mutex_);
      found_ = std::move(found);
    }
    makeFactor(request.x, request.frame, request.h, request.static_limit, request.static_only);
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      made_frame_ = request.frame;
    }
    made_.notify_all();
  }
}

double AnytimeFrames::staticLimit() const
{
  // Frames that have been inertial for a while lag the pointer, a little off balance: they
  // turn static again where the matrix factorises at the larger shift.
  return inertial_ && inertial_frames_ >= options_.return_frames ?
             std::max(options_.static_shift_limit, options_.return_shift_limit) :
             options_.static_shift_limit;
}

void AnytimeFrames::ask(bool search_contact, bool static_only)
{
  last_request_ = frame_;
  if (!options_.background)
  {
    makeFactor(x_, frame_, step_h_, staticLimit(), static_only);
    made_frame_ = frame_;
    return;
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    // The latest shown state replaces one not yet begun.
    request_ = { x_, frame_, search_contact, step_h_, staticLimit(), static_only };
    has_request_ = true;
  }
  wake_.notify_one();
}

void AnytimeFrames::waitForFactor(long frame)
{
  if (!options_.background)
    return;
  std::unique_lock<std::mutex> lock(mutex_);
  made_.wait(lock, [&] { return stop_ || (made_frame_ >= frame && !has_request_); });
}

void AnytimeFrames::correct(const Positions* y, double seconds, int max_corrections, double tolerance,
                            FrameReport& report)
{
  // The budget's clock: the wall's, or (budget_in_thread_cpu) this thread's CPU time.
  const auto clock = [this] { return options_.budget_in_thread_cpu ? threadCpuNow() : wallNow(); };
  const double start = clock();
  Eigen::VectorXd g, gs;
  double e = objective(x_, y, &g, &gs);
  report.start_force = forceOf(gs);
  report.max_force = report.start_force;
  report.start_energy = e;
  report.energy = e;
  shown_force_ = report.max_force;
  const Eigen::MatrixXd free_motions =
      y ? Eigen::MatrixXd(3 * free_count_, 0) :
          freeRigidMotions(x_, free_index_, free_count_, surroundings_.gravity != 0 || surroundings_.table);
  const double max_move = options_.max_step * contact_.range();
  Positions trial = x_;
  Eigen::VectorXd g_trial, gs_trial, z_last, direction;
  double rz_last = 0.0;
  for (int k = 0; k < max_corrections; ++k)
  {
    // Static frames stop at balance; inertial ones at the implicit Euler step's own.
    if ((y ? forceOf(g) : report.max_force) <= tolerance)
      break;
    if (k > 0 && clock() - start + correction_seconds_ > seconds)
      break;
    const double correction_start = clock();
    long tag = 0;
    // Preconditioned nonlinear conjugate gradients (Polak–Ribière): the kept factor's step,
    // made conjugate to the last one along the exact curvature that each secant measures, so
    // that a factor gone soft or stiff in a few modes since it was made costs iterations, not
    // the frame's shape.
    Eigen::VectorXd z = factor_.solve(-g, &tag);
    report.solve_seconds += clock() - correction_start;
    if (z.size() != g.size())
      break;
    report.factor_frame = taggedFrame(tag);
    if (free_motions.cols() > 0)
      z -= free_motions * (free_motions.transpose() * z);
    const double rz = -g.dot(z);
    Eigen::VectorXd step = z;
    if (k > 0 && rz_last > 0)
    {
      const double beta = std::max(0.0, -g.dot(z - z_last) / rz_last);
      step += beta * direction;
      if (!(g.dot(step) < 0))
        step = z;
    }
    z_last = std::move(z);
    rz_last = rz;
    double longest = 0.0;
    for (int i = 0; i < free_count_; ++i)
      longest = std::max(longest, step.segment<3>(3 * i).norm());
    if (longest > max_move)
    {
      step *= max_move / longest;
      longest = max_move;
    }
    const double slope = g.dot(step);
    // The residual check: the factor may be for another state (made frames ago, or inertial
    // where this frame is static), its step too long or too short where the soft modes'
    // stiffness has moved since. The energy and force at the step's end give the curvature
    // along it (a secant), and the step is taken at the minimum of that quadratic; of the two
    // points the one with the lower energy (below the energy's rounding: the lower force) is
    // shown, and neither where both are worse than where the frame is.
    const double worst_gap = contact_.worstGap(x_);
    const auto place = [&](double alpha, Positions& at) {
      for (size_t v = 0; v < free_index_.size(); ++v)
        if (const int f = free_index_[v]; f >= 0)
          at.col(v) = x_.col(v) + alpha * step.segment<3>(3 * f);
        else
          at.col(v) = x_.col(v);
      return contact_.worstGap(at) >= std::min(0.0, worst_gap) - 0.5 * contact_.thickness();
    };
    const double rounding = 1e-10 * std::abs(e);
    const double force_here = forceOf(g);
    const auto better = [&](double energy_there, const Eigen::VectorXd& g_there, double energy_best,
                            const Eigen::VectorXd* g_best) {
      if (std::abs(energy_there - energy_best) > rounding)
        return energy_there < energy_best;
      return forceOf(g_there) < (g_best ? forceOf(*g_best) : force_here);
    };
    bool taken = false;
    double e_taken = e;
    if (slope < 0 && std::isfinite(slope) && place(1.0, trial))
    {
      Eigen::VectorXd gs1;
      const double e1 = objective(trial, y, &g_trial, &gs1);
      const double slope_end = g_trial.dot(step);
      double alpha = slope_end > slope ? slope / (slope - slope_end) : 1.0;
      alpha = std::min(alpha, longest > 0 ? std::min(4.0, max_move / longest) : 1.0);
      if (std::isfinite(e1) && better(e1, g_trial, e, nullptr))
      {
        taken = true;
        e_taken = e1;
        gs_trial = gs1;
      }
      if (std::abs(alpha - 1.0) > 0.1 && alpha > 0)
      {
        Positions second = trial;
        Eigen::VectorXd g2, gs2;
        if (place(alpha, second))
        {
          const double e2 = objective(second, y, &g2, &gs2);
          if (std::isfinite(e2) && better(e2, g2, taken ? e1 : e, taken ? &g_trial : nullptr))
          {
            taken = true;
            e_taken = e2;
            trial = std::move(second);
            g_trial = std::move(g2);
            gs_trial = std::move(gs2);
          }
        }
      }
      // Neither lowered the energy (negative curvature along the step, or a factor far too
      // soft there): shorter steps, a quarter at a time, before the frame gives up on it.
      for (double shorter = std::min(alpha > 0 ? alpha : 1.0, 1.0) / 4; !taken && shorter >= 1.0 / 64; shorter /= 4)
      {
        Positions third = trial;
        Eigen::VectorXd g3, gs3;
        if (!place(shorter, third))
          continue;
        const double e3 = objective(third, y, &g3, &gs3);
        if (std::isfinite(e3) && better(e3, g3, e, nullptr))
        {
          taken = true;
          e_taken = e3;
          trial = std::move(third);
          g_trial = std::move(g3);
          gs_trial = std::move(gs3);
        }
      }
    }
    if (!taken)
    {
      ++report.refused;
      break;
    }
    std::swap(x_, trial);
    direction = step;
    // New watched pairs change the energy: then it is taken afresh.
    const int watched = contact_.watchedPairs();
    contact_.update(x_);
    g = g_trial;
    gs = gs_trial;
    e = e_taken;
    if (contact_.watchedPairs() != watched)
      e = objective(x_, y, &g, &gs);
    report.max_force = forceOf(gs);
    shown_force_ = report.max_force;
    report.energy = e;
    ++report.corrections;
    correction_seconds_ = clock() - correction_start;
  }
}

Expected<FrameReport> AnytimeFrames::frame(const std::vector<CurvedPin>& pins)
{
  if (!started_)
    return Expected<FrameReport>::failure("no sheet: start() first");
  if (pins.size() != pins_.size())
    return Expected<FrameReport>::failure("a frame's pins must hold the nodes start() was given");
  for (size_t k = 0; k < pins.size(); ++k)
    if (pins[k].node != pins_[k].node || !pins[k].position.allFinite())
      return Expected<FrameReport>::failure("a frame's pins must hold the nodes start() was given, at finite points");
  const double start = wallNow(), start_cpu = threadCpuNow();
  ++frame_;
  FrameReport report;
  if (options_.background)
  {
    std::unique_ptr<LayerContact::Candidates> found;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      found = std::move(found_);
    }
    if (found)
      contact_.adoptCandidates(std::move(*found), x_);
  }
  // Static or inertial, as the latest factor is: an implicit Euler step where the sheet's
  // Hessian at a recent state was not positive definite.
  const bool inertial = taggedInertial(factor_.tag());
  const double h = options_.time_step;
  const bool moved_before = x_before_.cols() == x_.cols();
  if (inertial && !inertial_)
  {
    // Off a branch: the sheet keeps (its share of) the speed the drag gave it.
    velocity_.setZero(3 * free_count_);
    if (moved_before)
      for (size_t v = 0; v < free_index_.size(); ++v)
        if (const int f = free_index_[v]; f >= 0)
          velocity_.segment<3>(3 * f) = options_.kept_velocity * (x_.col(v) - x_before_.col(v)) / h;
  }
  const bool inertial_before_frame = inertial_;
  inertial_ = inertial;
  inertial_frames_ = inertial ? inertial_frames_ + 1 : 0;
  // The prediction: where the nodes coast to (inertial), or the shape carried on along the
  // last two frames in the pins' travel (static).
  Positions predicted = x_;
  if (inertial && options_.kept_velocity > 0)
  {
    for (size_t v = 0; v < free_index_.size(); ++v)
      if (const int f = free_index_[v]; f >= 0)
        predicted.col(v) += h * velocity_.segment<3>(3 * f);
  }
  else if (moved_before && pins_before_.size() == pins.size())
  {
    // (Inertial frames from rest coast nowhere, but the pins drag the sheet on: they carry on
    // as static ones do.)
    // Lagrange's polynomial in the pins' travel through the last two shown shapes, or three
    // when the one before was static too (the pinned corner runs along a curve: a straight
    // carry strains its edges by the curve's bend).
    const double a = pinTravel(pins_before_, pins_), b = pinTravel(pins_, pins);
    if (a > 0 && b > 0 && b < 2 * a)
    {
      // (Only from frames near balance: a polynomial through shapes off balance carries their
      // errors on, magnified.)
      const double c = older_.cols() == x_.cols() && shown_force_ <= options_.off_balance_force ?
                           pinTravel(pins_older_, pins_before_) :
                           0.0;
      if (c > 0)
      {
        // Nodes at travel −(a + c), −a, 0; the shape wanted at b.
        const double t0 = -(a + c), t1 = -a, t = b;
        const double w0 = (t - t1) * t / ((t0 - t1) * t0), w1 = (t - t0) * t / ((t1 - t0) * t1),
                     w2 = (t - t0) * (t - t1) / (t0 * t1);
        predicted = w0 * older_ + w1 * x_before_ + w2 * x_;
      }
      else
        predicted += (b / a) * (x_ - x_before_);
    }
  }
  for (const CurvedPin& pin : pins)
    predicted.col(pin.node) = pin.position;
  if (!predicted.allFinite() ||
      contact_.worstGap(predicted) < std::min(0.0, contact_.worstGap(x_)) - 0.5 * contact_.thickness())
  {
    predicted = x_;
    for (const CurvedPin& pin : pins)
      predicted.col(pin.node) = pin.position;
  }
  report.contact_search = contact_.needsSearch(predicted);
  contact_.update(predicted);
  if (!inertial && !inertial_before_frame)
  {
    older_ = x_before_;
    pins_older_ = pins_before_;
  }
  else
    older_ = Positions();
  x_before_ = x_;
  pins_before_ = pins_;
  x_ = predicted;
  pins_ = pins;
  // The inertial frames' anchor: where the nodes coast to (from rest: the last shown shape,
  // the pins moved), not the carry along the branch: carried on, a sheet at a saddle would
  // follow it as the static frames do instead of falling off it.
  Positions target = predicted;
  if (inertial && options_.kept_velocity == 0)
  {
    target = x_before_;
    for (const CurvedPin& pin : pins)
      target.col(pin.node) = pin.position;
  }
  const double used = options_.budget_in_thread_cpu ? threadCpuNow() - start_cpu : wallNow() - start;
  correct(inertial ? &target : nullptr, options_.frame_seconds - used, options_.max_corrections,
          options_.frame_tolerance, report);
  report.inertial = inertial;
  if (inertial)
    for (size_t v = 0; v < free_index_.size(); ++v)
      if (const int f = free_index_[v]; f >= 0)
        velocity_.segment<3>(3 * f) = options_.kept_velocity * (x_.col(v) - x_before_.col(v)) / h;
  if (frame_ - last_request_ >= options_.refactor_frames || report.refused > 0)
    ask(contact_.skinUsed(x_) > 0.5);
  report.seconds = wallNow() - start;
  return report;
}

ReleaseReport AnytimeFrames::release()
{
  ReleaseReport result;
  if (!started_)
    return result;
  const double start = wallNow();
  const int factorizations_before = factorizations_;
  // A factor for the shape as it is now, and after each round of corrections a new one: each
  // step's matrix is the Hessian of a state at most a round old, so the corrections converge
  // as Newton's.
  // Only a static factor serves: where the static matrix does not factorise, no inertial one
  // is made (at 10,000 vertices one to three factorisations, a fifth to half a second).
  inertial_ = false;
  inertial_frames_ = 0;
  ++frame_;
  ask(contact_.skinUsed(x_) > 0.5, true);
  waitForFactor(frame_);
  for (int round = 0; round < options_.release_rounds && wallNow() - start < options_.release_seconds; ++round)
  {
    if (factor_.tag() != factorTag(frame_, false))
      break;  // still snapping: Newton's saddle test and damping finish it (below)
    FrameReport report;
    correct(nullptr, INFINITY, 8, options_.release_tolerance, report);
    result.corrections += report.corrections;
    if (report.max_force <= options_.release_tolerance)
      break;
    ++frame_;
    ask(contact_.skinUsed(x_) > 0.5, true);
    waitForFactor(frame_);
  }
  result.frame_factorizations = factorizations_ - factorizations_before;
  Eigen::VectorXd g;
  energy(x_, &g);
  result.max_force = forceOf(g);
  if (!(result.max_force <= options_.release_tolerance) && wallNow() - start < options_.release_seconds)
  {
    // Newton (curved_solver.h) from here: a fresh Hessian each iteration where needed, its
    // damping, and saddles left downhill.
    if (!newton_)
    {
      CurvedSolveOptions solve;
      solve.predict = false;
      newton_ = std::make_unique<CurvedSolver>(mesh_, paper_, material_, contact_options_, solve, surroundings_);
    }
    newton_->options().tolerance = options_.release_tolerance;
    newton_->options().max_seconds = std::max(0.1, options_.release_seconds - (wallNow() - start));
    const CurvedReport polished = newton_->solve(x_, pins_);
    result.newton_iterations = polished.iterations;
    result.factorizations += polished.factorizations;
    contact_.update(x_);
    energy(x_, &g);
    result.max_force = forceOf(g);
  }
  result.converged = result.max_force <= options_.release_tolerance;
  velocity_.setZero(3 * free_count_);
  x_before_ = Positions();
  older_ = Positions();
  result.factorizations += factorizations_ - factorizations_before;
  result.seconds = wallNow() - start;
  return result;
}

}  // namespace virtual_origami::core
