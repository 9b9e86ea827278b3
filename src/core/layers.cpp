#include "virtual_origami/core/layers.h"

#include <cmath>
#include <deque>

namespace virtual_origami::core
{
std::vector<int> levelsFromOrders(size_t faces, const std::vector<std::array<int, 2>>& below_above)
{
  std::vector<std::vector<int>> above(faces);  // above[f]: faces directly above f
  std::vector<int> below_count(faces, 0);
  for (const auto& [low, high] : below_above)
  {
    above[low].push_back(high);
    ++below_count[high];
  }
  // Longest path from the bottom (Kahn's order); faces left in a cycle keep what they have.
  std::vector<int> level(faces, 0);
  std::deque<int> ready;
  for (size_t f = 0; f < faces; ++f)
    if (below_count[f] == 0)
      ready.push_back(static_cast<int>(f));
  while (!ready.empty())
  {
    const int f = ready.front();
    ready.pop_front();
    for (int g : above[f])
    {
      level[g] = std::max(level[g], level[f] + 1);
      if (--below_count[g] == 0)
        ready.push_back(g);
    }
  }
  return level;
}

std::vector<int> stackLevels(const Paper& paper)
{
  const size_t n = paper.faces.size();
  std::vector<std::array<int, 2>> below_above;
  for (const FaceOrder& o : paper.face_orders)
  {
    if (o.face < 0 || o.other < 0 || static_cast<size_t>(o.face) >= n || static_cast<size_t>(o.other) >= n ||
        o.above == 0 || o.face == o.other)
      continue;
    // `above` is relative to the face's front normal; turn it into +z.
    const bool face_up = paper.faceNormal(o.face).z() >= 0;
    const bool other_is_higher = (o.above > 0) == face_up;
    below_above.push_back(other_is_higher ? std::array<int, 2>{ o.face, o.other } : std::array<int, 2>{ o.other, o.face });
  }
  return levelsFromOrders(n, below_above);
}

int layerCount(const Paper& paper, const Vec3& point, double margin)
{
  int count = 0;
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const std::vector<int>& vs = paper.faces[f].vertices;
    const Vec3 n = paper.faceNormal(static_cast<int>(f));
    if (std::abs(n.dot(point - paper.faceCentroid(static_cast<int>(f)))) > margin)
      continue;
    bool inside = true;
    for (size_t i = 0; i < vs.size() && inside; ++i)
    {
      const Vec3& a = paper.vertices[vs[i]].folded;
      const Vec3& b = paper.vertices[vs[(i + 1) % vs.size()]].folded;
      // Counter-clockwise about the front normal: inside lies left of every side.
      inside = (b - a).normalized().cross(point - a).dot(n) > margin;
    }
    count += inside ? 1 : 0;
  }
  return count;
}

}  // namespace virtual_origami::core
