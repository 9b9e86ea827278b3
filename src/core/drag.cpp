#include "virtual_origami/core/drag.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "virtual_origami/core/axis.h"
#include "virtual_origami/core/geometry.h"
#include "virtual_origami/core/layer_pick.h"

namespace virtual_origami::core
{
namespace
{
/// The face the eye sees at `press` (seed §3.3.2 step 1): of the faces the view line through
/// the press meets inside, the nearest to the eye; coincident layers by their stack order.
/// `hit` is where the line meets it.
int faceUnder(const Paper& paper, const Vec3& press, const Vec3& view, Vec3* hit = nullptr)
{
  const std::vector<int> faces = facesUnder(paper, press, view);
  if (faces.empty())
    return -1;
  const int best = faces.front();
  if (hit)
  {
    const Vec3 n = paper.faceNormal(best);
    *hit = press + (n.dot(paper.faceCentroid(best) - press) / n.dot(view)) * view;
  }
  return best;
}

std::vector<char> mask(size_t size, const std::vector<int>& members)
{
  std::vector<char> m(size, 0);
  for (int i : members)
    m[i] = 1;
  return m;
}

/// Request-angle limits from every hinge crease on the axis line (rotate() refuses any that
/// would pass ±180°). `side` is +1 when the hinge's left face turns.
void limitAngles(const Paper& paper, RotationRing& ring, const std::vector<char>& moving, double side)
{
  const Vec3 d = (ring.axis_b - ring.axis_a).normalized();
  const double tolerance = 1e-7 * paper.scale();
  const auto onAxis = [&](int v) {
    const Vec3 r = paper.vertices[v].folded - ring.axis_a;
    return (r - r.dot(d) * d).norm() <= tolerance;
  };
  for (const Edge& edge : paper.edges)
  {
    if (!edge.isCrease() || moving[edge.faces[0]] == moving[edge.faces[1]] || !onAxis(edge.vertices[0]) ||
        !onAxis(edge.vertices[1]))
      continue;
    const Vec3 dir = paper.vertices[edge.vertices[1]].folded - paper.vertices[edge.vertices[0]].folded;
    // This crease's fold angle changes by `rate` times the request angle (see rotate()).
    const double rate = (moving[edge.faces[0]] ? 1.0 : -1.0) * side * (dir.dot(d) > 0 ? 1.0 : -1.0);
    const double lo = rate > 0 ? -M_PI - edge.fold_angle : edge.fold_angle - M_PI;
    const double hi = rate > 0 ? M_PI - edge.fold_angle : edge.fold_angle + M_PI;
    ring.min_angle = std::max(ring.min_angle, lo);
    ring.max_angle = std::min(ring.max_angle, hi);
  }
}
}  // namespace

Vec3 onSurface(const Paper& paper, const Vec3& point, const Vec3& view_direction)
{
  if (!point.allFinite() || !view_direction.allFinite() || view_direction.norm() < 1e-12)
    return point;
  Vec3 hit = point;
  faceUnder(paper, point, view_direction.normalized(), &hit);
  return hit;
}

CreaseRequest CreaseDrag::request() const
{
  CreaseRequest r;
  r.start = start.point;
  r.end = end.point;
  r.snap = false;
  return r;
}

CreaseDrag creaseDrag(const Paper& paper, const Vec3& press, const Vec3& pointer, const SnapSettings& settings)
{
  CreaseDrag drag;
  drag.start = snapPoint(paper, press, settings);
  drag.end = snapPoint(paper, pointer, settings, drag.start.kind == SnapKind::Vertex ? drag.start.vertex : -1);
  return drag;
}

Expected<RotationRing> rotationRing(const Paper& paper, const Vec3& press, const Vec3& view_direction, int face,
                                    int axis_edge, bool carry_stack)
{
  using Failure = Expected<RotationRing>;
  if (!press.allFinite() || !view_direction.allFinite() || view_direction.norm() < 1e-12)
    return Failure::failure("the press point or the view direction is not usable");
  const Vec3 view = view_direction.normalized();
  RotationRing ring;
  Vec3 on_face = press;
  ring.face = face >= 0 ? face : faceUnder(paper, press, view, &on_face);
  if (ring.face < 0 || ring.face >= static_cast<int>(paper.faces.size()))
    return Failure::failure("no face under the press point");
  const Vec3 click = on_face;
  if (axis_edge < 0)
  {
    const Expected<int> chosen = automaticAxis(paper, ring.face, click);
    if (!chosen)
      return Failure::failure(chosen.message());
    axis_edge = *chosen;
  }
  if (axis_edge >= static_cast<int>(paper.edges.size()) || !paper.edges[axis_edge].isCrease())
    return Failure::failure("edge " + std::to_string(axis_edge) + " is not a crease to turn about");
  ring.axis_edge = axis_edge;
  const Edge& hinge = paper.edges[axis_edge];
  ring.axis_a = paper.vertices[hinge.vertices[0]].folded;
  ring.axis_b = paper.vertices[hinge.vertices[1]].folded;
  const Vec3 d = (ring.axis_b - ring.axis_a).normalized();

  ring.moving_faces = flapOf(paper, ring.face, axis_edge);
  if (ring.moving_faces.empty())
    ring.moving_faces = { ring.face };
  const std::vector<char> moving = mask(paper.faces.size(), ring.moving_faces);
  if (moving[hinge.faces[0]] == moving[hinge.faces[1]])
    return Failure::failure("face " + std::to_string(ring.face) + " lies on neither side of edge " +
                            std::to_string(axis_edge));

  ring.press = click;
  ring.centre = ring.axis_a + (click - ring.axis_a).dot(d) * d;
  const Vec3 radial = click - ring.centre;
  ring.radius = radial.norm();
  if (ring.radius < 1e-3 * paper.scale())
    return Failure::failure("the press is on the axis; press farther from the crease");
  // w: towards the eye, in the ring's plane; along the axis, any direction across it.
  Vec3 toward_eye = -view - (-view).dot(d) * d;
  ring.w = toward_eye.norm() > 1e-6 ? Vec3(toward_eye.normalized()) : Vec3(d.cross(radial).normalized());
  ring.u = ring.w.cross(d).normalized();
  if (ring.u.dot(radial) < 0)
    ring.u = -ring.u;
  ring.press_angle = std::atan2(radial.dot(ring.w), radial.dot(ring.u));
  ring.edge_on = std::abs(view.dot(d)) < 0.5;

  // rotate() turns the left face of the hinge (or its side) by +angle about a→b.
  const double side = moving[hinge.faces[0]] ? 1.0 : -1.0;
  ring.turn_sign = side * (ring.u.cross(ring.w).dot(d) > 0 ? 1.0 : -1.0);
  // Each way the turn carries the layers in its way along (rotate()'s carry_stack): the hinges
  // that limit it are those between the faces it turns and the rest.
  RotationRing up = ring, down = ring;
  limitAngles(paper, up, mask(paper.faces.size(), turnedFaces(paper, ring.face, axis_edge, 1.0, carry_stack)), side);
  limitAngles(paper, down, mask(paper.faces.size(), turnedFaces(paper, ring.face, axis_edge, -1.0, carry_stack)), side);
  ring.max_angle = up.max_angle;
  ring.min_angle = down.min_angle;
  return ring;
}

double ringAngle(const RotationRing& ring, const Vec3& pointer, const Vec3& view_direction, double previous)
{
  const Vec3 view = view_direction.normalized();
  double travel = 0.0;  // radians the pressed point moves from u towards w
  if (ring.edge_on)
  {
    // The ring seen as a segment from the press point across the axis to its mirror image.
    const auto halfTurn = [&](double s) { return 0.5 * M_PI * (1.0 - std::clamp(s / ring.radius, -1.0, 1.0)); };
    travel = halfTurn((pointer - ring.centre).dot(ring.u)) - halfTurn(ring.radius * std::cos(ring.press_angle));
  }
  else
  {
    // Seed §3.3.3: the pointer's ray meets the ring's plane; the face turns to point there.
    const Vec3 d = ring.u.cross(ring.w);
    const Vec3 on_plane = pointer - ((pointer - ring.centre).dot(d) / view.dot(d)) * view;
    const Vec3 r = on_plane - ring.centre;
    if (r.norm() < 1e-9 * ring.radius)
      return std::clamp(previous, ring.min_angle, ring.max_angle);
    travel = std::atan2(r.dot(ring.w), r.dot(ring.u)) - ring.press_angle;
    const double previous_travel = ring.turn_sign * previous;
    travel += 2 * M_PI * std::round((previous_travel - travel) / (2 * M_PI));
  }
  const double angle = std::clamp(ring.turn_sign * travel, ring.min_angle, ring.max_angle);
  // A half turn the pointer nearly reaches is one: a flap left at 179° is not flat, and the
  // next half turn over it crumples the model.
  const double half = std::copysign(M_PI, angle);
  if (std::abs(angle - half) < kHalfTurnSnap && half >= ring.min_angle && half <= ring.max_angle)
    return half;
  return angle;
}

Vec3 ringPoint(const RotationRing& ring, double angle)
{
  const double a = ring.press_angle + ring.turn_sign * angle;
  return ring.centre + ring.radius * (std::cos(a) * ring.u + std::sin(a) * ring.w);
}

}  // namespace virtual_origami::core
