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

namespace
{
/// The camera looking along `forward`, levelled (no roll), P kept at its camera coordinates
/// `seen`; none when `forward` is straight up or down.
std::optional<ViewCamera> lookingAlong(const Vec3& forward, const Vec3& press, const Vec3& seen)
{
  const Vec3 right = forward.cross(Vec3::UnitZ());
  if (right.norm() < 1e-6)
    return std::nullopt;  // straight up or down: no level view
  ViewCamera turned;
  turned.axes.col(0) = right.normalized();
  turned.axes.col(2) = forward.normalized();
  turned.axes.col(1) = turned.axes.col(2).cross(turned.axes.col(0));
  turned.eye = press - turned.axes * seen;
  return turned;
}
}  // namespace

std::optional<ViewCamera> turnedView(const ViewCamera& camera, const Vec3& press, const Vec3& centre,
                                     const Vec3& axis_direction, double min_cos)
{
  const Vec3 d = axis_direction.normalized();
  if (std::abs(camera.rayTo(press).dot(d)) >= min_cos)
    return std::nullopt;
  const Vec3 seen = camera.axes.transpose() * (press - camera.eye);  // P in camera coordinates
  const auto good = [&](const std::optional<ViewCamera>& turned) {
    return turned && std::abs(turned->rayTo(press).dot(d)) >= min_cos && turned->eye.z() > press.z();
  };
  // The seed's turn, about C–P; where the press is the centre, about the line across the axis.
  Vec3 about = centre - press;
  if (about.norm() < 1e-9)
    about = d.cross(camera.rayTo(press));
  if (about.norm() >= 1e-12)
  {
    about.normalize();
    for (int step = 1; step <= 15; ++step)
      for (double sign : { 1.0, -1.0 })
      {
        const double angle = sign * step * 5.0 * M_PI / 180.0;
        const std::optional<ViewCamera> turned =
            lookingAlong(Eigen::AngleAxisd(angle, about) * camera.forward(), press, seen);
        if (good(turned))
          return turned;
      }
  }
  // From a low oblique view C–P may lie almost along the sight line, and no turn about it
  // reaches the axis: orbit about the vertical through P and tilt, the smallest turn first.
  const Vec3 right = camera.forward().cross(Vec3::UnitZ());
  for (int step = 1; step <= 36; ++step)
    for (int tilt = 0; tilt <= std::min(step, 12); ++tilt)
      for (double sign : { 1.0, -1.0 })
        for (double lift : { 1.0, -1.0 })
        {
          if (tilt == 0 && lift < 0)
            continue;
          const double yaw = sign * step * 5.0 * M_PI / 180.0, pitch = lift * tilt * 5.0 * M_PI / 180.0;
          Vec3 forward = camera.forward();
          if (right.norm() > 1e-6)
            forward = Eigen::AngleAxisd(pitch, right.normalized()) * forward;
          forward = Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * forward;
          const std::optional<ViewCamera> turned = lookingAlong(forward, press, seen);
          if (good(turned))
            return turned;
        }
  return std::nullopt;
}

}  // namespace virtual_origami::core
