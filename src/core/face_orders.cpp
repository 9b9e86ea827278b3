#include "virtual_origami/core/face_orders.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace virtual_origami::core
{
namespace
{
/// The face's folded vertices in a 2D basis of the plane with normal `normal`.
std::vector<Vec2> inPlane(const Paper& paper, int face, const Vec3& e1, const Vec3& e2)
{
  std::vector<Vec2> points;
  for (int v : paper.faces[face].vertices)
    points.emplace_back(e1.dot(paper.vertices[v].folded), e2.dot(paper.vertices[v].folded));
  return points;
}

/// Convex polygons overlap with positive area when no side of either separates them by
/// more than −tolerance (separating axis theorem on both polygons' side normals).
bool convexOverlap(const std::vector<Vec2>& a, const std::vector<Vec2>& b, double tolerance)
{
  for (const std::vector<Vec2>* poly : { &a, &b })
  {
    const std::vector<Vec2>& p = *poly;
    for (size_t i = 0; i < p.size(); ++i)
    {
      const Vec2 side = p[(i + 1) % p.size()] - p[i];
      if (side.norm() <= tolerance)
        continue;
      const Vec2 axis = Vec2(-side.y(), side.x()).normalized();
      double a_min = std::numeric_limits<double>::infinity(), a_max = -a_min, b_min = a_min, b_max = -a_min;
      for (const Vec2& q : a)
      {
        a_min = std::min(a_min, axis.dot(q));
        a_max = std::max(a_max, axis.dot(q));
      }
      for (const Vec2& q : b)
      {
        b_min = std::min(b_min, axis.dot(q));
        b_max = std::max(b_max, axis.dot(q));
      }
      if (std::min(a_max, b_max) - std::max(a_min, b_min) <= tolerance)
        return false;
    }
  }
  return true;
}

bool validFace(const Paper& paper, int f)
{
  return f >= 0 && f < static_cast<int>(paper.faces.size());
}
}  // namespace

bool facesStacked(const Paper& paper, int face, int other, double tolerance)
{
  if (face == other || !validFace(paper, face) || !validFace(paper, other))
    return false;
  const Vec3 n = paper.faceNormal(face);
  const Vec3 m = paper.faceNormal(other);
  if (std::abs(n.dot(m)) < 1.0 - 1e-9)
    return false;
  const Vec3 origin = paper.faceCentroid(face);
  for (int v : paper.faces[other].vertices)
    if (std::abs(n.dot(paper.vertices[v].folded - origin)) > tolerance)
      return false;
  const Vec3 e1 = n.unitOrthogonal();
  const Vec3 e2 = n.cross(e1);
  return convexOverlap(inPlane(paper, face, e1, e2), inPlane(paper, other, e1, e2), tolerance);
}

int faceOrder(const Paper& paper, int face, int other)
{
  for (const FaceOrder& o : paper.face_orders)
  {
    if (o.face == face && o.other == other)
      return o.above;
    if (o.face == other && o.other == face)
    {
      // `face` is on the side of `other` given by o.above, measured along other's normal; from
      // face's side that flips when the two normals point the same way.
      const bool same_way = paper.faceNormal(face).dot(paper.faceNormal(other)) > 0;
      return same_way ? -o.above : o.above;
    }
  }
  return 0;
}

void setFaceOrder(Paper& paper, int face, int other, int above)
{
  auto& orders = paper.face_orders;
  orders.erase(std::remove_if(orders.begin(), orders.end(),
                              [&](const FaceOrder& o) {
                                return (o.face == face && o.other == other) || (o.face == other && o.other == face);
                              }),
               orders.end());
  orders.push_back({ face, other, above });
}

void clearFaceOrdersAcross(Paper& paper, const std::vector<char>& faces)
{
  const auto inside = [&](int f) { return f >= 0 && f < static_cast<int>(faces.size()) && faces[f]; };
  auto& orders = paper.face_orders;
  orders.erase(std::remove_if(orders.begin(), orders.end(),
                              [&](const FaceOrder& o) { return inside(o.face) != inside(o.other); }),
               orders.end());
}

void pruneFaceOrders(Paper& paper, double tolerance)
{
  auto& orders = paper.face_orders;
  orders.erase(std::remove_if(orders.begin(), orders.end(),
                              [&](const FaceOrder& o) { return !facesStacked(paper, o.face, o.other, tolerance); }),
               orders.end());
}

void inheritFaceOrders(Paper& paper, int parent, int child)
{
  const std::vector<FaceOrder> orders = paper.face_orders;
  for (const FaceOrder& o : orders)
  {
    if (o.face == parent && o.other != child)
      paper.face_orders.push_back({ child, o.other, o.above });
    else if (o.other == parent && o.face != child)
      paper.face_orders.push_back({ o.face, child, o.above });
  }
}

}  // namespace virtual_origami::core
