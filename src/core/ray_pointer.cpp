#include "virtual_origami/core/ray_pointer.h"

#include <cmath>

#include "virtual_origami/core/layer_pick.h"

namespace virtual_origami::core
{
std::optional<Vec3> sheetPointOnRay(const Paper& paper, const SightRay& ray, const PickableSheet& sheet)
{
  const Vec3& eye = ray.camera.eye;
  if (paper.vertices.empty() || !eye.allFinite() || !ray.direction.allFinite() || ray.direction.norm() < 1e-12)
    return std::nullopt;
  const Vec3 view = ray.direction.normalized();
  // The faces on the sight line, nearest the eye first; the first in front of the eye is seen.
  for (int face : facesUnder(paper, eye, view))
  {
    const Vec3 n = paper.faceNormal(face);
    const double t = n.dot(paper.faceCentroid(face) - eye) / n.dot(view);
    if (t > 0)
      return eye + (t - sheet.lift) * view;  // on the pickable copy, towards the eye
  }
  // The margin: a rectangle on the table under the sheet, around the paper's extent.
  Vec3 lo = paper.vertices[0].folded, hi = lo;
  for (const Vertex& v : paper.vertices)
  {
    lo = lo.cwiseMin(v.folded);
    hi = hi.cwiseMax(v.folded);
  }
  const double m = sheet.margin * paper.scale(), z = lo.z() + sheet.lift;
  if (std::abs(view.z()) < 1e-12)
    return std::nullopt;
  const double t = (z - eye.z()) / view.z();
  if (t <= 0)
    return std::nullopt;
  const Vec3 p = eye + t * view;
  if (p.x() < lo.x() - m || p.x() > hi.x() + m || p.y() < lo.y() - m || p.y() > hi.y() + m)
    return std::nullopt;
  return p;
}

Pointer RayPointer::at(const Paper& paper, const SightRay& ray, const PickableSheet& sheet)
{
  Pointer p;
  p.mouse_point = sheetPointOnRay(paper, ray, sheet);
  p.camera = ray.camera;
  return p;
}

Pointer RayPointer::press(const Paper& paper, const SightRay& ray, const PickableSheet& sheet)
{
  Pointer p = at(paper, ray, sheet);
  grab_ = p.mouse_point;
  moved_ = Vec3::Zero();
  return p;  // the marker where it lies: moves are measured from here
}

Pointer RayPointer::move(const SightRay& ray)
{
  Pointer p;
  p.camera = ray.camera;
  if (grab_)
  {
    // The plane through the grab point facing the camera, where the sight line meets it.
    const Vec3 normal = ray.camera.forward(), view = ray.direction;
    const double along = view.dot(normal);
    if (std::abs(along) > 1e-12 && view.allFinite())
    {
      const double t = (*grab_ - ray.camera.eye).dot(normal) / along;
      if (t > 0)
        moved_ = ray.camera.eye + t * view - *grab_;
    }
  }
  p.marker_position = moved_;
  return p;
}

Pointer RayPointer::release(const Paper& paper, const SightRay& ray, const PickableSheet& sheet)
{
  Pointer p = move(ray);
  p.mouse_point = sheetPointOnRay(paper, ray, sheet);
  letGo();
  return p;
}

}  // namespace virtual_origami::core
