#include "virtual_origami/core/pull.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <utility>
#include <vector>

#include "virtual_origami/core/face_orders.h"

namespace virtual_origami::core
{
namespace
{
/// Faces that came to lie on each other get the order they approached from: the side of
/// one face's plane the other's centroid was on before the pull.
void orderNewStacks(Paper& next, const Paper& before, double tolerance)
{
  // Only faces whose boxes touch can lie on each other: found by a sweep along x, then taken in
  // the order of the pairs (a < b), as every pair was once (a 2,500-face drag spent 0.1 s of
  // each preview testing all 3 million pairs).
  const int faces = static_cast<int>(next.faces.size());
  std::vector<Eigen::AlignedBox3d> boxes(faces);
  for (int f = 0; f < faces; ++f)
    for (int v : next.faces[f].vertices)
      boxes[f].extend(next.vertices[v].folded);
  std::vector<int> by_x(faces);
  std::iota(by_x.begin(), by_x.end(), 0);
  std::sort(by_x.begin(), by_x.end(), [&](int f, int g) { return boxes[f].min().x() < boxes[g].min().x(); });
  std::vector<std::pair<int, int>> near;
  for (int i = 0; i < faces; ++i)
    for (int j = i + 1; j < faces; ++j)
    {
      const int f = by_x[i], g = by_x[j];
      if (boxes[g].min().x() > boxes[f].max().x() + tolerance)
        break;
      if (boxes[f].exteriorDistance(boxes[g]) <= tolerance)
        near.emplace_back(std::min(f, g), std::max(f, g));
    }
  std::sort(near.begin(), near.end());
  for (const auto& [a, b] : near)
  {
    if (faceOrder(next, a, b) != 0 || !facesStacked(next, a, b, tolerance))
      continue;
    const double from = before.faceNormal(a).dot(before.faceCentroid(b) - before.faceCentroid(a));
    if (std::abs(from) > tolerance)
      setFaceOrder(next, a, b, from > 0 ? 1 : -1);
  }
  pruneFaceOrders(next, tolerance);
}
}  // namespace

Expected<PullResult> pull(Paper& paper, const std::vector<PullTarget>& targets, ShapeSolver* solver,
                          const std::vector<int>& held)
{
  using Failure = Expected<PullResult>;
  const int count = static_cast<int>(paper.vertices.size());
  std::vector<char> fixed(paper.vertices.size(), 0);
  for (const PullTarget& target : targets)
  {
    if (target.vertex < 0 || target.vertex >= count)
      return Failure::failure("vertex " + std::to_string(target.vertex) + " does not exist (the model has " +
                              std::to_string(count) + ")");
    if (!target.position.allFinite())
      return Failure::failure("the target of vertex " + std::to_string(target.vertex) + " is not a finite point");
    if (fixed[target.vertex])
      return Failure::failure("vertex " + std::to_string(target.vertex) + " is pulled twice");
    fixed[target.vertex] = 1;
  }
  if (!solver)
    return Failure::failure("pulling vertices needs a solver and none is selected");
  for (int v : held)
    if (v >= 0 && v < count)
      fixed[v] = 1;

  Paper next = paper;
  for (const PullTarget& target : targets)
    next.vertices[target.vertex].folded = target.position;
  PullResult result;
  result.solve = solver->solve(next, fixed);
  if (result.solve.diverged || !result.solve.converged)
    return Failure::failure(solver->name() + " cannot keep the faces rigid with the pulled vertices there: " +
                            result.solve.message + "; the model is unchanged");
  for (const Vertex& v : next.vertices)
    if (!v.folded.allFinite())
      return Failure::failure(solver->name() + " gave a position that is not finite; the model is unchanged");
  for (const PullTarget& target : targets)
    result.residual = std::max(result.residual, (next.vertices[target.vertex].folded - target.position).norm());
  updateFoldAngles(next);
  orderNewStacks(next, paper, 1e-7 * paper.scale());
  paper = std::move(next);
  return result;
}

}  // namespace virtual_origami::core
