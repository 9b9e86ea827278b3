#include "virtual_origami/core/face_springs.h"

#include <cmath>

namespace virtual_origami::core
{
std::vector<Spring> faceSprings(const Paper& paper)
{
  std::vector<Spring> springs;
  for (const Face& face : paper.faces)
  {
    const std::vector<int>& vs = face.vertices;
    for (size_t a = 0; a < vs.size(); ++a)
      for (size_t b = a + 1; b < vs.size(); ++b)
      {
        const double rest = (paper.vertices[vs[a]].crease_pattern - paper.vertices[vs[b]].crease_pattern).norm();
        springs.push_back({ vs[a], vs[b], rest });
      }
  }
  return springs;
}

StrainStats springStrain(const std::vector<Spring>& springs, const Positions& x)
{
  StrainStats stats;
  double sum = 0.0;
  for (const Spring& s : springs)
  {
    const double strain = std::abs((x.col(s.i) - x.col(s.j)).norm() / s.rest - 1.0);
    // NaN must not hide behind max(): a non-finite strain is the worst there is.
    stats.max = std::isfinite(strain) ? std::max(stats.max, strain) : INFINITY;
    sum += strain;
  }
  stats.pairs = static_cast<int>(springs.size());
  stats.mean = springs.empty() ? 0.0 : sum / static_cast<double>(springs.size());
  return stats;
}

SpringState evaluateSprings(const std::vector<Spring>& springs, const Positions& x, Positions* forces)
{
  if (forces)
    forces->setZero(3, x.cols());
  SpringState state;
  for (const Spring& s : springs)
  {
    const Eigen::Vector3d r = x.col(s.j) - x.col(s.i);
    const double length = r.norm();
    state.energy += 0.5 * (length - s.rest) * (length - s.rest);
    const double strain = std::abs(length / s.rest - 1.0);
    state.max_strain = std::isfinite(strain) ? std::max(state.max_strain, strain) : INFINITY;
    if (forces && length > 0)
    {
      const Eigen::Vector3d f = (1.0 - s.rest / length) * r;
      forces->col(s.i) += f;
      forces->col(s.j) -= f;
    }
  }
  return state;
}

void springHessianProduct(const std::vector<Spring>& springs, const Positions& x, const Positions& v, Positions& out)
{
  out.setZero(3, x.cols());
  for (const Spring& s : springs)
  {
    const Eigen::Vector3d r = x.col(s.j) - x.col(s.i);
    const double length = r.norm();
    if (!(length > 0))
      continue;
    const Eigen::Vector3d u = r / length;
    const Eigen::Vector3d dv = v.col(s.j) - v.col(s.i);
    // Axial stiffness along the spring, geometric stiffness (tension) across it.
    const double along = u.dot(dv);
    const Eigen::Vector3d h = along * u + (1.0 - s.rest / length) * (dv - along * u);
    out.col(s.j) += h;
    out.col(s.i) -= h;
  }
}

}  // namespace virtual_origami::core
