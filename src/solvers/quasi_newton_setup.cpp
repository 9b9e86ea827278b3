#include "quasi_newton_setup.h"

#include <algorithm>

#include "virtual_origami/core/compliant_faces.h"
#include "virtual_origami/core/positions.h"

namespace virtual_origami::core
{
bool QuasiNewtonDriver::AssemblyPlan::matches(const std::vector<Eigen::Triplet<double>>& triplets) const
{
  if (triplets.size() != entries.size())
    return false;
  for (size_t k = 0; k < triplets.size(); ++k)
    if (triplets[k].row() != entries[k].first || triplets[k].col() != entries[k].second)
      return false;
  return true;
}

void QuasiNewtonDriver::AssemblyPlan::plan(const std::vector<Eigen::Triplet<double>>& triplets, int rows)
{
  pattern.resize(rows, rows);
  pattern.setFromTriplets(triplets.begin(), triplets.end());
  pattern.makeCompressed();
  slots.resize(triplets.size());
  entries.resize(triplets.size());
  const int* inner = pattern.innerIndexPtr();
  for (size_t k = 0; k < triplets.size(); ++k)
  {
    const int begin = pattern.outerIndexPtr()[triplets[k].col()];
    const int end = pattern.outerIndexPtr()[triplets[k].col() + 1];
    slots[k] = static_cast<int>(std::lower_bound(inner + begin, inner + end, triplets[k].row()) - inner);
    entries[k] = { triplets[k].row(), triplets[k].col() };
  }
}

QuasiNewtonDriver::Setup::Setup(const Paper& paper, const std::vector<char>& held, const std::vector<double>& target,
                                double stiffness, std::shared_ptr<numerics::SpdFactorization::SharedAnalysis> analysis)
  : crease_pattern(creasePattern(paper))
  , fixed(held)
  , driven_edges(drivenEdges(paper, target))
  , springs(faceSprings(paper))
  , energy(paper, stiffness)
{
  gauss_newton.shareAnalysis(std::move(analysis));
  for (const Face& face : paper.faces)
    face_vertices.push_back(face.vertices);
  free_index = freeIndices(fixed, paper.vertices.size(), &free_count);
  for (size_t v = 0; v < free_index.size(); ++v)
    if (free_index[v] >= 0)
      free_vertices.push_back(static_cast<int>(v));
  energy.setTargets(target);
  constant_matrix = energy.constantMatrix(free_index, free_count);
  // Nothing held: the energy has the rigid motions as null space. A shift far below the
  // faces' stiffness makes the matrix definite without steering the steps.
  const bool anchored = std::any_of(fixed.begin(), fixed.end(), [](char c) { return c != 0; });
  double shift = 0.0;
  for (int k = 0; k < constant_matrix.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(constant_matrix, k); it; ++it)
      if (it.row() == it.col())
        shift = std::max(shift, it.value());
  shift *= anchored ? 1e-12 : 1e-8;
  for (int i = 0; i < free_count; ++i)
    constant_matrix.coeffRef(i, i) += shift;
}

bool QuasiNewtonDriver::Setup::factorConstant()
{
  if (!constant_tried)
  {
    constant_tried = true;
    factor.cholmod().print = 0;  // not definite is answered by the callers, not printed
    {
      const std::unique_lock<std::mutex> blas = numerics::lockBlas();
      factor.compute(constant_matrix);
    }
    factored = factor.info() == Eigen::Success;
    constant_matrix = Eigen::SparseMatrix<double>();
  }
  return factored;
}

Eigen::MatrixX3d QuasiNewtonDriver::Setup::solveConstant(const Eigen::MatrixX3d& rhs)
{
  if (!factorConstant())
    return Eigen::MatrixX3d::Zero(rhs.rows(), 3);
  const std::unique_lock<std::mutex> blas = numerics::lockBlas();
  return factor.solve(rhs);
}

bool QuasiNewtonDriver::Setup::matches(const Paper& paper, const std::vector<char>& held,
                                       const std::vector<double>& target) const
{
  if (held != fixed || paper.faces.size() != face_vertices.size() || creasePattern(paper) != crease_pattern ||
      drivenEdges(paper, target) != driven_edges)
    return false;
  for (size_t f = 0; f < paper.faces.size(); ++f)
    if (paper.faces[f].vertices != face_vertices[f])
      return false;
  return true;
}

std::vector<Vec2> QuasiNewtonDriver::Setup::creasePattern(const Paper& paper)
{
  std::vector<Vec2> c;
  c.reserve(paper.vertices.size());
  for (const Vertex& v : paper.vertices)
    c.push_back(v.crease_pattern);
  return c;
}

std::vector<char> QuasiNewtonDriver::Setup::drivenEdges(const Paper& paper, const std::vector<double>& target)
{
  // A facet (always driven, at its own target) counts apart: turning split edges into facets
  // changes the energy's faces.
  std::vector<char> out(paper.edges.size(), 0);
  for (size_t e = 0; e < out.size(); ++e)
    out[e] = isFacet(paper.edges[e]) ? 2 : e < target.size() && driven(target[e]) ? 1 : 0;
  return out;
}

}  // namespace virtual_origami::core
