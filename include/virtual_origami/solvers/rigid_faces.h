// One rigid shape constraint per face (shape matching): the face's crease-pattern polygon,
// turned and moved to fit its folded vertices best. Shared by the exact solvers.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/face_springs.h"
#include "virtual_origami/core/positions.h"
#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
struct RigidFace
{
  std::vector<int> vertices;
  Eigen::Matrix2Xd rest;  // crease-pattern positions minus their mean, one column per vertex
};

/// One per face; the convex pieces of a concave face a file gave (joined by split edges) make one,
/// unless they are compliant (joined by facets, which bend: core/compliant_faces.h).
/// `exact_rest`: each rest shape from its crease-pattern coordinates' differences, exact; else
/// from their mean over the face, which rounds to the coordinates' ulp (a sheet 92 units wide:
/// 1.4e-14, which a large Miura-ori's near-singular balance amplified to a strain of 1.7e-9
/// that no solver could close). The crease drivers keep the mean (their step counts are tuned
/// and tested on it; a turn guide only starts the rigid solver).
std::vector<RigidFace> rigidFaces(const Paper& paper, bool exact_rest = true);

/// The face's folded vertices, one column each, less their mean.
Eigen::Matrix3Xd centredFace(const RigidFace& face, const Positions& x);

/// The rotation that best turns the face's rest shape onto the centred folded vertices. The
/// rest shape is planar, so only the first two columns are fitted (the polar factor of a
/// 3 × 2 matrix) and the third is their cross product: always proper, and a face folded
/// over is just turned, never mirrored.
Eigen::Matrix3d fitRotation(const RigidFace& face, const Positions& x);

/// E = ½ Σ_f Σ_{v∈f} |(x_v − x̄_f) − R_f p̃_v|², each R_f fitted: zero exactly when every
/// face has its crease-pattern shape.
struct RigidFit
{
  double energy = 0.0;
  double max_residual = 0.0;  // largest |(x_v − x̄_f) − R_f p̃_v|
  std::vector<Eigen::Matrix3d> rotations;
};
RigidFit fitRigidFaces(const std::vector<RigidFace>& faces, const Positions& x);

/// How every exact solver ends: a diverged solve leaves the paper at `start` and says it was
/// rolled back; otherwise the paper takes `x`, the strain is measured there, and an unconverged
/// report says why it stopped (`stop_reason`, or "stopped") and how far from the tolerance.
void finishRigidSolve(const std::string& solver, Paper& paper, const std::vector<Spring>& springs,
                      const Positions& start, const Positions& x, bool diverged, const RigidFit& fit,
                      const std::string& stop_reason, double tolerance, SolveReport& report);

}  // namespace virtual_origami::core
