// The model's invariants (SPEC §2), checked after every operation in tests.
#pragma once

#include <string>
#include <vector>

#include "virtual_origami/core/paper.h"

namespace virtual_origami::core
{
struct ValidityReport
{
  std::vector<std::string> problems;
  bool ok() const { return problems.empty(); }
  std::string summary() const;  // the problems, one per line
};

struct ValidityTolerance
{
  double length = 1e-9;  // |3D − crease-pattern| distance within a face, relative to the sheet scale
  double area = 1e-9;    // relative
  double convexity = 1e-12;  // cross-product slack, relative to the squared scale
};

/// Every crease has exactly two faces and every boundary edge one; faces are convex and
/// counter-clockwise in the crease pattern; face areas sum to the sheet's; V − E + F = pieces −
/// holes (a sheet in several pieces, or with holes or opened slits, is paper too);
/// folded distances between vertices of a face equal their crease-pattern distances.
ValidityReport checkValidity(const Paper& paper, const ValidityTolerance& tolerance = {});

}  // namespace virtual_origami::core
