#include "virtual_origami/curved/curved_follow.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "virtual_origami/curved/paper_material.h"

namespace virtual_origami::core
{
bool sameCreasePattern(const Paper& a, const Paper& b)
{
  if (a.vertices.size() != b.vertices.size() || a.edges.size() != b.edges.size() || a.faces.size() != b.faces.size())
    return false;
  for (size_t v = 0; v < a.vertices.size(); ++v)
    if (a.vertices[v].crease_pattern != b.vertices[v].crease_pattern)
      return false;
  for (size_t e = 0; e < a.edges.size(); ++e)
    if (a.edges[e].vertices != b.edges[e].vertices || a.edges[e].assignment != b.edges[e].assignment)
      return false;
  for (size_t f = 0; f < a.faces.size(); ++f)
    if (a.faces[f].vertices != b.faces[f].vertices)
      return false;
  return true;
}

namespace
{
double steadySeconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool sameFoldedState(const Paper& a, const Paper& b)
{
  const double still = 1e-12 * std::max(a.scale(), b.scale());
  for (size_t v = 0; v < a.vertices.size(); ++v)
    if ((a.vertices[v].folded - b.vertices[v].folded).norm() > still)
      return false;
  return true;
}
}  // namespace

CurvedSheetFollower::CurvedSheetFollower(CurvedMesher mesher, CurvedFollowOptions options)
  : mesher_(std::move(mesher)), options_(std::move(options))
{}

Status CurvedSheetFollower::checkPins(const Paper& paper, const std::vector<PullTarget>& pins) const
{
  std::vector<char> seen(paper.vertices.size(), 0);
  for (const PullTarget& pin : pins)
  {
    if (pin.vertex < 0 || pin.vertex >= static_cast<int>(paper.vertices.size()))
      return failure("pinned vertex " + std::to_string(pin.vertex) + " does not exist (the paper has " +
                     std::to_string(paper.vertices.size()) + ")");
    if (!pin.position.allFinite())
      return failure("the pin of vertex " + std::to_string(pin.vertex) + " is not at a finite point");
    if (seen[pin.vertex])
      return failure("vertex " + std::to_string(pin.vertex) + " is pinned twice");
    seen[pin.vertex] = 1;
  }
  return success();
}

CurvedSolveOptions solveOptionsFor(const CurvedMaterial& material, CurvedSolveOptions solve, const CurvedMesh& mesh)
{
  // The tolerance is a share of an edge's force per unit strain times the spacing; it was tuned
  // where a hinge bends with 1e-4 of that per radian (bend 1e-6 × stretch on a unit sheet
  // meshed at 0.1). A physical paper bends far more softly against its stretch: the share is
  // cut by as much, so that bending (and the weight, which bending carries) is resolved as finely.
  constexpr double kTunedBendRatio = 1e-4;
  if (material.thickness > 0 && mesh.spacing > 0)
    solve.tolerance *=
        std::min(1.0, material.bend / (material.stretch * mesh.spacing * mesh.spacing) / kTunedBendRatio);
  return solve;
}

Status checkSurroundings(const Surroundings& surroundings)
{
  if (!std::isfinite(surroundings.gravity) || !std::isfinite(surroundings.table_height) ||
      !std::isfinite(surroundings.table_stiffness) || surroundings.table_stiffness < 0)
    return failure("gravity, the table's height and its stiffness must be finite (and the stiffness not negative)");
  return success();
}

Status CurvedSheetFollower::setMaterial(const CurvedMaterial& material, const Surroundings& surroundings)
{
  if (const Status checked = checkCurvedMaterial(material); !checked)
    return checked;
  if (const Status checked = checkSurroundings(surroundings); !checked)
    return checked;
  if (mesh_)
    if (const Status checked = checkThicknessAgainstSpacing(material.thickness, mesh_->spacing); !checked)
      return checked;
  options_.material = material;
  options_.surroundings = surroundings;
  // The same mesh, a solver for the new paper; the sheet solves on from where it lies (frames
  // too: made anew at the next one).
  frames_.reset();
  frames_live_ = false;
  if (mesh_)
    solver_ = makeSolver(*mesh_, *paper_, layered_rest_);
  return success();
}

Expected<CurvedReport> CurvedSheetFollower::solveState(const Paper& paper, const std::vector<PullTarget>& pins,
                                                       bool anew)
{
  using Failure = Expected<CurvedReport>;
  if (const Status checked = checkPins(paper, pins); !checked)
    return Failure::failure(checked.message());
  if (const Status checked = checkCurvedMaterial(options_.material); !checked)
    return Failure::failure(checked.message());
  if (const Status checked = checkSurroundings(options_.surroundings); !checked)
    return Failure::failure(checked.message());
  // Nothing pulls an unpinned, weightless sheet: it lies as the model's faces have it, and no
  // solver is made until a pin comes (making one, with the layers' contact, is most of a solve:
  // 0.75 s of CPU for a folded 2,500-vertex Miura-ori, on every state the model publishes).
  const bool at_rest = pins.empty() && options_.surroundings.gravity == 0 && !options_.surroundings.table;
  const bool same_pattern = mesh_ && sameCreasePattern(*paper_, paper);
  if (!anew && !at_rest && same_pattern && sameFoldedState(*paper_, paper))
    return moveTo(pins);  // the pins alone moved: from the last balance

  // A new shape: the state's rigid faces are the start, on the kept mesh or a new one. The
  // old sheet stays until the new one is made.
  auto next_paper = std::make_unique<Paper>(paper);
  std::unique_ptr<CurvedMesh> next_mesh;
  if (same_pattern)
    next_mesh = std::make_unique<CurvedMesh>(*mesh_);
  else
  {
    Expected<CurvedMesh> meshed = mesher_(paper);
    if (!meshed)
      return Failure::failure("cannot mesh the paper: " + meshed.message());
    if (const Status checked = checkThicknessAgainstSpacing(options_.material.thickness, meshed->spacing); !checked)
      return Failure::failure(checked.message());
    next_mesh = std::make_unique<CurvedMesh>(std::move(*meshed));
  }
  Positions next_x = options_.layered ?
                         layeredStart(*next_mesh, *next_paper, layersFor(*next_paper, options_.layer_gap)).positions :
                         placeNodes(*next_mesh, *next_paper);
  // A layered start rests as drawn, whenever its solver is made.
  Positions next_rest = options_.layered ? next_x : Positions();
  std::unique_ptr<CurvedSolver> next_solver;
  if (!at_rest)
    next_solver = makeSolver(*next_mesh, *next_paper, next_rest);

  // The frames hold the old paper and mesh: they go first.
  frames_.reset();
  frames_live_ = false;
  std::swap(paper_, next_paper);
  std::swap(mesh_, next_mesh);
  std::swap(solver_, next_solver);
  std::swap(x_, next_x);
  std::swap(layered_rest_, next_rest);
  std::vector<PullTarget> last_pins = std::move(pins_);
  pins_.clear();
  if (at_rest)
  {
    last_steps_ = 0;
    balanced_ = true;
    CurvedReport report;
    report.converged = true;
    report.message = "nothing pulls the sheet: it lies as the model's faces";
    return report;
  }
  Expected<CurvedReport> moved = moveTo(pins);
  if (!moved)
  {
    // Back to the last sheet, as it was.
    std::swap(paper_, next_paper);
    std::swap(mesh_, next_mesh);
    std::swap(solver_, next_solver);
    std::swap(x_, next_x);
    std::swap(layered_rest_, next_rest);
    pins_ = std::move(last_pins);
  }
  return moved;
}

Expected<CurvedReport> CurvedSheetFollower::follow(const std::vector<PullTarget>& pins)
{
  if (!hasSheet())
    return Expected<CurvedReport>::failure("no state to follow pins on yet");
  if (const Status checked = checkPins(*paper_, pins); !checked)
    return Expected<CurvedReport>::failure(checked.message());
  return moveTo(pins);
}

Expected<CurvedReport> CurvedSheetFollower::moveTo(const std::vector<PullTarget>& pins)
{
  using Failure = Expected<CurvedReport>;
  // Every pin starts from where its node lies now and moves on a straight line. A layered start
  // drew its vertices a few gaps off the model's (lifted, hinges set out, raw edges drawn back):
  // a pin moves its node by as much as it moves the vertex from where the model has it.
  std::vector<Vec3> from, to;
  double farthest = 0.0;
  for (const PullTarget& pin : pins)
  {
    const int node = mesh_->vertex_nodes[pin.vertex];
    from.push_back(x_.col(node));
    to.push_back(options_.layered ? Vec3(pin.position + layered_rest_.col(node) - paper_->vertices[pin.vertex].folded) :
                                    pin.position);
    farthest = std::max(farthest, (to.back() - from.back()).norm());
  }
  const double step = options_.max_pin_step * mesh_->spacing;
  const int steps = step > 0 ? std::max(1, static_cast<int>(std::ceil(farthest / step))) : 1;
  if (steps > options_.max_steps)
    return Failure::failure("a pin would move " + std::to_string(farthest) + " in one go, more than " +
                            std::to_string(options_.max_steps) + " steps of " + std::to_string(step));

  if (!solver_)  // a sheet at rest until now (solveState)
    solver_ = makeSolver(*mesh_, *paper_, layered_rest_);
  const Positions start = x_;
  CurvedReport total;
  std::vector<CurvedPin> at(pins.size());
  for (int k = 1; k <= steps; ++k)
  {
    const double t = static_cast<double>(k) / steps;
    for (size_t i = 0; i < pins.size(); ++i)
      at[i] = { mesh_->vertex_nodes[pins[i].vertex], k == steps ? to[i] : Vec3(from[i] + t * (to[i] - from[i])) };
    CurvedReport report = solver_->solve(x_, at);
    report.iterations += total.iterations;
    report.factorizations += total.factorizations;
    report.seconds += total.seconds;
    total = report;
    if (report.diverged || report.refused)
    {
      x_ = start;
      return Failure::failure((report.refused ? "refused: " : "the curved sheet diverged: ") + report.message);
    }
  }
  pins_ = pins;
  last_steps_ = steps;
  balanced_ = total.converged;
  frames_live_ = false;
  return total;
}

LayeredStartOptions layersFor(const Paper& paper, double layer_gap)
{
  LayeredStartOptions layers;
  layers.gap = layer_gap * paper.scale();
  return layers;
}

std::unique_ptr<CurvedSolver> CurvedSheetFollower::makeSolver(const CurvedMesh& mesh, const Paper& paper,
                                                              const Positions& rest) const
{
  ContactOptions contact = options_.contact;
  if (options_.layered)
  {
    contact.barrier = true;
    contact.barrier_activation = 0.5 * layersFor(paper, options_.layer_gap).gapFor(paper);
  }
  auto solver = std::make_unique<CurvedSolver>(mesh, paper, options_.material, contact,
                                               solveOptionsFor(options_.material, options_.solve, mesh),
                                               options_.surroundings);
  if (options_.layered)
    solver->restTermsAt(rest);
  return solver;
}

CurvedSolveOptions CurvedSheetFollower::solveOptions() const
{
  return solveOptionsFor(options_.material, options_.solve, *mesh_);
}

Expected<FrameReport> CurvedSheetFollower::frame(const std::vector<PullTarget>& pins)
{
  using Failure = Expected<FrameReport>;
  if (!hasSheet())
    return Failure::failure("no state to follow pins on yet");
  if (options_.layered)
    return Failure::failure("anytime frames keep layers apart with the penalty contact only: a layered sheet follows "
                            "its pins by balanced solves");
  if (const Status checked = checkPins(*paper_, pins); !checked)
    return Failure::failure(checked.message());
  std::vector<CurvedPin> at;
  for (const PullTarget& pin : pins)
    at.push_back({ mesh_->vertex_nodes[pin.vertex], pin.position });
  bool same_vertices = frames_live_ && pins.size() == pins_.size();
  for (size_t k = 0; same_vertices && k < pins.size(); ++k)
    same_vertices = pins[k].vertex == pins_[k].vertex;
  if (!same_vertices)
  {
    // The frames start where the sheet lies, every pinned node held where it is; the frame
    // then moves them to their pins.
    if (!frames_)
    {
      AnytimeFrameOptions options = options_.frames;
      options.release_tolerance = solveOptions().tolerance;
      frames_ = std::make_unique<AnytimeFrames>(*mesh_, *paper_, options_.material, options_.contact, options,
                                                options_.surroundings);
    }
    std::vector<CurvedPin> here = at;
    for (CurvedPin& pin : here)
      pin.position = x_.col(pin.node);
    if (const Status started = frames_->start(x_, here); !started)
      return Failure::failure(started.message());
    frames_live_ = true;
  }
  Expected<FrameReport> report = frames_->frame(at);
  if (!report)
    return report;
  x_ = frames_->positions();
  pins_ = pins;
  last_steps_ = 1;
  balanced_ = !report->inertial && report->max_force <= solveOptions().tolerance;
  frame_made_ = steadySeconds();
  return report;
}

double CurvedSheetFollower::secondsSinceFrame() const
{
  return steadySeconds() - frame_made_;
}

Expected<CurvedReport> CurvedSheetFollower::settle()
{
  if (!hasSheet())
    return Expected<CurvedReport>::failure("no state to settle yet");
  CurvedReport report;
  report.converged = balanced_;
  if (!onFrames())
    return report;
  const ReleaseReport released = frames_->release();
  x_ = frames_->positions();
  balanced_ = released.converged;
  report.converged = released.converged;
  report.max_force = released.max_force;
  report.iterations = released.corrections + released.newton_iterations;
  report.factorizations = released.factorizations;
  report.seconds = released.seconds;
  return report;
}

}  // namespace virtual_origami::core
