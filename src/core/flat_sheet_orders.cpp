#include "virtual_origami/core/flat_sheet_orders.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/flat_vertices.h"

namespace virtual_origami::core
{
namespace
{
/// A crease left unfolded: its faces lie flat side by side, one sheet; `a`→`b` its folded ends.
struct UnfoldedCrease
{
  int edge = -1;
  int left = -1, right = -1;  // the faces left and right of a→b, seen along the faces' front normal
  Vec3 a, b, normal;
};

/// +1 when the face lies left of the line a→b in the plane with front normal `normal`, −1 right.
int sideOf(const Paper& paper, int face, const Vec3& a, const Vec3& b, const Vec3& normal)
{
  return normal.cross(b - a).dot(paper.faceCentroid(face) - a) > 0 ? 1 : -1;
}

std::vector<UnfoldedCrease> unfoldedCreases(const Paper& paper)
{
  std::vector<UnfoldedCrease> creases;
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& edge = paper.edges[e];
    if (!edge.isCrease() || std::abs(edge.fold_angle) > kFlatAngleTolerance)
      continue;
    UnfoldedCrease crease{ static_cast<int>(e),
                           edge.faces[0],
                           edge.faces[1],
                           paper.vertices[edge.vertices[0]].folded,
                           paper.vertices[edge.vertices[1]].folded,
                           paper.faceNormal(edge.faces[0]) };
    if (sideOf(paper, crease.left, crease.a, crease.b, crease.normal) < 0)
      std::swap(crease.left, crease.right);
    creases.push_back(crease);
  }
  return creases;
}

/// Whether the segment a→b runs through the inside of the (flat, convex) face, off its sides,
/// for more than `tolerance`.
bool runsInside(const Paper& paper, int face, const Vec3& a, const Vec3& b, double tolerance)
{
  const Vec3 normal = paper.faceNormal(face);
  const std::vector<int>& vs = paper.faces[face].vertices;
  const auto inward = [&](size_t i) {  // the side's inward normal and a point of it
    const Vec3& p = paper.vertices[vs[i]].folded;
    const Vec3& q = paper.vertices[vs[(i + 1) % vs.size()]].folded;
    return std::pair{ normal.cross(q - p).normalized(), p };
  };
  double t0 = 0.0, t1 = 1.0;  // the part of a→b inside the face
  for (size_t i = 0; i < vs.size() && t0 <= t1; ++i)
  {
    const auto [n, p] = inward(i);
    const double da = n.dot(a - p), db = n.dot(b - p);
    if (da < 0 && db < 0)
      return false;
    if (da < 0)
      t0 = std::max(t0, da / (da - db));
    else if (db < 0)
      t1 = std::min(t1, da / (da - db));
  }
  if ((t1 - t0) * (b - a).norm() <= tolerance)
    return false;
  const Vec3 middle = a + 0.5 * (t0 + t1) * (b - a);
  for (size_t i = 0; i < vs.size(); ++i)
  {
    const auto [n, p] = inward(i);
    if (n.dot(middle - p) <= tolerance)
      return false;
  }
  return true;
}

/// Whether the segment c→d lies on the line of a→b and overlaps a→b by more than `tolerance`.
bool onOneLine(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double tolerance)
{
  const Vec3 u = (b - a).normalized();
  const auto off = [&](const Vec3& p) { return ((p - a) - (p - a).dot(u) * u).norm(); };
  if (off(c) > tolerance || off(d) > tolerance)
    return false;
  const double c_at = u.dot(c - a), d_at = u.dot(d - a);
  return std::min((b - a).norm(), std::max(c_at, d_at)) - std::max(0.0, std::min(c_at, d_at)) > tolerance;
}

std::string sheetText(const Paper& paper, const UnfoldedCrease& u)
{
  return faceText(paper, u.left) + " and " + faceText(paper, u.right) + ", one flat sheet across " +
         creaseText(paper, u.edge);
}
}  // namespace

std::vector<SheetOrderClash> sheetOrderClashes(const Paper& paper, double tolerance)
{
  std::vector<SheetOrderClash> clashes;
  const std::vector<UnfoldedCrease> unfolded = unfoldedCreases(paper);
  // `why` is written only for a clash: writing it for every pair judged took a sixth of a flap
  // drag's resolving.
  const auto judge = [&](int f, int g, int f2, int g2, int relation, const auto& why) {
    if (!facesStacked(paper, f, g, tolerance) || !facesStacked(paper, f2, g2, tolerance))
      return;
    const int first = faceOrder(paper, f, g), second = faceOrder(paper, f2, g2);
    if (first != 0 && second != 0 && first != relation * second)
      clashes.push_back({ f, g, f2, g2, relation, why() });
  };
  for (const UnfoldedCrease& u : unfolded)
    for (size_t h = 0; h < paper.faces.size(); ++h)
    {
      const int layer = static_cast<int>(h);
      if (layer != u.left && layer != u.right && runsInside(paper, layer, u.a, u.b, tolerance))
        judge(u.left, layer, u.right, layer, 1, [&] {
          return faceText(paper, layer) + " and " + sheetText(paper, u) +
                 ", pass through each other: it lies above one of the two faces and below the other";
        });
    }
  for (size_t i = 0; i < unfolded.size(); ++i)
    for (size_t j = i + 1; j < unfolded.size(); ++j)
    {
      const UnfoldedCrease &u = unfolded[i], &w = unfolded[j];
      if (!onOneLine(u.a, u.b, w.a, w.b, tolerance) || std::abs(std::abs(u.normal.dot(w.normal)) - 1.0) > 1e-6)
        continue;
      const int w_left = sideOf(paper, w.left, u.a, u.b, u.normal) > 0 ? w.left : w.right;
      const int w_right = w_left == w.left ? w.right : w.left;
      judge(u.left, w_left, u.right, w_right, 1, [&] {
        return sheetText(paper, u) + ", and " + sheetText(paper, w) +
               ", pass through each other: one lies above the other on one side of the crease and below it on "
               "the other";
      });
    }
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const Edge& fold = paper.edges[e];
    if (!fold.isCrease() || std::abs(std::abs(fold.fold_angle) - M_PI) > kFlatAngleTolerance)
      continue;
    const Vec3 a = paper.vertices[fold.vertices[0]].folded, b = paper.vertices[fold.vertices[1]].folded;
    const int f = fold.faces[0], g = fold.faces[1];
    for (const UnfoldedCrease& u : unfolded)
    {
      if (!onOneLine(a, b, u.a, u.b, tolerance) || std::abs(std::abs(u.normal.dot(paper.faceNormal(f))) - 1.0) > 1e-6)
        continue;
      // The face of the sheet on the fold's side of the line (f and g lie on one side).
      const int h = sideOf(paper, u.left, a, b, paper.faceNormal(f)) == sideOf(paper, f, a, b, paper.faceNormal(f)) ?
                        u.left :
                        u.right;
      if (h == f || h == g || !facesStacked(paper, g, h, tolerance))
        continue;
      // f and g face opposite ways: h outside both is order(f, h) = −order(g, h).
      judge(f, h, g, h, -1, [&] {
        return faceText(paper, h) + ", in " + sheetText(paper, u) + ", lies between " + faceText(paper, f) + " and " +
               faceText(paper, g) + ", folded on each other at " + creaseText(paper, static_cast<int>(e)) +
               " on the same line: it would go through that fold";
      });
    }
  }
  return clashes;
}

}  // namespace virtual_origami::core
