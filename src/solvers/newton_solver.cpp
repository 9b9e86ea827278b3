#include "virtual_origami/solvers/newton_solver.h"

#include <algorithm>
#include <memory>
#include <cmath>

#include <Eigen/CholmodSupport>
#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "virtual_origami/core/compliant_faces.h"
#include "virtual_origami/core/face_springs.h"
#include "virtual_origami/numerics/spd_factorization.h"
#include "virtual_origami/solvers/rigid_faces.h"
#include "virtual_origami/numerics/solve_budget.h"

#include "../numerics/nested_dissection.h"

namespace virtual_origami::core
{
namespace
{
using SparseMatrix = Eigen::SparseMatrix<double>;

Eigen::Matrix3d skew(const Eigen::Vector3d& q)
{
  Eigen::Matrix3d s;
  s << 0, -q.z(), q.y(), q.z(), 0, -q.x(), -q.y(), q.x(), 0;
  return s;
}

/// The reduced Gauss–Newton matrix over the free vertices (3 rows each). Its pattern is
/// ordered once and stored as one triangle in that order: every step only refills values in
/// place and factors them numerically. A small model's order is approximate minimum degree on
/// the vertex graph (the 3 × 3 blocks together), its upper triangle factored as it stands. A
/// large model's is the one CHOLMOD's analysis picks (nested dissection, numerics/
/// nested_dissection.h), in which its lower triangle is stored: CHOLMOD then factors the values
/// as they are, where in any other order it first copies the matrix into its own, twice
/// transposed, at every factorisation (7 % of a 10,000-vertex turn preview's time, with the
/// allocations and page faults of the copies).
class ReducedSystem
{
public:
  ReducedSystem(const std::vector<RigidFace>& faces, const std::vector<int>& free_index, int free_count)
    : faces_(faces), free_index_(free_index), size_(3 * free_count), neighbours_(free_count)
  {
    // Which free vertices share a face.
    for (const RigidFace& face : faces)
      for (int v : face.vertices)
        for (int w : face.vertices)
          if (free_index[v] >= 0 && free_index[w] >= 0)
            neighbours_[free_index[v]].push_back(free_index[w]);
    std::vector<Eigen::Triplet<double>> block_pattern;
    for (int i = 0; i < free_count; ++i)
    {
      std::sort(neighbours_[i].begin(), neighbours_[i].end());
      neighbours_[i].erase(std::unique(neighbours_[i].begin(), neighbours_[i].end()), neighbours_[i].end());
      for (int j : neighbours_[i])
        block_pattern.emplace_back(i, j, 1.0);
    }
    SparseMatrix blocks(free_count, free_count);
    blocks.setFromTriplets(block_pattern.begin(), block_pattern.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    Eigen::AMDOrdering<int>()(blocks, inverse);
    const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> order = inverse.inverse();
    rows_.resize(size_);
    for (int i = 0; i < free_count; ++i)
      for (int a = 0; a < 3; ++a)
        rows_[3 * i + a] = 3 * order.indices()[i] + a;  // the blocks' new positions
    first_rows_ = rows_;
    storePattern(true);
  }

  /// The pattern's analysis, once: at the first factorisation, not before (a solve that starts
  /// converged, a turn its crease driver has guided, needs none, and a large model's analysis is
  /// 10–100 ms), or ahead of a drag's frames (NewtonSolver::solveLoosely).
  void analyse()
  {
    if (analysed_)
      return;
    if (size_ >= kSupernodalRows)
    {
      // Rows renumbered in the order CHOLMOD's analysis picks, the lower triangle stored in it,
      // and analysed again in that order as given.
      const std::vector<int> order = numerics::choleskyOrdering(matrix_);
      std::vector<int> position(order.size());
      for (size_t k = 0; k < order.size(); ++k)
        position[order[k]] = static_cast<int>(k);
      for (int& r : rows_)
        r = position[r];
      storePattern(false);
      supernodal_ = std::make_unique<Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>>();
      supernodal_->cholmod().print = 0;  // not definite is an answer (the damping rises)
      numerics::analyzeInGivenOrder(*supernodal_, matrix_);
    }
    else
      solver_.analyzePattern(matrix_);
    analysed_ = true;
  }

  /// Fills the matrix for the fitted rotations, adds μ on the diagonal and factors it.
  bool factor(const std::vector<Eigen::Matrix3d>& rotations, double mu)
  {
    analyse();
    double* values = matrix_.valuePtr();
    std::fill(values, values + matrix_.nonZeros(), 0.0);
    std::vector<Eigen::Vector3d> q;
    for (size_t f = 0; f < faces_.size(); ++f)
    {
      const RigidFace& face = faces_[f];
      const size_t n = face.vertices.size();
      q.resize(n);
      Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
      for (size_t k = 0; k < n; ++k)
      {
        q[k] = rotations[f].leftCols<2>() * face.rest.col(static_cast<Eigen::Index>(k));
        inertia += q[k].squaredNorm() * Eigen::Matrix3d::Identity() - q[k] * q[k].transpose();
      }
      // Eliminating the face's rotation: C_f ⊗ I minus B D⁻¹ Bᵀ with B_v = [q_v]×, D the inertia.
      const Eigen::Matrix3d inertia_inv = inertia.inverse();
      const double inv_n = 1.0 / static_cast<double>(n);
      size_t s = 0;
      for (size_t k = 0; k < n; ++k)
      {
        if (free_index_[face.vertices[k]] < 0)
          continue;
        const Eigen::Matrix3d left = skew(q[k]) * inertia_inv;
        for (size_t l = 0; l < n; ++l)
        {
          if (free_index_[face.vertices[l]] < 0)
            continue;
          Eigen::Matrix3d block = left * skew(q[l]);
          block.diagonal().array() += (k == l ? 1.0 : 0.0) - inv_n;
          for (int b = 0; b < 3; ++b)
            for (int a = 0; a < 3; ++a, ++s)
              if (slots_[f][s] >= 0)
                values[slots_[f][s]] += block(a, b);
        }
      }
    }
    for (int i : diagonal_)
      values[i] += mu;
    if (supernodal_)
    {
      const std::unique_lock<std::mutex> blas = numerics::lockBlas();
      supernodal_->factorize(matrix_);
      return supernodal_->info() == Eigen::Success;
    }
    solver_.factorize(matrix_);
    return solver_.info() == Eigen::Success;
  }

  /// Solves in the free vertices' own order (3 per vertex).
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const
  {
    Eigen::VectorXd ordered(size_);
    for (int k = 0; k < size_; ++k)
      ordered[rows_[k]] = rhs[k];
    const Eigen::VectorXd solution = supernodal_ ? [&]() {
      const std::unique_lock<std::mutex> blas = numerics::lockBlas();
      return Eigen::VectorXd(supernodal_->solve(ordered));
    }()
                                                 : Eigen::VectorXd(solver_.solve(ordered));
    Eigen::VectorXd result(size_);
    for (int k = 0; k < size_; ++k)
      result[k] = solution[rows_[k]];
    return result;
  }

private:
  int row(int free_vertex, int axis) const { return rows_[3 * free_vertex + axis]; }

  /// The matrix's pattern in the rows' order, its upper or lower triangle stored, and where each
  /// face's 3 × 3 blocks and the diagonal land among its values.
  void storePattern(bool upper)
  {
    upper_ = upper;
    std::vector<Eigen::Triplet<double>> triplets;
    for (int i = 0; i < size_ / 3; ++i)
      for (int j : neighbours_[i])
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            if (upper ? row(i, a) <= row(j, b) : row(i, a) >= row(j, b))
              triplets.emplace_back(row(i, a), row(j, b), 0.0);
    matrix_.resize(size_, size_);
    matrix_.setFromTriplets(triplets.begin(), triplets.end());
    matrix_.makeCompressed();
    // Where each face's 3 × 3 blocks land among the stored values (-1: the other triangle).
    // Of an entry's two mirrored blocks, the one the first order's upper triangle holds fills
    // it, in either order: the same sums, so the same factor (a block and its mirror's
    // transpose differ in rounding).
    slots_.assign(faces_.size(), {});
    for (size_t f = 0; f < faces_.size(); ++f)
      for (int v : faces_[f].vertices)
        for (int w : faces_[f].vertices)
          if (free_index_[v] >= 0 && free_index_[w] >= 0)
            for (int b = 0; b < 3; ++b)
              for (int a = 0; a < 3; ++a)
              {
                const int i = 3 * free_index_[v] + a, j = 3 * free_index_[w] + b;
                slots_[f].push_back(first_rows_[i] <= first_rows_[j] ? slot(rows_[i], rows_[j]) : -1);
              }
    diagonal_.clear();
    for (int i = 0; i < size_; ++i)
      diagonal_.push_back(slot(i, i));
  }

  /// Where the entry (r, c) or its mirror is stored.
  int slot(int r, int c) const
  {
    if (upper_ ? r > c : r < c)
      std::swap(r, c);
    const int* rows = matrix_.innerIndexPtr();
    const int begin = matrix_.outerIndexPtr()[c], end = matrix_.outerIndexPtr()[c + 1];
    return static_cast<int>(std::lower_bound(rows + begin, rows + end, r) - rows);
  }

  const std::vector<RigidFace>& faces_;
  const std::vector<int>& free_index_;
  int size_;
  std::vector<std::vector<int>> neighbours_;  // the free vertices sharing a face with each
  std::vector<int> rows_;                     // the matrix row of each free vertex's coordinate
  std::vector<int> first_rows_;               // the same in minimum degree's order
  bool upper_ = true;
  SparseMatrix matrix_;
  std::vector<std::vector<int>> slots_;
  std::vector<int> diagonal_;
  bool analysed_ = false;
  // Already ordered: the natural ordering takes the upper triangle as it is, without a copy.
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper, Eigen::NaturalOrdering<int>> solver_;
  // Large models (a tessellation of thousands of vertices): CHOLMOD's supernodal Cholesky,
  // which factors a 10,000-vertex Miura-ori's matrix several times faster than the simplicial
  // one (the damping μ > 0 keeps the matrix definite), in nested dissection's order: a fifth
  // less time per factorisation there than in the minimum-degree one.
  static constexpr int kSupernodalRows = 3000;
  std::unique_ptr<Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>> supernodal_;
};

/// Gradient of the rigid-face energy over the free vertices (3 per vertex): with the
/// rotations fitted, it is the sum of each vertex's residuals over its faces.
Eigen::VectorXd gradient(const std::vector<RigidFace>& faces, const RigidFit& fit, const Positions& x,
                         const std::vector<int>& free_index, int free_count)
{
  Eigen::VectorXd g = Eigen::VectorXd::Zero(3 * free_count);
  for (size_t f = 0; f < faces.size(); ++f)
  {
    const RigidFace& face = faces[f];
    const Eigen::Matrix3Xd centred = centredFace(face, x);
    for (size_t k = 0; k < face.vertices.size(); ++k)
    {
      const int i = free_index[face.vertices[k]];
      if (i >= 0)
        g.segment<3>(3 * i) += centred.col(static_cast<Eigen::Index>(k)) -
                               fit.rotations[f].leftCols<2>() * face.rest.col(static_cast<Eigen::Index>(k));
    }
  }
  return g;
}

void moveFree(Positions& x, const Positions& from, const Eigen::VectorXd& step, double alpha,
              const std::vector<int>& free_index)
{
  for (Eigen::Index v = 0; v < x.cols(); ++v)
    if (free_index[v] >= 0)
      x.col(v) = from.col(v) + alpha * step.segment<3>(3 * free_index[v]);
}
}  // namespace

/// What a solve sets up from the model's faces and held vertices alone: kept while they stay
/// the same (the steps of one drag), so the sparse pattern is analysed once.
struct NewtonSolver::Setup
{
  std::vector<std::vector<int>> face_vertices;
  std::vector<Vec2> crease_pattern;
  std::vector<char> fixed;
  std::vector<char> facets;  // the split edges that bend (core/compliant_faces.h): not joined
  std::vector<RigidFace> faces;
  std::vector<Spring> springs;
  std::vector<int> free_index;
  int free_count = 0;
  std::unique_ptr<ReducedSystem> system;

