// A curved sheet that follows its pins as they move (a gripper's frame): the mesh and the last
// balance are kept from one solve to the next, so each move starts from where the paper lies
// instead of from its rigid faces. A long move is split into short ones: Newton, started a
// whole half circle away from the answer, does not find it. Moves made at the mouse can instead
// be shown as anytime frames (anytime_frames.h): one frame per move within a wall-time budget,
// and the shape polished to balance when the pins stand still (settle).
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "virtual_origami/core/pull.h"
#include "virtual_origami/curved/anytime_frames.h"
#include "virtual_origami/curved/curved_solver.h"
#include "virtual_origami/curved/layered_start.h"

namespace virtual_origami::core
{
using CurvedMesher = std::function<Expected<CurvedMesh>(const Paper&)>;

struct CurvedFollowOptions
{
  CurvedMaterial material;
  ContactOptions contact;
  CurvedSolveOptions solve;
  Surroundings surroundings;  // weightless and in the air unless set
  /// No pin moves farther than this many mesh spacings in one solve; a longer move is made in
  /// equal steps, each solved from the last.
  double max_pin_step = 0.25;
  /// A new state's sheet starts with its stacked layers lifted apart (layeredStart), `layer_gap`
  /// × the sheet's scale between two layers, every term at rest there, and contact keeps them
  /// apart with a barrier no step passes (ContactOptions::barrier, within half a gap): a folded
  /// model bent or pulled open (seed 002 Fig. 1.1). The mesher must give the creases strips as
  /// wide as layersFor(paper, layer_gap) has them (BubbleMeshOptions::crease_strip). The pins
  /// should move little per solve (max_pin_step): the folded crane's pulls balance in steps of
  /// 1/100 spacing (curved_mesh_solver's `layers`).
  bool layered = false;
  /// 10⁻⁵: the folded crane's pulls balance in 30–60 Newton iterations; at the layered start's
  /// own 10⁻⁶, 160–185 (docs/CURVED.md).
  double layer_gap = 1e-5;
  int max_steps = 400;  // a move that would need more steps is refused
  /// The anytime frames of frame() (their release tolerance is the solve's, as solveOptionsFor
  /// gives it). Corrections bound by the frame's wall-time budget alone: a pointer moves far more
  /// per frame than the bench's drag (each correction moves a node less than half a spacing),
  /// and on a small sheet a correction takes well under a millisecond.
  AnytimeFrameOptions frames = [] {
    AnytimeFrameOptions options;
    options.max_corrections = 100;
    return options;
  }();
};

/// The layered start a follower with `layered` gives `paper`: layers `layer_gap` × its scale apart.
LayeredStartOptions layersFor(const Paper& paper, double layer_gap);

class CurvedSheetFollower
{
public:
  explicit CurvedSheetFollower(CurvedMesher mesher, CurvedFollowOptions options = {});

  /// A state of the paper with its pins (every held vertex and where it is held). The mesh is
  /// kept while the crease pattern stays the same, else made anew; the solve starts from the
  /// last balance while the folded positions stay the same too (the pins alone moved), else
  /// from the state's rigid faces. Fails, changing nothing, on a pin of a vertex that does not
  /// exist or at a point that is not finite, a paper the mesher cannot mesh, a material or
  /// surroundings setMaterial would refuse (a paper thicker than the new mesh's spacing too), a
  /// move of more than max_steps steps, or a solve that diverges (the last balance stays).
  /// `anew`: from the state's rigid faces even where the last balance could go on (paper let
  /// go springs back to its rest, which no resolution of a soft bend by a force tolerance finds).
  /// A sheet with no pins, no weight and no table is not solved: nothing pulls it, so it lies as
  /// the state's rigid faces (the report converged, no iterations); the solver is made when pins
  /// come.
  Expected<CurvedReport> solveState(const Paper& paper, const std::vector<PullTarget>& pins, bool anew = false);

  /// Another paper or surroundings (a physical paper's moduli, gravity): the sheet keeps its
  /// mesh and shape and solves on with them from the next solve. Refused, changing nothing, for
  /// moduli checkCurvedMaterial refuses, surroundings that are not finite, or a paper thicker
  /// than the mesh's spacing.
  Status setMaterial(const CurvedMaterial& material, const Surroundings& surroundings);

