// Euler's elastica (SPEC §4.2, §6): the closed forms a bent strip of curved paper converges
// to. A planar inextensible rod of length L along arc length s, tangent angle θ(s) measured
// from +x towards +z, bending stiffness EI; its moment EI·θ′ balances the forces beyond s:
// - end loads only (both ends held): θ″ = a·cos θ + b·sin θ, (a, b) the end force over EI
//   turned by a quarter (constant along the rod);
// - its own weight w per length along −z, free end: θ″ = (w/EI)·(L − s)·cos θ, θ′(L) = 0.
// Each is integrated by RK4 in equal steps and its unknown start values found by shooting
// (Newton on the end conditions), with continuation from an easy case.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// The rod's mid-line, sampled at equal steps of arc length from the clamp at the origin.
struct ElasticaCurve
{
  double length = 0.0;
  std::vector<double> x, z, theta, curvature;  // at s = length·k/steps, k = 0 … steps

  int steps() const { return static_cast<int>(x.size()) - 1; }
  /// The point at arc length s ∈ [0, length] (cubic Hermite between samples, the tangents
  /// (cos θ, sin θ): fourth order, as the integration).
  Eigen::Vector2d at(double s) const;
  double angleAt(double s) const;  // θ(s), linear between samples
};

struct ElasticaOptions
{
  int steps = 4000;          // RK4 steps over the rod
  double tolerance = 1e-12;  // end conditions met to this, relative to the length
  int max_iterations = 50;   // Newton iterations per continuation stage
  int stages = 16;           // continuation stages from the easy case
};

/// A rod clamped at the origin along +x, its end held at `end` (x, z) with tangent angle
/// `end_angle`. Starts from the circular arc that reaches `end_angle` and moves the end to
/// `end` in stages. Fails when the end is out of reach (|end| ≥ length) or shooting does not
/// converge.
struct HeldElastica
{
  ElasticaCurve curve;
  double a = 0.0, b = 0.0;   // θ″ = a·cos θ + b·sin θ
  double residual = 0.0;     // of the end conditions at the solution, relative to the length
};
Expected<HeldElastica> heldElastica(double length, const Eigen::Vector2d& end, double end_angle,
                                    const ElasticaOptions& options = {});

/// A cantilever clamped at the origin along +x under its own weight, `load` = w/EI per unit
/// length (1/m³): θ″ = load·(L − s)·cos θ, θ′(L) = 0. Starts from the small-deflection
/// solution and raises the load in stages.
struct CantileverElastica
{
  ElasticaCurve curve;
  double residual = 0.0;  // |θ′(L)|·L at the solution
};
Expected<CantileverElastica> cantileverElastica(double length, double load, const ElasticaOptions& options = {});

/// Integrates θ″ = a cos θ + b sin θ from the clamp with θ′(0) = start_curvature.
ElasticaCurve integrateHeldElastica(double length, double start_curvature, double a, double b, int steps);

}  // namespace virtual_origami::core