  Setup(const Paper& paper, const std::vector<char>& held)
    : crease_pattern(creasePattern(paper))
    , fixed(held)
    , facets(facetsOf(paper))
    , faces(rigidFaces(paper))
    , springs(faceSprings(paper))
  {
    for (const Face& face : paper.faces)
      face_vertices.push_back(face.vertices);
    free_index = freeIndices(fixed, paper.vertices.size(), &free_count);
    system = std::make_unique<ReducedSystem>(faces, free_index, free_count);
  }

  bool matches(const Paper& paper, const std::vector<char>& held) const
  {
    if (held != fixed || paper.faces.size() != face_vertices.size() || creasePattern(paper) != crease_pattern ||
        facetsOf(paper) != facets)
      return false;
    for (size_t f = 0; f < paper.faces.size(); ++f)
      if (paper.faces[f].vertices != face_vertices[f])
        return false;
    return true;
  }

  static std::vector<char> facetsOf(const Paper& paper)
  {
    std::vector<char> out;
    out.reserve(paper.edges.size());
    for (const Edge& e : paper.edges)
      out.push_back(isFacet(e) ? 1 : 0);
    return out;
  }

  static std::vector<Vec2> creasePattern(const Paper& paper)
  {
    std::vector<Vec2> c;
    c.reserve(paper.vertices.size());
    for (const Vertex& v : paper.vertices)
      c.push_back(v.crease_pattern);
    return c;
  }
};

namespace
{
/// The pace of the last kPaceWindow iterations is judged once within kPaceNear times the
/// tolerance (further out, a damped start may still turn into Newton's quadratic steps).
constexpr int kPaceWindow = 25;
constexpr double kPaceNear = 100.0;
/// A stalled solve (SolveLimits::stall_window) cut its energy by less than this over the window:
/// 1 %, no progress at all. A solve drifting along a valley of near-constant energy may still
/// converge (a hex/tri tessellation's closure cut its energy only 10^0.2–10^0.3-fold per 30
/// iterations for over a hundred, then converged and was taken); the closures that fail for good
/// end on an energy constant to the last digit.
constexpr double kStallDrop = 1.01;
/// How far a creeping solve lowers its damping floor per step (NewtonOptions::lowest_damping).
constexpr double kFloorCut = 1e-2;
/// A whole step that leaves more than this share of the energy creeps (a frame then tries it
/// longer, extendWhileFalling).
constexpr double kCreepingStep = 0.25;

/// Near the flat sheet a drag's frame creeps along its soft modes: Gauss–Newton's whole steps
/// fall short there by a near-constant factor (a 10,000-vertex Miura-ori turned 0.5°: each cut
/// the energy by 8 %). So the whole step `taken` (from `from` along `step`) is tried twice as
/// long, and again up to 32 times, while the energy keeps falling: the first preview there took
/// 29 steps instead of 67.
void extendWhileFalling(const std::vector<RigidFace>& faces, const Positions& from, const Eigen::VectorXd& step,
                        const std::vector<int>& free_index, Positions& taken, RigidFit& taken_fit)
{
  Positions longer = taken;
  for (double times : { 2.0, 4.0, 8.0, 16.0, 32.0 })
  {
    moveFree(longer, from, step, times, free_index);
    RigidFit longer_fit = fitRigidFaces(faces, longer);
    if (!(longer_fit.energy < taken_fit.energy))
      return;
    taken = longer;
    taken_fit = std::move(longer_fit);
  }
}
}  // namespace

NewtonSolver::NewtonSolver(NewtonOptions options) : options_(options)
{
  limits_.max_iterations = 200;
}

NewtonSolver::~NewtonSolver() = default;

SolveReport NewtonSolver::solve(Paper& paper, const std::vector<char>& fixed)
{
  return solveWithin(paper, fixed, limits_, false);
}

SolveReport NewtonSolver::solveLoosely(Paper& paper, const std::vector<char>& fixed, double looser)
{
  SolveLimits limits = limits_;
  if (looser > limits.tolerance)
    limits.tolerance = looser;
  return solveWithin(paper, fixed, limits, true);
}

namespace
{
/// Set-ups kept: a turn's and a fold's (each holds a factor of the pattern's size).
constexpr size_t kKeptSetups = 2;
}  // namespace

NewtonSolver::Setup& NewtonSolver::setupFor(const Paper& paper, const std::vector<char>& fixed)
{
  auto kept = std::find_if(setups_.begin(), setups_.end(),
                           [&](const std::unique_ptr<Setup>& s) { return s->matches(paper, fixed); });
  if (kept == setups_.end())
  {
    if (setups_.size() >= kKeptSetups)
      setups_.pop_back();
    setups_.insert(setups_.begin(), std::make_unique<Setup>(paper, fixed));
  }
  else
    std::rotate(setups_.begin(), kept, kept + 1);
  return *setups_.front();
}

void NewtonSolver::prepare(const Paper& paper, const std::vector<char>& fixed)
{
  setupFor(paper, fixed).system->analyse();
}

SolveReport NewtonSolver::solveWithin(Paper& paper, const std::vector<char>& fixed, const SolveLimits& limits,
                                      bool frame)
{
  const double floor = frame ? std::min(options_.min_damping, options_.frame_damping) : options_.min_damping;
  numerics::SolveBudget budget(limits);
  SolveReport report;
  Setup& setup = setupFor(paper, fixed);
  const std::vector<RigidFace>& faces = setup.faces;
  const std::vector<Spring>& springs = setup.springs;
  const std::vector<int>& free_index = setup.free_index;
  const int free_count = setup.free_count;
  ReducedSystem& system = *setup.system;
  const Positions start = foldedPositions(paper);
  Positions x = start, trial = start;
  const double residual_tolerance = limits.tolerance * paper.scale();

  RigidFit fit = fitRigidFaces(faces, x);
  std::string stuck;
  std::vector<double> distances;  // how far from the tolerance each iteration started (1: there)
  std::vector<double> energies;   // the rigid-face energy each iteration started from
  double damping_floor = floor;
  bool factored = false;
  bool diverged = !std::isfinite(fit.energy);
  while (!diverged)
  {
    report.max_strain = springStrain(springs, x).max;
    if (report.max_strain <= limits.tolerance && fit.max_residual <= residual_tolerance)
    {
      report.converged = true;
      break;
    }
    if (budget.exhausted(report.iterations))
      break;
    // Near the tolerance, a pace that cannot reach it within the iteration limit ends the solve
    // now: a near-singular balance (a large Miura-ori turned near the flat sheet) otherwise spent
    // its 200 factorisations creeping at a few percent per step and was refused all the same.
    const double distance =
        std::max(report.max_strain / limits.tolerance, fit.max_residual / std::max(residual_tolerance, 1e-300));
    distances.push_back(distance);
    energies.push_back(fit.energy);
    // Further out, an energy that hardly falls any more: no rigid state near (limits.
    // stall_window, for callers that take only such a state).
    const int window = limits.stall_window;
    if (window > 0 && static_cast<int>(energies.size()) > window && distance >= kPaceNear &&
        !(fit.energy < energies[energies.size() - 1 - static_cast<size_t>(window)] / kStallDrop))
    {
      stuck = "stalled (its rigid-face energy fell less than 1 % over its last " + std::to_string(window) +
              " iterations, far from the tolerance)";
      break;
    }
    if (static_cast<int>(distances.size()) > kPaceWindow && distance < kPaceNear)
    {
      const double then = distances[distances.size() - 1 - kPaceWindow];
      const double pace = std::pow(distance / then, 1.0 / kPaceWindow);
      const int left = limits.max_iterations - report.iterations;
      if (!(pace < 1.0) || distance * std::pow(pace, left) > 1.0)
      {
        stuck = "too slow to converge (at the pace of its last " + std::to_string(kPaceWindow) +
                " iterations it would not reach the tolerance within its iteration limit)";
        break;
      }
    }
    ++report.iterations;
    const Eigen::VectorXd g = gradient(faces, fit, x, free_index, free_count);
    double mu = std::max(damping_floor, options_.damping * g.norm() / paper.scale());
    const bool at_floor = mu == damping_floor;
    const double energy_before = fit.energy;
    bool accepted = false;
    bool whole_fresh_step = false;  // a fresh factorisation's step, taken whole
    // First with the factorisation kept from an earlier step (if any), then fresh ones with
    // rising damping, which turns Gauss–Newton towards gradient descent.
    for (int attempt = factored ? -1 : 0; attempt < 4 && !accepted; ++attempt)
    {
      if (attempt >= 0)
      {
        factored = system.factor(fit.rotations, mu);
        mu *= 100;
        if (!factored)
          continue;
      }
      const Eigen::VectorXd step = system.solve(-g);
      const double slope = g.dot(step);
      if (!std::isfinite(slope) || slope >= 0)
        continue;
      double alpha = 1.0;
      for (int k = 0; k < options_.max_line_search; ++k, alpha *= 0.5)
      {
        moveFree(trial, x, step, alpha, free_index);
        RigidFit trial_fit = fitRigidFaces(faces, trial);
        if (trial_fit.energy <= fit.energy + options_.armijo * alpha * slope)
        {
          if (frame && options_.extend_creeping_frames && k == 0 && trial_fit.energy > kCreepingStep * fit.energy)
            extendWhileFalling(faces, x, step, free_index, trial, trial_fit);
          std::swap(x, trial);
          fit = std::move(trial_fit);
          accepted = true;
          whole_fresh_step = attempt == 0 && k == 0;
          break;
        }
      }
    }
    if (!accepted)
    {
      stuck = "no step lowers the rigid-face energy any further";
      break;
    }
    // Creeping: a whole step at the damping floor that did not halve the energy. The floor, not
    // the model, holds the step back there (a near-singular balance whose soft modes are less
    // stiff than the floor: a 10,000-vertex Miura-ori turned near the flat sheet crept 237
    // steps from 2e-9 to 1e-10). Lowered while the steps are whole, raised again at a step the
    // line search shortens or a retry.
    if (whole_fresh_step && at_floor && fit.energy > 0.5 * energy_before)
      damping_floor = std::max(options_.lowest_damping, damping_floor * kFloorCut);
    else if (!whole_fresh_step)
      damping_floor = floor;
    // A kept factorisation pays while it cuts the energy fast; when progress slows, refresh.
    if (!options_.reuse_factorization || fit.energy > options_.refactor_ratio * energy_before)
      factored = false;
    diverged = !std::isfinite(fit.energy);
  }
  // A drag's frames go on: a frame its start balanced (the guide's, a mirror image's) readies
  // the analysis the next ones factorise with (at 1,681 vertices the third preview's 9 ms).
  if (frame && !diverged)
    system.analyse();
  report.seconds = budget.seconds();
  finishRigidSolve("newton", paper, springs, start, x, diverged, fit, stuck, limits.tolerance, report);
  return report;
}

}  // namespace virtual_origami::core
