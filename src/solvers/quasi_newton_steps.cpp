// The directions a QuasiNewtonDriver's frame steps along, and the matrices behind them: the
// kept Gauss–Newton factorisation and the constant matrix, each solve counted in the report.
#include <algorithm>
#include <cmath>
#include <utility>

#include "quasi_newton_drive_run.h"

namespace virtual_origami::core
{
/// L-BFGS: the two-loop recursion with the factorised matrix's inverse as the initial Hessian.
Eigen::MatrixX3d QuasiNewtonDriver::DriveRun::lbfgsStep()
{
  return -history_.apply(g_, [this](const Eigen::MatrixX3d& q) { return precondition(q); });
}

/// Newton–Krylov: the Gauss–Newton system at x solved by conjugate gradients, preconditioned
/// by the kept factorisation (the matrix of a nearby state, so a few iterations do).
Eigen::MatrixX3d QuasiNewtonDriver::DriveRun::newtonKrylovStep(const DrivenFaces::Linearization& l,
                                                               const RigidMotions* rigid)
{
  Eigen::MatrixX3d r = -g_;
  if (rigid)
    rigid->remove(r);
  Eigen::MatrixX3d d = Eigen::MatrixX3d::Zero(r.rows(), 3);
  step_product_ = Eigen::MatrixX3d::Zero(r.rows(), 3);
  const double solve_from = budget_.seconds();
  Eigen::MatrixX3d z = precondition(r);
  solve_seconds_ = budget_.seconds() - solve_from;
  if (rigid)
    rigid->remove(z);
  Eigen::MatrixX3d p = z;
  const Eigen::MatrixX3d first = z;
  double rz = numerics::innerProduct(r, z);
  const double goal = options_.krylov_tolerance * std::sqrt(numerics::innerProduct(r, r));
  krylov_slow_ = true;
  krylov_cut_ = false;
  for (int k = 0; k < options_.krylov_iterations; ++k)
  {
    const Eigen::MatrixX3d ap = multiply(l, p);
    const double curvature = numerics::innerProduct(p, ap);
    if (!(curvature > 0))
    {
      // The Hessian is not positive along p (away from a stable balance): the steps so far
      // descend; with none yet, the kept matrix's own step does.
      if (k == 0)
      {
        d = p;
        step_product_ = ap;
      }
      break;
    }
    const double a = rz / curvature;
    d += a * p;
    step_product_ += a * ap;
    r -= a * ap;
    if (std::sqrt(numerics::innerProduct(r, r)) <= goal)
    {
      krylov_slow_ = k + 1 > options_.krylov_iterations / 2;
      break;
    }
    // Anytime: a frame's budget spent, the step so far serves (each iteration improves it).
    if (!fits(solve_seconds_))
    {
      krylov_cut_ = true;
      break;
    }
    z = precondition(r);
    if (rigid)
      rigid->remove(z);
    const double rz_next = numerics::innerProduct(r, z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  // A trust region for the exact Hessian: a step ten times the kept matrix's own says
  // the Hessian is near singular here (a mechanism starting to turn): the kept matrix's step
  // serves, and Gauss–Newton the rest of the frame.
  if (exact_products_ && d.cwiseAbs().maxCoeff() > 10.0 * first.cwiseAbs().maxCoeff())
  {
    exact_products_ = false;
    exact_refused_ = true;
    d = first;
    step_product_ = multiply(l, d);
  }
  return d;
}

/// The Newton–Krylov step d and the last frame's motion m as one Galerkin step over both: the
/// step a·d + b·m that the Gauss–Newton model at x prefers. A matrix kept from another state
/// calls a mechanism's present turn stiff, so its steps fall ever further behind the balance
/// along the turn (a slide's frames lag, then snap back through stretched faces); the motion
/// is that turn, and the model says how far along it to go, for one product more.
void QuasiNewtonDriver::DriveRun::followMotion(const DrivenFaces::Linearization& l, const RigidMotions* rigid,
                                               Eigen::MatrixX3d& direction)
{
  Eigen::MatrixX3d m = motion_;
  if (rigid)
    rigid->remove(m);
  const Eigen::MatrixX3d hm = multiply(l, m);
  Eigen::Matrix2d model;
  model << numerics::innerProduct(direction, step_product_), numerics::innerProduct(direction, hm),
      numerics::innerProduct(m, step_product_), numerics::innerProduct(m, hm);
  const Eigen::Vector2d slope(-numerics::innerProduct(g_, direction), -numerics::innerProduct(g_, m));
  // Only where the two directions are independent under the model (m may be d again).
  if (!(model(0, 0) > 0 && model(1, 1) > 0 && model.determinant() > 1e-6 * model(0, 0) * model(1, 1)))
    return;
  const Eigen::Vector2d c = model.llt().solve(slope);
  if (c.allFinite())
    direction = c(0) * direction + c(1) * m;
}

/// A frame's step without the Gauss–Newton factorisation: the Galerkin step of the
/// Gauss–Newton model over the last frame's motion and conjugate directions of the constant
/// matrix (conjugate gradients augmented by the motion). The constant matrix calls a
/// mechanism's turn stiff, the motion is that turn; the matrix restores what the motion's
/// linear step stretches. Each direction costs one back-substitution of the constant
/// (scalar) factor and one product, a fifth of a back-substitution of the kept one.
Eigen::MatrixX3d QuasiNewtonDriver::DriveRun::subspaceStep(const DrivenFaces::Linearization& l,
                                                           const RigidMotions* rigid)
{
  const double step_from = budget_.seconds();
  Galerkin galerkin;
  galerkin.residual = -g_;
  if (rigid)
    rigid->remove(galerkin.residual);
  const double goal =
      options_.krylov_tolerance * std::sqrt(numerics::innerProduct(galerkin.residual, galerkin.residual));
  galerkin.step = Eigen::MatrixX3d::Zero(galerkin.residual.rows(), 3);
  step_product_ = Eigen::MatrixX3d::Zero(galerkin.residual.rows(), 3);
  // A slide's first frame (not going on from the last, its motion from elsewhere on the
  // path): the kept matrix's step as well, which points along the turn the balance takes
  // here, if too short.
  if (motion_.size() > 0)
    addToSubspace(galerkin, motion_, l, rigid);
  if (!continues_ && setup_.gauss_newton.valid())
    addToSubspace(galerkin, precondition(galerkin.residual), l, rigid);
  krylov_cut_ = false;
  for (int k = 0; k < options_.subspace_directions; ++k)
  {
    if (std::sqrt(numerics::innerProduct(galerkin.residual, galerkin.residual)) <= goal)
      break;
    if (k > 0 && !fits(subspace_add_seconds_))
    {
      krylov_cut_ = true;
      break;
    }
    const double add_from = budget_.seconds();
    addToSubspace(galerkin, solveConstant(galerkin.residual), l, rigid);
    subspace_add_seconds_ = budget_.seconds() - add_from;
  }
  solve_seconds_ = budget_.seconds() - step_from;  // what the next iteration's step will cost
  return std::move(galerkin.step);
}

/// v made H-orthogonal to the subspace so far and added to it, the step extended along it
/// (unless v lies in the subspace already).
void QuasiNewtonDriver::DriveRun::addToSubspace(Galerkin& galerkin, Eigen::MatrixX3d v,
                                                const DrivenFaces::Linearization& l, const RigidMotions* rigid)
{
  if (rigid)
    rigid->remove(v);
  Eigen::MatrixX3d hv = multiply(l, v);
  const double before = numerics::innerProduct(v, hv);
  for (size_t i = 0; i < galerkin.basis.size(); ++i)
  {
    const double c = numerics::innerProduct(galerkin.basis_product[i], v);
    v -= c * galerkin.basis[i];
    hv -= c * galerkin.basis_product[i];
  }
  const double norm2 = numerics::innerProduct(v, hv);
  if (!(norm2 > 1e-10 * before))
    return;
  const double norm = std::sqrt(norm2);
  galerkin.basis.push_back(v / norm);
  galerkin.basis_product.push_back(hv / norm);
  const double c = numerics::innerProduct(galerkin.basis.back(), galerkin.residual);
  galerkin.step += c * galerkin.basis.back();
  step_product_ += c * galerkin.basis_product.back();
  galerkin.residual -= c * galerkin.basis_product.back();
}

/// The Hessian's product with v at the free vertices: the energy's own once the steps converge
/// (exact_products_), else the Gauss–Newton matrix's.
Eigen::MatrixX3d QuasiNewtonDriver::DriveRun::multiply(const DrivenFaces::Linearization& l, const Eigen::MatrixX3d& v)
{
  for (size_t i = 0; i < free_.size(); ++i)
    spread_.col(free_[i]) = v.row(static_cast<Eigen::Index>(i)).transpose();
  if (exact_products_)
    energy_.hessianProduct(l, spread_, product_);
  else
    energy_.gaussNewtonProduct(l, spread_, product_);
  return gather(product_);
}

/// The kept factorisation's solve (the constant matrix's before there is one), counted.
Eigen::MatrixX3d QuasiNewtonDriver::DriveRun::precondition(const Eigen::MatrixX3d& q)
{
  if (options_.hessian == DriverHessian::Constant || !setup_.gauss_newton.valid())
    return solveConstant(q);
  ++report_.back_substitutions;
  const Eigen::MatrixX3d qt = q;  // row per vertex: flattened row-major it is 3i + axis
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> rows = qt;
  const Eigen::VectorXd solved = setup_.gauss_newton.solve(Eigen::Map<const Eigen::VectorXd>(rows.data(), rows.size()));
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(solved.data(), rows.rows(), 3);
}

/// The constant matrix's solve, counted (and its factorisation, where this frame makes it).
Eigen::MatrixX3d QuasiNewtonDriver::DriveRun::solveConstant(const Eigen::MatrixX3d& rhs)
{
  const bool unfactored = !setup_.constant_tried;
  Eigen::MatrixX3d solved = setup_.solveConstant(rhs);
  report_.factorizations += unfactored ? 1 : 0;
  report_.back_substitutions += setup_.factored ? 1 : 0;
  return solved;
}

/// One step of the constant matrix from `at` (rotations fitted, the faces' shapes restored),
/// taken where it lowers the energy: what a linear step along turning faces stretched, taken
/// out for about one back-substitution.
void QuasiNewtonDriver::DriveRun::restoreFaces(Positions& at, Positions& at_gradient,
                                               DrivenFaces::Evaluation& at_energy)
{
  const numerics::SolveBudget clock(SolveLimits{});
  Eigen::MatrixX3d restore = -solveConstant(gather(at_gradient));
  if (frame_rigid_)
    frame_rigid_->remove(restore);
  else if (!anchored_)
    RigidMotions(at, free_).remove(restore);
  for (double length = 1.0; length >= 0.25; length *= 0.5)
  {
    Positions restored = at, restored_gradient;
    moveFree(restored, length, restore);
    const DrivenFaces::Evaluation better = energy_.evaluate(restored, &restored_gradient);
    if (better.energy < at_energy.energy)
    {
      at = std::move(restored);
      at_gradient = std::move(restored_gradient);
      at_energy = better;
      break;
    }
  }
  setup_.restore_seconds = clock.seconds();
}

/// The Gauss–Newton matrix at x factorised; nothing held, its null space (rigid motions) is
/// shifted away by far less than the faces' stiffness, and a failed factorisation (a
/// degenerate face) is retried with more.
bool QuasiNewtonDriver::DriveRun::refactor()
{
  const numerics::SolveBudget clock(SolveLimits{});
  assembleGaussNewton();
  const Eigen::SparseMatrix<double>& m = setup_.gauss_newton_matrix;
  double largest = 0.0;
  for (int k = 0; k < m.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(m, k); it; ++it)
      if (it.row() == it.col())
        largest = std::max(largest, it.value());
  bool factorized = false;
  for (double shift = largest * (anchored_ ? 1e-12 : 1e-9); shift <= largest && !factorized; shift *= 100)
  {
    ++report_.factorizations;
    factorized = setup_.gauss_newton.factorize(m, shift);
  }
  setup_.factor_seconds = clock.seconds();
  return factorized;
}

/// A fresh factorisation; the curvature pairs gathered against the old one go with it.
void QuasiNewtonDriver::DriveRun::refactorAfresh()
{
  if (refactor())
    history_.clear();
}

/// The Gauss–Newton matrix at x in its compressed pattern: the pattern and where each entry
/// lands planned once per pattern (and shared with the driver's clones), the values summed.
void QuasiNewtonDriver::DriveRun::assembleGaussNewton()
{
  if (setup_.triplets.empty())
  {
    // A new set-up (a commit's fresh clone) takes the planned count at once: grown entry by
    // entry, the list was copied as it grew (a seventh of the samples in a profile of a
    // 10,000-vertex release before the nodes kept their freed memory, heap_reuse.h).
    const std::lock_guard<std::mutex> planning(driver_.assembly_->mutex);
    setup_.triplets.reserve(driver_.assembly_->entries.size());
  }
  energy_.gaussNewtonTriplets(x_, setup_.free_index, setup_.triplets);
  Eigen::SparseMatrix<double>& m = setup_.gauss_newton_matrix;
  if (setup_.slots.size() != setup_.triplets.size())
  {
    AssemblyPlan& plan = *driver_.assembly_;
    const std::lock_guard<std::mutex> planning(plan.mutex);
    if (!plan.matches(setup_.triplets))
      plan.plan(setup_.triplets, 3 * setup_.free_count);
    m = plan.pattern;
    setup_.slots = plan.slots;
  }
  double* values = m.valuePtr();
  std::fill(values, values + m.nonZeros(), 0.0);
  for (size_t k = 0; k < setup_.triplets.size(); ++k)
    values[setup_.slots[k]] += setup_.triplets[k].value();
}

/// Whether `work` (and the line search's passes and the final restoring step after it) ends
/// within the frame's time budget.
bool QuasiNewtonDriver::DriveRun::fits(double work) const
{
  return limits_.max_seconds <= 0 ||
         budget_.seconds() + work + 2 * evaluate_seconds_ + final_reserve_ < limits_.max_seconds;
}

/// A factorisation is paid for only where the budget has room for it (twice what the last
/// one took): in a preview frame the kept matrix serves until it fails outright.
bool QuasiNewtonDriver::DriveRun::roomForFactor() const
{
  return limits_.max_seconds <= 0 || limits_.max_seconds - budget_.seconds() > 2 * setup_.factor_seconds;
}

/// How far the faces turned since the kept matrix was factorised, as K·δ² for the face that
/// turned most (δ its turn in radians, K the face stiffness): what that matrix's face term
/// charges along the mechanism's present turn, against the hinges' stiffness (about 1).
double QuasiNewtonDriver::DriveRun::turnedSinceFactor(const DrivenFaces::Linearization& l) const
{
  if (setup_.factor_frames.size() != l.frame.size())
    return INFINITY;
  double largest = 0.0;
  for (size_t f = 0; f < l.frame.size(); ++f)
    largest = std::max(largest, (l.frame[f] - setup_.factor_frames[f]).squaredNorm());
  return energy_.faceStiffness() * largest;
}

}  // namespace virtual_origami::core
