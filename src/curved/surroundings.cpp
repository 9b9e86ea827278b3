#include "virtual_origami/curved/surroundings.h"

namespace virtual_origami::core
{
double evaluateSurroundings(const Surroundings& surroundings, const std::vector<double>& mass, const Positions& x,
                            const Assembly& out)
{
  const double table_stiffness = surroundings.table_stiffness;
  double energy = 0.0;
  for (Eigen::Index v = 0; v < x.cols(); ++v)
  {
    const double z = x(2, v);
    double force_z = 0.0;  // dE/dz
    if (surroundings.gravity != 0.0)
    {
      energy += mass[v] * surroundings.gravity * z;
      force_z += mass[v] * surroundings.gravity;
    }
    const double depth = surroundings.table_height - z;
    const bool pressing = surroundings.table && depth > 0;
    if (pressing)
    {
      energy += 0.5 * table_stiffness * depth * depth;
      force_z -= table_stiffness * depth;
    }
    const int f = out.free_index ? (*out.free_index)[v] : -1;
    if (f < 0)
      continue;
    if (out.gradient)
      (*out.gradient)[3 * f + 2] += force_z;
    if (pressing && out.wantsHessian())
    {
      Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
      block(2, 2) = table_stiffness;
      out.addBlock(f, f, block);
    }
  }
  return energy;
}

}  // namespace virtual_origami::core
