#include "virtual_origami/core/convex_partition.h"

#include <algorithm>

#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
namespace
{
bool convexCycle(const std::vector<Vec2>& polygon, const std::vector<int>& cycle, double slack)
{
  const size_t n = cycle.size();
  for (size_t i = 0; i < n; ++i)
  {
    const Vec2& a = polygon[cycle[i]];
    const Vec2& b = polygon[cycle[(i + 1) % n]];
    const Vec2& c = polygon[cycle[(i + 2) % n]];
    if (cross2(b - a, c - b) < -slack)
      return false;
  }
  return true;
}

}  // namespace

std::vector<int> startingAt(const std::vector<int>& cycle, int first)
{
  std::vector<int> turned = cycle;
  std::rotate(turned.begin(), std::find(turned.begin(), turned.end(), first), turned.end());
  return turned;
}

ConvexPieces convexPieces(const std::vector<Vec2>& polygon, double slack)
{
  ConvexPieces result;
  std::vector<int> remaining(polygon.size());
  for (size_t i = 0; i < remaining.size(); ++i)
    remaining[i] = static_cast<int>(i);
  while (remaining.size() > 3)
  {
    const size_t m = remaining.size();
    bool clipped = false;
    for (size_t k = 0; k < m && !clipped; ++k)
    {
      const int p = remaining[(k + m - 1) % m], i = remaining[k], q = remaining[(k + 1) % m];
      const Vec2 &a = polygon[p], &b = polygon[i], &c = polygon[q];
      if (cross2(b - a, c - b) <= slack)
        continue;  // reflex or straight: no ear
      bool empty = true;
      for (int r : remaining)
        if (r != p && r != i && r != q && cross2(b - a, polygon[r] - a) >= -slack &&
            cross2(c - b, polygon[r] - b) >= -slack && cross2(a - c, polygon[r] - c) >= -slack)
          empty = false;
      if (!empty)
        continue;
      result.pieces.push_back({ p, i, q });
      result.diagonals.push_back({ p, q });
      remaining.erase(remaining.begin() + static_cast<long>(k));
      clipped = true;
    }
    if (!clipped)
      return {};
  }
  result.pieces.push_back(remaining);
  // Join the pieces across every diagonal that leaves them convex, the last cut first.
  std::vector<std::array<int, 2>> kept;
  for (auto d = result.diagonals.rbegin(); d != result.diagonals.rend(); ++d)
  {
    const int u = (*d)[0], v = (*d)[1];  // not a structured binding: clang 14 cannot capture one
    const auto hasSide = [](const std::vector<int>& cycle, int from, int to) {
      const size_t n = cycle.size();
      for (size_t i = 0; i < n; ++i)
        if (cycle[i] == from && cycle[(i + 1) % n] == to)
          return true;
      return false;
    };
    auto first = std::find_if(result.pieces.begin(), result.pieces.end(),
                              [&](const std::vector<int>& c) { return hasSide(c, u, v); });
    auto second = std::find_if(result.pieces.begin(), result.pieces.end(),
                               [&](const std::vector<int>& c) { return hasSide(c, v, u); });
    if (first == result.pieces.end() || second == result.pieces.end())
      return {};  // every diagonal has a piece on each side: never happens
    // From v, the first piece ends at u; from u, the second ends at v: joined, v … u … back to v.
    std::vector<int> joined = startingAt(*first, v);
    const std::vector<int> rest = startingAt(*second, u);
    joined.insert(joined.end(), rest.begin() + 1, rest.end() - 1);
    if (!convexCycle(polygon, joined, slack))
    {
      kept.push_back(*d);
      continue;
    }
    *first = joined;
    result.pieces.erase(second);
  }
  result.diagonals.assign(kept.rbegin(), kept.rend());
  return result;
}

}  // namespace virtual_origami::core
