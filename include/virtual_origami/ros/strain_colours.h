// Colours for strain, as Origami Simulator shows it: blue where a face keeps its shape, through
// cyan, green and yellow, to red at the full scale and beyond.
#pragma once

#include <std_msgs/ColorRGBA.h>

namespace virtual_origami
{
/// Hue from 240° (blue, strain 0) down to 0° (red, strain ≥ full_scale), linear in the strain,
/// full saturation; opaque. A strain that is not a number is drawn magenta (nothing else is).
std_msgs::ColorRGBA strainColour(double strain, double full_scale);

}  // namespace virtual_origami