  /// The pins of the current state moved: the same as solveState with the current state.
  /// Fails, changing nothing, before any state.
  Expected<CurvedReport> follow(const std::vector<PullTarget>& pins);

  /// The pins of the current state moved, shown as one anytime frame: the shape carried on and
  /// corrected within the frames' budget, not balanced (balanced() false unless the frame's force
  /// is within the tolerance). The frames start from the sheet as it lies, on its first call and
  /// whenever the pinned vertices change (a vertex grabbed or let go) or another call changed the
  /// sheet. Fails, changing nothing, before any state or for pins solveState would refuse.
  Expected<FrameReport> frame(const std::vector<PullTarget>& pins);

  /// The pins stand still: the anytime frames' shape is brought to the solve's tolerance at the
  /// frames' last pins (AnytimeFrames::release). A sheet that is not on frames is left as it is
  /// (its report says whether it is balanced). Fails before any state.
  Expected<CurvedReport> settle();

  /// Whether the sheet shown is an anytime frame not yet settled.
  bool onFrames() const
  {
    return frames_live_ && !balanced_;
  }
  /// Wall time since the last frame was made (how long the pins have stood still).
  double secondsSinceFrame() const;

  bool hasSheet() const
  {
    return mesh_ != nullptr;
  }
  const Paper& paper() const
  {
    return *paper_;
  }
  const CurvedMesh& mesh() const
  {
    return *mesh_;
  }
  const Positions& positions() const
  {
    return x_;
  }
  /// The pins the current positions balance.
  const std::vector<PullTarget>& pins() const
  {
    return pins_;
  }
  /// How many solves the last move took (1 unless it was split).
  int lastSteps() const
  {
    return last_steps_;
  }
  /// Whether the last solve reached balance (a solve stopped by its budget can be resumed by
  /// following the same pins again).
  bool balanced() const
  {
    return balanced_;
  }

private:
  Status checkPins(const Paper& paper, const std::vector<PullTarget>& pins) const;
  Expected<CurvedReport> moveTo(const std::vector<PullTarget>& pins);
  /// The solve options of the current mesh.
  CurvedSolveOptions solveOptions() const;
  /// A solver for `mesh` of `paper`; with `layered`, its contact the barrier within half a gap
  /// and every term at rest in `rest`.
  std::unique_ptr<CurvedSolver> makeSolver(const CurvedMesh& mesh, const Paper& paper, const Positions& rest) const;

  CurvedMesher mesher_;
  CurvedFollowOptions options_;
  // The solver keeps references to the paper and the mesh: both live on the heap, at fixed
  // addresses, for as long as the solver does.
  Positions layered_rest_;  // with `layered`: the sheet's start, where its bends rest
  std::unique_ptr<Paper> paper_;
  std::unique_ptr<CurvedMesh> mesh_;
  std::unique_ptr<CurvedSolver> solver_;
  // The anytime frames on the same paper and mesh (made at the first frame); live while x_ is
  // their shape and their pins are the vertices of pins_.
  std::unique_ptr<AnytimeFrames> frames_;
  bool frames_live_ = false;
  double frame_made_ = 0.0;  // steady-clock seconds at the end of the last frame
  Positions x_;
  std::vector<PullTarget> pins_;
  int last_steps_ = 0;
  bool balanced_ = false;
};

/// Whether two papers have the same crease pattern (vertices, edges with their assignments,
/// faces): one mesh serves both.
bool sameCreasePattern(const Paper& a, const Paper& b);

/// The solve options the follower gives a solver on `mesh`: `solve`, its tolerance cut for a
/// physical paper (material.thickness > 0) by as much as the paper's bending is softer against its
/// stretch than the default material's on its default mesh (bend / (stretch · spacing²) against
/// 1e-4), so that a thin paper's bending and weight are resolved as finely.
CurvedSolveOptions solveOptionsFor(const CurvedMaterial& material, CurvedSolveOptions solve, const CurvedMesh& mesh);

/// Refuses surroundings with a gravity, table height or table stiffness that is not finite, or a
/// negative table stiffness.
Status checkSurroundings(const Surroundings& surroundings);

}  // namespace virtual_origami::core
