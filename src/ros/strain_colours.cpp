#include "virtual_origami/ros/strain_colours.h"

#include <algorithm>
#include <cmath>

#include "virtual_origami/ros/markers.h"

namespace virtual_origami
{
std_msgs::ColorRGBA strainColour(double strain, double full_scale)
{
  if (!std::isfinite(strain) && !(strain > 0))
    return rgba(1.0f, 0.0f, 1.0f);
  const double t = full_scale > 0 ? std::clamp(strain / full_scale, 0.0, 1.0) : 1.0;
  // HSV with S = V = 1: hue h in [0, 4) sixths of the circle, blue at 4, red at 0.
  const double h = 4.0 * (1.0 - t);
  const double x = 1.0 - std::abs(std::fmod(h, 2.0) - 1.0);
  const float c = 1.0f, xf = static_cast<float>(x);
  if (h < 1.0)
    return rgba(c, xf, 0.0f);  // red to yellow
  if (h < 2.0)
    return rgba(xf, c, 0.0f);  // yellow to green
  if (h < 3.0)
    return rgba(0.0f, c, xf);  // green to cyan
  return rgba(0.0f, xf, c);    // cyan to blue
}

}  // namespace virtual_origami
