// The planar straight-line graph that segments draw: their ends merged within a tolerance, the
// segments split wherever they meet, and the faces traced. The FOLD and ORIPA readers build
// their crease patterns with it.
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
/// Points merged within a tolerance, found through a hash grid of that cell size.
class SnappedPoints
{
public:
  explicit SnappedPoints(double tolerance);

  /// The id of the nearest point within the tolerance, or of `p`, added.
  int snap(const Vec2& p);

  const std::vector<Vec2>& points() const
  {
    return points_;
  }

private:
  long long cell(double x) const;

  double tolerance_;
  std::vector<Vec2> points_;
  std::unordered_map<std::uint64_t, std::vector<int>> cells_;
};

/// A segment from `a` to `b`, its ends snapped to the points `ia` and `ib`.
struct SnappedSegment
{
  Vec2 a = Vec2::Zero();
  Vec2 b = Vec2::Zero();
  int ia = -1;
  int ib = -1;
};

/// For each segment, the points along it from `ia` to `ib`, never one twice in a row: its ends,
/// the ends of the other segments within `tolerance` of it, and where it crosses another away
/// from their ends (snapped into `points`). Consecutive points are the pieces it splits into.
std::vector<std::vector<int>> pointsAlongSegments(const std::vector<SnappedSegment>& segments, SnappedPoints& points,
                                                  double tolerance);

/// The half-edges leaving each point, counter-clockwise by direction (half-edge 2e + s runs from
/// edges[e][s] to edges[e][1 - s]), and for each half-edge the one that follows it round the face
/// on its left: at its end, the first edge clockwise from its twin.
struct Rotation
{
  std::vector<std::vector<int>> outgoing;
  std::vector<int> next;
};
Rotation rotationSystem(const std::vector<Vec2>& points, const std::vector<std::array<int, 2>>& edges);

/// The faces of a planar graph, each a cycle of half-edges with the face on its left: the
/// bounded faces of a connected graph come out counter-clockwise, the outer face clockwise.
/// Half-edge 2e + s runs from edges[e][s] to edges[e][1 - s]; its twin is h ^ 1.
std::vector<std::vector<int>> traceHalfEdgeCycles(const std::vector<Vec2>& points,
                                                  const std::vector<std::array<int, 2>>& edges);

/// A bounded face: its corners counter-clockwise, and the half-edges from each corner to the next.
struct TracedFace
{
  std::vector<int> vertices;
  std::vector<int> half_edges;
};

/// The cycles of traceHalfEdgeCycles that enclose more than `min_area` counter-clockwise: the
/// bounded faces, without the outer face and without the slivers rounding leaves.
std::vector<TracedFace> boundedFaces(const std::vector<Vec2>& points, const std::vector<std::array<int, 2>>& edges,
                                     double min_area);

}  // namespace virtual_origami::core
