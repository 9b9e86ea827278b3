// Model no more than a scene needs (SPEC §4.3): rigid faces where the faces can stay flat,
// the curved mesh only on the faces that must bend (and the layers stacked on them), and a
// mesh no finer than the accuracy asked for. The choice says why, and every part of it can
// be overridden.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/curved/curved_mesh.h"
#include "virtual_origami/core/shape_solver.h"

namespace virtual_origami::core
{
enum class PaperModel
{
  Rigid,   // flat faces, the rigid-face solvers of §4.1
  Curved,  // the bubble mesh and the forces of §4.2 on `curved_faces`
};

struct ModelChoiceOptions
{
  /// "auto" decides; "rigid" or "curved" (every face) override it.
  std::string mode = "auto";
  /// Strain the rigid solve may leave and still count as reaching the pins.
  double rigid_tolerance = 1e-6;
  /// Mesh spacing to start from (0: an eighth of the sheet's scale); see refineSpacing.
  double spacing = 0.0;
};

struct ModelChoice
{
  PaperModel model = PaperModel::Rigid;
  std::vector<char> curved_faces;  // per face, when Curved: 1 bends, 0 stays flat and coarse
  double spacing = 0.0;            // when Curved
  double rigid_strain = 0.0;       // what the rigid attempt left (auto only)
  std::string reason;
};

/// A paper vertex held at a position.
using VertexPin = std::pair<int, Vec3>;

/// Tries the pins on rigid faces first (`rigid` solves from the paper with the pinned
/// vertices moved): when the faces keep their shapes the scene is rigid. Otherwise the faces
/// the rigid attempt had to strain bend, and so do the faces stacked on them (face orders,
/// creases folded to ±180°), which must bend along; the rest stay flat. Fails on a pin that
/// names no vertex or an unknown mode.
Expected<ModelChoice> chooseModel(const Paper& paper, const std::vector<VertexPin>& pins, ShapeSolver& rigid,
                                  const ModelChoiceOptions& options = {});

/// One level of refineSpacing: a spacing and how far its solution lies from the next
/// coarser one's (the largest distance of a node from the coarser surface's interpolation).
struct SpacingLevel
{
  double spacing = 0.0;
  double change = 0.0;  // infinity for the first level
  int nodes = 0;
};

struct SpacingChoice
{
  double spacing = 0.0;  // the coarsest spacing found accurate enough
  bool met = false;      // false: even the finest level moved more than the accuracy
  std::vector<SpacingLevel> levels;
};

/// Halves the spacing from `start` (meshing the paper with bubbleMesh, `curved_faces` as
/// given) and solves each mesh with `solve`, until a solution lies within `accuracy` (a
/// length) of the previous, coarser one, whose spacing is then the choice: its error against
/// the finer mesh is measured, not guessed. Stops at `finest` unmet. Fails when meshing or
/// `solve` fails.
Expected<SpacingChoice> refineSpacing(const Paper& paper, const std::vector<char>& curved_faces, double start,
                                      double finest, double accuracy,
                                      const std::function<Expected<Positions>(const CurvedMesh&)>& solve);

}  // namespace virtual_origami::core
