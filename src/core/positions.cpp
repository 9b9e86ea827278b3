#include "virtual_origami/core/positions.h"

namespace virtual_origami::core
{
Positions foldedPositions(const Paper& paper)
{
  Positions x(3, paper.vertices.size());
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    x.col(static_cast<Eigen::Index>(v)) = paper.vertices[v].folded;
  return x;
}

void setFoldedPositions(Paper& paper, const Positions& positions)
{
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    paper.vertices[v].folded = positions.col(static_cast<Eigen::Index>(v));
}

std::vector<int> freeIndices(const std::vector<char>& fixed, size_t vertex_count, int* free_count)
{
  std::vector<int> index(vertex_count, -1);
  int count = 0;
  for (size_t v = 0; v < vertex_count; ++v)
    if (v >= fixed.size() || !fixed[v])
      index[v] = count++;
  if (free_count)
    *free_count = count;
  return index;
}

}  // namespace virtual_origami::core
