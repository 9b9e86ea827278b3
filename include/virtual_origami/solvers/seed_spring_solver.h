// The seed's spring model (seed 000 §3.2, eq. 2–4) kept exactly, as the baseline.
#pragma once

#include <string>
#include <vector>

#include "virtual_origami/core/face_springs.h"
#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
struct SeedSpringOptions
{
  double d = 0.2;   // the seed's "damping constant" in eq. 3 (0 ≤ d ≤ 1)
  double dt = 1.0;  // Δt of eq. 3–4
  /// Share of the velocity an iteration keeps. The printed eq. 3–4 with D = 0 (its
  /// simplification of eq. 1) has no dissipation at all: carried whole (1) the scheme is a
  /// symplectic Euler that keeps oscillating and never settles. 0, the default, reads d as
  /// the damping it is named: each step starts from rest, v = d·F·Δt, r ← r + v·Δt — explicit
  /// Euler of the overdamped motion ṙ = d·F, which settles and is the seed's anytime shape.
  double velocity_carry = 0.0;
  /// Divergence: total energy above this multiple of where it started, or rising this many
  /// iterations in a row (only without carried velocity, where a stable step always lowers it).
  double divergence_growth = 1e3;
  int rising_window = 25;
};

/// Largest spring-stiffness eigenvalue the scheme survives: d·λ·Δt² < 2(1 + carry). With the
/// seed's d = 0.2, Δt = 1 and no carried velocity that is λ < 10, and a face of n vertices
/// alone has λ = n (restStiffnessBound): faces of 10 vertices stop converging, 11 diverge.
double seedStabilityLimit(const SeedSpringOptions& options);

/// Largest eigenvalue of the spring stiffness on the free vertices at the paper's current
/// positions (power iteration): the number to compare with seedStabilityLimit.
double springStiffnessMax(const Paper& paper, const std::vector<char>& fixed, int iterations = 200);

class SeedSpringSolver : public ShapeSolver
{
public:
  explicit SeedSpringSolver(SeedSpringOptions options = {});
  std::string name() const override
  {
    return "seed_spring";
  }
  SolveReport solve(Paper& paper, const std::vector<char>& fixed) override;
  const SeedSpringOptions& options() const
  {
    return options_;
  }

private:
  SeedSpringOptions options_;
};

}  // namespace virtual_origami::core
