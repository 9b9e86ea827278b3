#include "virtual_origami/core/view_camera.h"

#include <cmath>

namespace virtual_origami::core
{
std::optional<Vec3> alongSightOnto(const ViewCamera& camera, const Vec3& point, const Vec3& origin, const Vec3& normal)
{
  const Vec3 ray = camera.rayTo(point);
  const double across = ray.dot(normal);
  if (!ray.allFinite() || std::abs(across) < 1e-6)
    return std::nullopt;
  const double t = (origin - camera.eye).dot(normal) / across;
  if (t <= 0)
    return std::nullopt;
  return Vec3(camera.eye + t * ray);
}

std::optional<ViewCamera> turnedView(const ViewCamera& camera, const Vec3& press, const Vec3& centre,
                                     const Vec3& axis_direction, double min_cos)
{
  const Vec3 d = axis_direction.normalized();
  if (std::abs(camera.rayTo(press).dot(d)) >= min_cos)
    return std::nullopt;
  // About C–P; where the press is the centre, about the line across the axis in the view.
  Vec3 about = centre - press;
  if (about.norm() < 1e-9)
    about = d.cross(camera.rayTo(press));
  if (about.norm() < 1e-12)
    return std::nullopt;
  about.normalize();
  const Vec3 seen = camera.axes.transpose() * (press - camera.eye);  // P in camera coordinates
  const Vec3 up = Vec3::UnitZ();
  for (int step = 1; step <= 15; ++step)
    for (double sign : { 1.0, -1.0 })
    {
      const double angle = sign * step * 5.0 * M_PI / 180.0;
      const Vec3 forward = Eigen::AngleAxisd(angle, about) * camera.forward();
      const Vec3 right = forward.cross(up);
      if (right.norm() < 1e-6)
        continue;  // straight up or down: no level view
      ViewCamera turned;
      turned.axes.col(0) = right.normalized();
      turned.axes.col(2) = forward.normalized();
      turned.axes.col(1) = turned.axes.col(2).cross(turned.axes.col(0));
      turned.eye = press - turned.axes * seen;
      if (std::abs(turned.rayTo(press).dot(d)) >= min_cos && turned.eye.z() > press.z())
        return turned;
    }
  return std::nullopt;
}

}  // namespace virtual_origami::core
