#include "virtual_origami/core/planar_graph.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
namespace
{
std::uint64_t cellKey(long long x, long long y)
{
  return (static_cast<std::uint64_t>(x) << 32) ^ static_cast<std::uint64_t>(y & 0xffffffffLL);
}

}  // namespace

SnappedPoints::SnappedPoints(double tolerance) : tolerance_(tolerance)
{}

long long SnappedPoints::cell(double x) const
{
  return static_cast<long long>(std::floor(x / tolerance_));
}

int SnappedPoints::snap(const Vec2& p)
{
  const long long cx = cell(p.x()), cy = cell(p.y());
  int best = -1;
  double best_distance = tolerance_;
  for (long long x = cx - 1; x <= cx + 1; ++x)
    for (long long y = cy - 1; y <= cy + 1; ++y)
    {
      const auto it = cells_.find(cellKey(x, y));
      if (it == cells_.end())
        continue;
      for (int i : it->second)
      {
        const double d = (points_[i] - p).norm();
        if (d <= best_distance)
        {
          best = i;
          best_distance = d;
        }
      }
    }
  if (best >= 0)
    return best;
  points_.push_back(p);
  cells_[cellKey(cx, cy)].push_back(static_cast<int>(points_.size()) - 1);
  return static_cast<int>(points_.size()) - 1;
}

std::vector<std::vector<int>> pointsAlongSegments(const std::vector<SnappedSegment>& segments, SnappedPoints& points,
                                                  double tolerance)
{
  std::vector<std::vector<int>> on(segments.size());  // points met between the ends
  const auto touch = [&](size_t s, int id) {
    const SnappedSegment& g = segments[s];
    if (id != g.ia && id != g.ib && pointSegmentDistance(points.points()[id], g.a, g.b) <= tolerance)
      on[s].push_back(id);
  };
  // Sweep in x: only segments whose x ranges overlap can meet.
  std::vector<int> order(segments.size());
  for (size_t i = 0; i < order.size(); ++i)
    order[i] = static_cast<int>(i);
  const auto low_x = [&](int i) { return std::min(segments[i].a.x(), segments[i].b.x()); };
  std::sort(order.begin(), order.end(), [&](int i, int j) { return low_x(i) < low_x(j); });
  for (size_t oi = 0; oi < order.size(); ++oi)
  {
    const int si = order[oi];
    const SnappedSegment& s = segments[si];
    const double high_x = std::max(s.a.x(), s.b.x()) + tolerance;
    const double s_low_y = std::min(s.a.y(), s.b.y()) - tolerance, s_high_y = std::max(s.a.y(), s.b.y()) + tolerance;
    for (size_t oj = oi + 1; oj < order.size() && low_x(order[oj]) <= high_x; ++oj)
    {
      const int ti = order[oj];
      const SnappedSegment& t = segments[ti];
      if (std::max(t.a.y(), t.b.y()) < s_low_y || std::min(t.a.y(), t.b.y()) > s_high_y)
        continue;
      touch(si, t.ia);
      touch(si, t.ib);
      touch(ti, s.ia);
      touch(ti, s.ib);
      // A proper crossing, away from every end (ends are the touches above).
      const Vec2 d1 = s.b - s.a, d2 = t.b - t.a;
      const double denominator = cross2(d1, d2);
      if (std::abs(denominator) <= 1e-12 * d1.norm() * d2.norm())
        continue;
      const double u = cross2(t.a - s.a, d2) / denominator, v = cross2(t.a - s.a, d1) / denominator;
      const double margin_u = tolerance / d1.norm(), margin_v = tolerance / d2.norm();
      if (u > margin_u && u < 1 - margin_u && v > margin_v && v < 1 - margin_v)
      {
        const int id = points.snap(s.a + u * d1);
        for (int g : { si, ti })
          if (id != segments[g].ia && id != segments[g].ib)
            on[g].push_back(id);
      }
    }
  }
  std::vector<std::vector<int>> along_segments(segments.size());
  for (size_t i = 0; i < segments.size(); ++i)
  {
    const SnappedSegment& s = segments[i];
    std::vector<std::pair<double, int>> along{ { 0.0, s.ia }, { 1.0, s.ib } };
    const Vec2 d = s.b - s.a;
    for (int id : on[i])
      along.emplace_back((points.points()[id] - s.a).dot(d) / d.squaredNorm(), id);
    std::sort(along.begin(), along.end());
    for (const auto& [t, id] : along)
      if (along_segments[i].empty() || along_segments[i].back() != id)
        along_segments[i].push_back(id);
  }
  return along_segments;
}

Rotation rotationSystem(const std::vector<Vec2>& points, const std::vector<std::array<int, 2>>& edges)
{
  const auto from = [&](int h) { return edges[h / 2][h % 2]; };
  const auto to = [&](int h) { return edges[h / 2][1 - h % 2]; };
  const int half_count = 2 * static_cast<int>(edges.size());
  std::vector<double> direction(half_count);
  Rotation rotation;
  rotation.outgoing.resize(points.size());
  for (int h = 0; h < half_count; ++h)
  {
    const Vec2 d = points[to(h)] - points[from(h)];
    direction[h] = std::atan2(d.y(), d.x());
    rotation.outgoing[from(h)].push_back(h);
  }
  std::vector<int> slot(half_count);
  for (std::vector<int>& around : rotation.outgoing)
  {
    std::sort(around.begin(), around.end(), [&](int a, int b) { return direction[a] < direction[b]; });
    for (size_t i = 0; i < around.size(); ++i)
      slot[around[i]] = static_cast<int>(i);
  }
  // Arriving along h, the face on the left leaves along the first edge clockwise from the twin.
  rotation.next.resize(half_count);
  for (int h = 0; h < half_count; ++h)
  {
    const std::vector<int>& around = rotation.outgoing[to(h)];
    const int n = static_cast<int>(around.size());
    rotation.next[h] = around[(slot[h ^ 1] + n - 1) % n];
  }
  return rotation;
}

std::vector<std::vector<int>> traceHalfEdgeCycles(const std::vector<Vec2>& points,
                                                  const std::vector<std::array<int, 2>>& edges)
{
  const int half_count = 2 * static_cast<int>(edges.size());
  const std::vector<int> next = rotationSystem(points, edges).next;
  std::vector<char> visited(half_count, 0);
  std::vector<std::vector<int>> cycles;
  for (int start = 0; start < half_count; ++start)
  {
    if (visited[start])
      continue;
    std::vector<int> cycle;
    for (int h = start; !visited[h]; h = next[h])
    {
      visited[h] = 1;
      cycle.push_back(h);
    }
    cycles.push_back(std::move(cycle));
  }
  return cycles;
}

std::vector<TracedFace> boundedFaces(const std::vector<Vec2>& points, const std::vector<std::array<int, 2>>& edges,
                                     double min_area)
{
  std::vector<TracedFace> faces;
  for (std::vector<int>& cycle : traceHalfEdgeCycles(points, edges))
  {
    TracedFace face;
    std::vector<Vec2> polygon;
    for (int h : cycle)
    {
      face.vertices.push_back(edges[h / 2][h % 2]);
      polygon.push_back(points[face.vertices.back()]);
    }
    if (!(signedArea(polygon) > min_area))  // the outer face, a sliver, or overflow
      continue;
    face.half_edges = std::move(cycle);
    faces.push_back(std::move(face));
  }
  return faces;
}

}  // namespace virtual_origami::core
