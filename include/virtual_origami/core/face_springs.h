// The seed's spring network (seed 000 §3.2, eq. 2): a unit spring between every pair of
// vertices of each face, none across faces, rest lengths from the crease pattern.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/positions.h"

namespace virtual_origami::core
{
struct Spring
{
  int i = -1, j = -1;
  double rest = 0.0;  // crease-pattern distance
};

/// Max and mean of the strain |l/l0 − 1| over the springs (every vertex pair of each face).
struct StrainStats
{
  double max = 0.0;
  double mean = 0.0;
  int pairs = 0;
};

/// One spring per vertex pair per face: a pair on a crease is in two faces and gets two
/// springs, as in the seed. Built from the current faces, so a crease re-wires it.
std::vector<Spring> faceSprings(const Paper& paper);

StrainStats springStrain(const std::vector<Spring>& springs, const Positions& x);

struct SpringState
{
  double energy = 0.0;
  double max_strain = 0.0;  // non-finite positions give infinity
};

/// E = ½ Σ (|r_ij| − L_ij)², whose negative gradient is the seed's force
/// F_i = Σ_j (1 − L_ij/|r_ij|)(x_j − x_i) (a stretched spring pulls i towards j).
/// Writes the forces into `forces` (3 × V) when given.
SpringState evaluateSprings(const std::vector<Spring>& springs, const Positions& x, Positions* forces = nullptr);

/// out = H v, H the Hessian of the spring energy at x (3 × V each).
void springHessianProduct(const std::vector<Spring>& springs, const Positions& x, const Positions& v, Positions& out);

/// Largest eigenvalue of the spring stiffness (the Hessian of springEnergy) at rest for one
/// face of `n` vertices: exactly n, whatever the face's shape. The dilation field
/// d_i = x_i − centroid is an eigenvector (u uᵀ(d_i − d_j) = x_i − x_j for every spring),
/// and n bounds the spectrum because the stiffness is at most the Laplacian of K_n.
inline double restStiffnessBound(int n)
{
  return static_cast<double>(n);
}

}  // namespace virtual_origami::core
