#include "virtual_origami/core/bend_reach.h"

#include <cstdio>
#include <string>

namespace virtual_origami::core
{
Status bendingReaches(const Paper& paper, const PullTarget& target, const std::vector<int>& held)
{
  const int count = static_cast<int>(paper.vertices.size());
  if (target.vertex < 0 || target.vertex >= count)
    return failure("vertex " + std::to_string(target.vertex) + " does not exist (the model has " +
                   std::to_string(count) + ")");
  if (!target.position.allFinite())
    return failure("the point to drag vertex " + std::to_string(target.vertex) + " to is not a finite point");
  const Vec2 from = paper.vertices[target.vertex].crease_pattern;
  // Rounding of lengths the solvers keep to this: a point exactly at full stretch is reached.
  const double slack = 1e-9 * paper.scale();
  int worst = -1;
  double worst_excess = 0.0, worst_apart = 0.0, worst_distance = 0.0;
  for (int v : held)
  {
    if (v < 0 || v >= count)
      continue;
    if (v == target.vertex)
      return failure("vertex " + std::to_string(v) + " is pinned; release it before dragging it");
    const double apart = (paper.vertices[v].crease_pattern - from).norm();
    const double distance = (paper.vertices[v].folded - target.position).norm();
    if (distance - apart > std::max(slack, worst_excess))
    {
      worst = v;
      worst_excess = distance - apart;
      worst_apart = apart;
      worst_distance = distance;
    }
  }
  if (worst < 0)
    return success();
  char text[200];
  std::snprintf(text, sizeof text,
                "paper does not stretch: the point is %.3g m from pinned vertex %d, which lies %.3g m from vertex %d "
                "on the sheet",
                worst_distance, worst, worst_apart, target.vertex);
  return failure(text);
}

}  // namespace virtual_origami::core
