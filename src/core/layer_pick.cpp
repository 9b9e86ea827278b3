#include "virtual_origami/core/layer_pick.h"

#include <algorithm>
#include <cmath>

#include "virtual_origami/core/geometry.h"
#include "virtual_origami/core/layers.h"

namespace virtual_origami::core
{
namespace
{
struct Candidate
{
  int index = -1;
  double depth = 0.0;     // along the sight line from the point
  int order = 0;          // lower: nearer the eye among coincident layers
  int then = 0;           // lower: nearer the eye where `order` ties (a crease's farther layer)
  double distance = 0.0;  // from the sight line
};

/// Nearest the eye first: depths within `tolerance` of each other are one depth (a flat stack
/// drawn apart only on screen), ordered by layer, then by distance from the sight line.
/// Distances within `tolerance` are one distance, taken by index: coincident creases (or
/// vertices) of a stack differ only by rounding there, and the rounding changed with the side
/// of the line the click was on; so the list is the same from either side.
std::vector<int> ordered(std::vector<Candidate> candidates, double tolerance)
{
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.depth < b.depth; });
  const auto nearer = [](const Candidate& a, const Candidate& b) {
    if (a.order != b.order)
      return a.order < b.order;
    return a.then != b.then ? a.then < b.then : a.distance < b.distance;
  };
  const auto byIndex = [](const Candidate& a, const Candidate& b) { return a.index < b.index; };
  for (size_t begin = 0; begin < candidates.size();)
  {
    size_t end = begin + 1;
    while (end < candidates.size() && candidates[end].depth <= candidates[begin].depth + tolerance)
      ++end;
    std::sort(candidates.begin() + begin, candidates.begin() + end, nearer);
    for (size_t tie = begin; tie < end;)
    {
      size_t last = tie + 1;
      while (last < end && candidates[last].order == candidates[tie].order &&
             candidates[last].then == candidates[tie].then &&
             candidates[last].distance <= candidates[last - 1].distance + tolerance)
        ++last;
      std::sort(candidates.begin() + tie, candidates.begin() + last, byIndex);
      tie = last;
    }
    begin = end;
  }
  std::vector<int> out;
  for (const Candidate& c : candidates)
    out.push_back(c.index);
  return out;
}

/// A stack level as an order along the view: from above (view down −z) the highest level first.
int viewOrder(int level, const Vec3& view)
{
  return view.z() <= 0 ? -level : level;
}

/// Distance of `p` from the sight line through `point`, and its depth along it.
void alongSight(const Vec3& p, const Vec3& point, const Vec3& view, double& distance, double& depth)
{
  depth = (p - point).dot(view);
  distance = (p - point - depth * view).norm();
}
}  // namespace

std::vector<int> facesUnder(const Paper& paper, const Vec3& point, const Vec3& view_direction)
{
  const Vec3 view = view_direction.normalized();
  const std::vector<int> levels = stackLevels(paper);
  const double tolerance = 1e-6 * paper.scale();
  std::vector<Candidate> candidates;
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const int face = static_cast<int>(f);
    const Vec3 n = paper.faceNormal(face);
    if (std::abs(n.dot(view)) < 1e-9)
      continue;  // seen edge-on
    const double t = n.dot(paper.faceCentroid(face) - point) / n.dot(view);
    const FaceProjection hit = projectOntoFace(paper, face, point + t * view);
    if (hit.inside && hit.distance <= tolerance)
      candidates.push_back({ face, t, viewOrder(levels[f], view), 0, 0.0 });
  }
  return ordered(std::move(candidates), tolerance);
}

std::vector<int> creasesUnder(const Paper& paper, const Vec3& point, const Vec3& view_direction, double radius)
{
  const Vec3 view = view_direction.normalized();
  const std::vector<int> levels = stackLevels(paper);
  std::vector<Candidate> candidates;
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease())
      continue;
    const Vec3& a = paper.vertices[edge.vertices[0]].folded;
    const Vec3& b = paper.vertices[edge.vertices[1]].folded;
    // The segment's point nearest the sight line, seen along it.
    const Vec3 ab = b - a;
    const Vec3 ab_across = ab - ab.dot(view) * view;
    const Vec3 pa_across = (point - a) - (point - a).dot(view) * view;
    const double s = ab_across.squaredNorm() > 0 ? std::clamp(pa_across.dot(ab_across) / ab_across.squaredNorm(), 0.0, 1.0) : 0.0;
    Candidate c;
    c.index = static_cast<int>(e);
    alongSight(a + s * ab, point, view, c.distance, c.depth);
    if (c.distance > radius)
      continue;
    // A fold's crease lies at the layers it joins: the nearer first, then the farther (of
    // nested folds the outer one is seen first, from either side of the stack).
    const int near0 = viewOrder(levels[edge.faces[0]], view), near1 = viewOrder(levels[edge.faces[1]], view);
    c.order = std::min(near0, near1);
    c.then = std::max(near0, near1);
    candidates.push_back(c);
  }
  return ordered(std::move(candidates), 1e-6 * paper.scale());
}

std::vector<int> verticesUnder(const Paper& paper, const Vec3& point, const Vec3& view_direction, double radius)
{
  const Vec3 view = view_direction.normalized();
  const std::vector<int> levels = stackLevels(paper);
  std::vector<int> order(paper.vertices.size(), 1 << 30), then(paper.vertices.size(), -(1 << 30));
  for (size_t f = 0; f < paper.faces.size(); ++f)
    for (int v : paper.faces[f].vertices)
    {
      order[v] = std::min(order[v], viewOrder(levels[f], view));
      then[v] = std::max(then[v], viewOrder(levels[f], view));
    }
  std::vector<Candidate> candidates;
  for (size_t v = 0; v < paper.vertices.size(); ++v)
  {
    Candidate c;
    c.index = static_cast<int>(v);
    alongSight(paper.vertices[v].folded, point, view, c.distance, c.depth);
    c.order = order[v];
    c.then = then[v];
    if (c.distance <= radius)
      candidates.push_back(c);
  }
  return ordered(std::move(candidates), 1e-6 * paper.scale());
}

}  // namespace virtual_origami::core
