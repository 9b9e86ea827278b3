#include "virtual_origami/solvers/shape_matching_solver.h"

#include <cmath>
#include <deque>

#include <Eigen/Dense>
#include <Eigen/Sparse>

#include "virtual_origami/core/face_springs.h"
#include "virtual_origami/solvers/rigid_faces.h"
#include "virtual_origami/numerics/solve_budget.h"

namespace virtual_origami::core
{
namespace
{
using SparseMatrix = Eigen::SparseMatrix<double>;

/// The global step: minimise Σ_f |C_f X_f − R_f P̃_f|² + ε|X − X_prev|² over the free
/// vertices. The matrix is the same for x, y and z and for every iteration.
class GlobalStep
{
public:
  GlobalStep(const std::vector<RigidFace>& faces, const std::vector<int>& free_index, int free_count,
             const Positions& x, double proximal)
    : faces_(faces), free_index_(free_index), proximal_(proximal), fixed_part_(Eigen::MatrixX3d::Zero(free_count, 3))
  {
    std::vector<Eigen::Triplet<double>> triplets;
    for (const RigidFace& face : faces)
    {
      const double inv_n = 1.0 / static_cast<double>(face.vertices.size());
      for (int v : face.vertices)
      {
        const int i = free_index[v];
        if (i < 0)
          continue;
        for (int w : face.vertices)
        {
          const double c = (v == w ? 1.0 : 0.0) - inv_n;  // the centring matrix C_f
          const int j = free_index[w];
          if (j >= 0)
            triplets.emplace_back(i, j, c);
          else
            fixed_part_.row(i) -= c * x.col(w).transpose();
        }
      }
    }
    for (int i = 0; i < free_count; ++i)
      triplets.emplace_back(i, i, proximal);
    SparseMatrix a(free_count, free_count);
    a.setFromTriplets(triplets.begin(), triplets.end());
    solver_.compute(a);
  }

  bool ok() const
  {
    return solver_.info() == Eigen::Success;
  }

  /// New free positions (one row per free vertex) for the fitted rotations.
  Eigen::MatrixX3d solve(const std::vector<Eigen::Matrix3d>& rotations, const Eigen::MatrixX3d& previous) const
  {
    Eigen::MatrixX3d rhs = fixed_part_ + proximal_ * previous;
    for (size_t f = 0; f < faces_.size(); ++f)
    {
      const RigidFace& face = faces_[f];
      for (size_t k = 0; k < face.vertices.size(); ++k)
      {
        const int i = free_index_[face.vertices[k]];
        if (i >= 0)
          rhs.row(i) += (rotations[f].leftCols<2>() * face.rest.col(static_cast<Eigen::Index>(k))).transpose();
      }
    }
    return solver_.solve(rhs);
  }

private:
  const std::vector<RigidFace>& faces_;
  const std::vector<int>& free_index_;
  double proximal_;
  Eigen::MatrixX3d fixed_part_;
  Eigen::SimplicialLDLT<SparseMatrix> solver_;
};

Eigen::MatrixX3d gatherFree(const Positions& x, const std::vector<int>& free_index, int free_count)
{
  Eigen::MatrixX3d free(free_count, 3);
  for (Eigen::Index v = 0; v < x.cols(); ++v)
    if (free_index[v] >= 0)
      free.row(free_index[v]) = x.col(v).transpose();
  return free;
}

void scatterFree(const Eigen::MatrixX3d& free, const std::vector<int>& free_index, Positions& x)
{
  for (Eigen::Index v = 0; v < x.cols(); ++v)
    if (free_index[v] >= 0)
      x.col(v) = free.row(free_index[v]).transpose();
}

/// Anderson acceleration (type II) of the fixed-point map x ↦ G(x) over a short history.
class Anderson
{
public:
  explicit Anderson(int depth) : depth_(depth)
  {}

  void reset()
  {
    g_.clear();
    f_.clear();
  }

  /// Takes G(x) and the residual G(x) − x; returns the accelerated next iterate.
  Eigen::VectorXd step(const Eigen::VectorXd& g, const Eigen::VectorXd& f)
  {
    g_.push_back(g);
    f_.push_back(f);
    if (static_cast<int>(g_.size()) > depth_ + 1)
    {
      g_.pop_front();
      f_.pop_front();
    }
    const int m = static_cast<int>(g_.size()) - 1;
    if (m == 0)
      return g;
    Eigen::MatrixXd df(f.size(), m), dg(g.size(), m);
    for (int k = 0; k < m; ++k)
    {
      df.col(k) = f_[k + 1] - f_[k];
      dg.col(k) = g_[k + 1] - g_[k];
    }
    const Eigen::VectorXd gamma = df.completeOrthogonalDecomposition().solve(f);
    return g - dg * gamma;
  }

private:
  int depth_;
  std::deque<Eigen::VectorXd> g_, f_;
};
}  // namespace

ShapeMatchingSolver::ShapeMatchingSolver(ShapeMatchingOptions options) : options_(options)
{
  limits_.max_iterations = 20000;
}

SolveReport ShapeMatchingSolver::solve(Paper& paper, const std::vector<char>& fixed)
{
  numerics::SolveBudget budget(limits_);
  SolveReport report;
  const std::vector<RigidFace> faces = rigidFaces(paper);
  const std::vector<Spring> springs = faceSprings(paper);
  int free_count = 0;
  const std::vector<int> free_index = freeIndices(fixed, paper.vertices.size(), &free_count);
  const Positions start = foldedPositions(paper);
  Positions x = start;
  const double residual_tolerance = limits_.tolerance * paper.scale();

  const GlobalStep global(faces, free_index, free_count, x, options_.proximal);
  Anderson anderson(options_.anderson);
  RigidFit fit = fitRigidFaces(faces, x);
  Eigen::MatrixX3d current = gatherFree(x, free_index, free_count);
  double accepted_energy = fit.energy;
  if (!global.ok())
  {
    report.message = "shape matching could not factor its global system";
    report.max_strain = springStrain(springs, x).max;
    return report;
  }
  bool diverged = false;
  while (!diverged)
  {
    report.max_strain = springStrain(springs, x).max;
    if (report.max_strain <= limits_.tolerance && fit.max_residual <= residual_tolerance)
    {
      report.converged = true;
      break;
    }
    if (budget.exhausted(report.iterations))
      break;
    const Eigen::MatrixX3d next = global.solve(fit.rotations, current);
    ++report.iterations;
    Eigen::MatrixX3d candidate = next;
    if (options_.anderson > 0)
    {
      const Eigen::VectorXd g = Eigen::Map<const Eigen::VectorXd>(next.data(), next.size());
      const Eigen::VectorXd f = g - Eigen::Map<const Eigen::VectorXd>(current.data(), current.size());
      const Eigen::VectorXd accelerated = anderson.step(g, f);
      candidate = Eigen::Map<const Eigen::MatrixX3d>(accelerated.data(), next.rows(), 3);
    }
    scatterFree(candidate, free_index, x);
    fit = fitRigidFaces(faces, x);
    if (options_.anderson > 0 && !(fit.energy <= accepted_energy))
    {
      // The accelerated point is worse: take the plain step, which never raises the energy.
      anderson.reset();
      candidate = next;
      scatterFree(candidate, free_index, x);
      fit = fitRigidFaces(faces, x);
    }
    current = candidate;
    accepted_energy = fit.energy;
    diverged = !std::isfinite(fit.energy);
  }
  report.seconds = budget.seconds();
  finishRigidSolve("shape matching", paper, springs, start, x, diverged, fit, "", limits_.tolerance, report);
  return report;
}

}  // namespace virtual_origami::core
