// What the paper lies in: its weight, and the table under it. Seed 002's scenes have neither
// (the sheet floats, and with two corners held it may swing freely about their line); paper a
// hand lifts by one corner stays on the table where nothing lifts it, and that takes both.
#pragma once

#include <vector>

#include "virtual_origami/curved/curved_forces.h"

namespace virtual_origami::core
{
struct Surroundings
{
  /// Weight per unit mass, along −z of the paper's frame (the crease pattern's normal); 0:
  /// weightless. With a physical paper (paper_material.h: density in kg/m², the sheet in
  /// metres) it is in m/s²: 9.81. With the default material (bend 1e-6, density 1), 3e-5 gives
  /// a sheet of side 1 the sag of 15-cm origami paper: its gravity–bending length
  /// (bend / (density·g))^⅓ is a third of the side.
  double gravity = 0.0;
  /// A table at z = table_height that nodes cannot sink below (penalty).
  bool table = false;
  double table_height = 0.0;
  /// The table's penalty weight per node; 0: layer contact's stiffness.
  double table_stiffness = 0.0;
};

/// Energy of the weight, Σ m·g·z, and of the table, Σ ½·w·(h − z)² over the nodes below it
/// (w = table_stiffness, which must be set), with its derivatives into `out` (the weight's
/// Hessian is zero, the table's w on z·z).
double evaluateSurroundings(const Surroundings& surroundings, const std::vector<double>& mass, const Positions& x,
                            const Assembly& out = {});

}  // namespace virtual_origami::core
