// How near a curved sheet's layers come to each other: the smallest distance between a node
// and a triangle, or two edges, of the mesh that share no node. Zero where layers touch or
// cross; a layered start (layered_start.h) has them apart.
#pragma once

#include <array>

#include "virtual_origami/curved/curved_mesh.h"

namespace virtual_origami::core
{
struct ClosestApproach
{
  double distance = 0.0;  // infinity when no pair comes within the search's reach
  int kind = -1;          // 0: node and triangle, 1: two edges
  std::array<int, 2> pair{ -1, -1 };  // (node, triangle) or (edge, edge)
};

/// The nearest pair among those whose boxes lie within `reach` of each other (a pair farther
/// apart than `reach` is not looked at).
ClosestApproach closestApproach(const CurvedMesh& mesh, const Positions& x, double reach);

/// The nearest point of triangle abc to p (on the face, a side or a corner), as its barycentric
/// weights of a, b and c.
Vec3 nearestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
/// The nearest points of the segments pq and rs, as their parameters: p + u·(q − p), r + v·(s − r).
Vec2 nearestOnSegments(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s);

/// Distance from p to triangle abc.
double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);
/// Distance between the segments pq and rs.
double segmentDistance(const Vec3& p, const Vec3& q, const Vec3& r, const Vec3& s);

}  // namespace virtual_origami::core
