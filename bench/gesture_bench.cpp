// Benchmark (not a test): the preview latency of the crane's mouse gestures (SPEC §3.6–3.8), from
// a pointer event to the serialized markers that show it, on the crane at its most layered state.
//
//   gesture_bench OUT.csv CRANE.json
//
// The crane is folded by its reference sequence (test/data/crane_reference.json); of the states
// after every step the one with the most layers of paper over one point (core::layerCount at the
// faces' centroids) is taken. On it, every pointer event of a gesture is timed alone (wall clock,
// steady_clock, one event at a time on this thread), the whole path a preview takes inside the
// nodes except the transport between them:
//
// - vertex_drag, vertex_drag_stack: the interaction's target for the pointer, then paper_model's
//   drag_vertex preview (Session::dragVertex, commit false: the workspace copied, the solve with
//   spring_solver's defaults, the preview set) and the paper's markers (paperMarkers) serialized
//   as publish serializes them. vertex_drag moves a wing's tip along the path the wing's fold takes
//   it (its faces hinge on the wing's axis: the solver finds them rigid at once); vertex_drag_stack
//   moves the far corner of the stack the rotation below turns, along that turn's arc, so the
//   solver carries every layer after it (each preview from the committed paper, as the node does).
// - flat_fold_frame: one frame of an animated fold on chosen creases (Session::flatFold, commit
//   false, fractions 1/8 … 1, as the interaction's animation asks them) and the markers.
// - rotate_stack: the interaction's ring angle for the pointer (core::ringAngle) and its drag
//   markers (rotationDragMarkers), then paper_model's rotate preview of a flap carrying its stack
//   (Session::rotate, commit false, carry_stack) and the paper's markers, 0.45° further each event.
//   The stack: the most faces any right-angle turn about a crease carries rigidly (on the crane
//   before its wings open, the body's eight layers about a wing's hinge), within the ring's limits
//   (core::rotationRing: those of the layers the turn carries).
// - pick_vertex, pick_face, mark_crease: the interaction's own work on a press in drag mode, on a
//   face, and a click on a crease in fold mode: core::verticesUnder / facesUnder / creasesUnder on
//   the state and the markers that show the pick (pickMarkers, chosenCreaseMarkers), serialized.
//
// Left out: the ROS service round trip between interaction and paper_model (and paper_model's to
// spring_solver: the solve runs in this process, with spring_solver's default limits), the
// publish's socket write and rviz drawing. A few events of each gesture run first untimed.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <ros/serialization.h>
#include <ros/time.h>

#include "virtual_origami/core/chosen_creases.h"
#include "virtual_origami/core/drag.h"
#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/core/layer_pick.h"
#include "virtual_origami/core/layers.h"
#include "virtual_origami/core/rotate.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/snap.h"
#include "virtual_origami/ros/interaction_markers.h"
#include "virtual_origami/ros/markers.h"
#include "virtual_origami/solvers/solver_factory.h"

namespace
{
using namespace virtual_origami;
using namespace virtual_origami::core;
using Clock = std::chrono::steady_clock;

constexpr int kEvents = 200;
constexpr int kWarmup = 5;

double percentile(std::vector<double> v, double p)
{
  std::sort(v.begin(), v.end());
  const double rank = p * (v.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(rank));
  const size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (rank - lo) * (v[hi] - v[lo]);
}

/// What publish does with a message for a subscriber in another process: its length, a buffer,
/// the bytes written. Returns the length so the work cannot be optimised away.
template <class Message>
size_t serialized(const Message& message)
{
  const ros::SerializedMessage bytes = ros::serialization::serializeMessage(message);
  return bytes.num_bytes;
}

/// Layers of paper over a face's centroid (the faces whose folded polygon holds it), per face.
std::vector<int> layersPerFace(const Paper& paper)
{
  std::vector<int> out;
  for (size_t f = 0; f < paper.faces.size(); ++f)
    out.push_back(layerCount(paper, paper.faceCentroid(static_cast<int>(f)), 1e-9 * paper.scale()));
  return out;
}

int maxStackLevel(const Paper& paper)
{
  const std::vector<int> levels = stackLevels(paper);
  return levels.empty() ? 0 : *std::max_element(levels.begin(), levels.end());
}

struct Row
{
  explicit Row(std::string name) : gesture(std::move(name)) {}
  std::string gesture;
  std::vector<double> ms;
  int refused = 0;
};

struct Timer
{
  Clock::time_point start = Clock::now();
  double ms() const { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }
};

std::shared_ptr<ShapeSolver> springSolverDefault()
{
  // spring_solver's defaults (cfg/SpringSolver.cfg): newton, strain 1e-10, 1000 iterations, 1 s.
  std::shared_ptr<ShapeSolver> solver = makeSolver("newton");
  SolveLimits limits;
  limits.tolerance = 1e-10;
  limits.max_iterations = 1000;
  limits.max_seconds = 1.0;
  solver->setLimits(limits);
  return solver;
}

const Vec3 kDown(0, 0, -1);  // the interaction's presses and clicks look straight down on the model

Expected<FoldSequence> readSequence(const char* path)
{
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return parseFoldSequence(text.str());
}

/// The most layered state: the most layers over one point; of states with as many, the most
/// faces lying in stacks (the sum of the layers over every face), then the later (the most folded).
struct MostLayered
{
  size_t state = 0;
  int layers = 0, stacked = 0;
};

MostLayered mostLayered(const std::vector<Paper>& states)
{
  MostLayered chosen;
  for (size_t s = 0; s < states.size(); ++s)
  {
    const std::vector<int> per_face = layersPerFace(states[s]);
    const int here = per_face.empty() ? 0 : *std::max_element(per_face.begin(), per_face.end());
    int sum = 0;
    for (int l : per_face)
      sum += l;
    std::printf("state %2zu: %3zu vertices, %3zu faces, %2d layers, %4d face layers, stack levels %d\n", s,
                states[s].vertices.size(), states[s].faces.size(), here, sum, maxStackLevel(states[s]) + 1);
    if (here > chosen.layers || (here == chosen.layers && sum >= chosen.stacked))
      chosen = MostLayered{ s, here, sum };
  }
  return chosen;
}

/// A fold that exists at that state: the wing steps first (opening a wing), then every other
/// flat fold of the sequence, the first whose whole fold the state accepts. Null if none.
const FlatFoldRequest* foldOfState(const FoldSequence& sequence, const Paper& paper)
{
  for (auto it = sequence.steps.rbegin(); it != sequence.steps.rend(); ++it)
  {
    if (it->operation.kind != Operation::Kind::FlatFold)
      continue;
    Paper copy = paper;
    const Expected<FlatFoldResult> made = flatFold(copy, it->operation.flat_fold);
    if (made && !made->moved_faces.empty())
    {
      std::printf("flat fold: \"%s\" (%zu creases set, %zu faces move)\n", it->note.c_str(), made->changed_edges.size(),
                  made->moved_faces.size());
      return &it->operation.flat_fold;
    }
  }
  return nullptr;
}

/// The turn that carries the most: a face turned a right angle about one of its creases (towards
/// unfolded, by the sign the turn's own checks accept) rigidly, without a solver, with the layers
/// stacked on its side; of those, the one that moves the most faces. `flap` empty if none.
struct StackTurn
{
  RotateRequest request;
  std::vector<int> flap;
};

StackTurn turnCarryingMost(const Paper& paper)
{
  StackTurn best;
  for (size_t e = 0; e < paper.edges.size(); ++e)
    for (int f : paper.edges[e].faces)
    {
      const double current = paper.edges[e].fold_angle;
      if (f < 0 || std::abs(current) < 0.5)  // a flat crease: nothing stacked turns about it
        continue;
      for (double sign : { -1.0, 1.0 })
      {
        RotateRequest request;
        request.face = f;
        request.axis_edge = static_cast<int>(e);
        request.click = paper.faceCentroid(f);
        request.angle = sign * std::copysign(M_PI / 2, current);
        request.carry_stack = true;
        Paper copy = paper;
        const Expected<RotateResult> turned = rotate(copy, request, nullptr);
        if (!turned || turned->used_solver)
          continue;
        if (turned->moved_faces.size() > best.flap.size())
          best = StackTurn{ request, turned->moved_faces };
      }
    }
  return best;
}

/// A vertex dragged along a path, one point an event.
struct DragPath
{
  std::string gesture;
  int vertex = -1;
  std::vector<Vec3> path;
};

/// Two vertex drags. The wing's tip: of the vertices the flat fold moves, the one it moves
/// farthest. The stack's far corner: of the vertices the turn carries, the farthest from the axis.
std::vector<DragPath> dragVertices(const Paper& paper, const FlatFoldRequest& fold, const StackTurn& turn,
                                   const Vec3& axis_d)
{
  std::vector<DragPath> drags(2);
  drags[0].gesture = "vertex_drag";
  drags[1].gesture = "vertex_drag_stack";
  const Expected<Paper> folded = flatFoldFrame(paper, fold, 1.0);
  double reach = -1;
  for (size_t v = 0; v < paper.vertices.size(); ++v)
  {
    const double moved = (folded->vertices[v].folded - paper.vertices[v].folded).norm();
    if (moved > reach)
    {
      reach = moved;
      drags[0].vertex = static_cast<int>(v);
    }
  }
  const Vec3 axis_a = paper.vertices[paper.edges[turn.request.axis_edge].vertices[0]].folded;
  const auto fromAxis = [&](int v) {
    const Vec3 r = paper.vertices[v].folded - axis_a;
    return (r - r.dot(axis_d) * axis_d).norm();
  };
  // Not a vertex whose faces all hinge on the axis (a wing's tip): one that moving alone
  // would tear a face off the rest, so the solver must carry the stack after it.
  const auto hinged = [&](int v) {
    for (int f : paper.facesOfVertex(v))
      for (int w : paper.faces[f].vertices)
        if (w != v && fromAxis(w) > 1e-7 * paper.scale())
          return false;
    return true;
  };
  reach = -1;
  for (int f : turn.flap)
    for (int v : paper.faces[f].vertices)
      if (fromAxis(v) > reach && !hinged(v))
      {
        reach = fromAxis(v);
        drags[1].vertex = v;
      }
  return drags;
}

/// The drags' paths: the wing's tip along the path the fold's frames take it (event i: i/N of the
/// fold; its faces all hinge on the wing's axis, so the solver finds them rigid at once), the
/// stack's far corner along the path the turn takes it (event i: i/N of the right angle; the
/// solver moves every layer of the stack after it). False if a frame or turn fails.
bool followPaths(const Paper& paper, const FlatFoldRequest& fold, const RotateRequest& turn,
                 const std::vector<double>& angles, std::vector<DragPath>& drags)
{
  for (int i = 0; i < kEvents; ++i)
  {
    const Expected<Paper> frame = flatFoldFrame(paper, fold, static_cast<double>(i + 1) / kEvents);
    RotateRequest request = turn;
    request.angle = angles[i];
    Paper turned = paper;
    if (!frame || !rotate(turned, request, nullptr))
    {
      std::cerr << "gesture_bench: no path for the drags at " << i + 1 << "/" << kEvents << "\n";
      return false;
    }
    drags[0].path.push_back(frame->vertices[drags[0].vertex].folded);
    drags[1].path.push_back(turned.vertices[drags[1].vertex].folded);
  }
  for (const DragPath& drag : drags)
    std::printf("%s: vertex %d, %.3f of the sheet along its path\n", drag.gesture.c_str(), drag.vertex,
                (drag.path.back() - paper.vertices[drag.vertex].folded).norm());
  return true;
}

/// Every gesture timed on one state of the paper, a row each, in the order run; a few events of
/// each run first untimed.
class GestureTiming
{
public:
  explicit GestureTiming(const Paper& paper) : paper_(paper), radius_(SnapSettings{}.radius * paper.scale())
  {}

  /// (a) A vertex drag: the pointer's move since the press carries the vertex as far.
  void vertexDrag(const DragPath& drag)
  {
    Row row(drag.gesture);
    Session session(paper_);
    session.setSolver(springSolverDefault());
    const Vec3 at_press = paper_.vertices[drag.vertex].folded;
    int iterations = 0;
    double off_target = 0.0, strain = 0.0;
    for (int i = -kWarmup; i < kEvents; ++i)
    {
      const Vec3 pointer = drag.path[std::max(i, 0)] - at_press;  // the pointer's move since the press
      const Timer timer;
      // The interaction: the vertex's target, where it was at the press moved as far as the pointer.
      const Vec3 target = at_press + pointer;
      const Expected<PullResult> dragged = session.dragVertex(PullTarget{ drag.vertex, target }, false);
      if (dragged)
        bytes_ += serialized(paperMarkers(*session.preview(), marker_style_, ros::Time::now()));
      const double ms = timer.ms();
      if (i < 0)
        continue;
      row.ms.push_back(ms);
      if (dragged)
      {
        iterations += dragged->solve.iterations;
        off_target = std::max(off_target, (session.preview()->vertices[drag.vertex].folded - target).norm());
        strain = std::max(strain, dragged->solve.max_strain);
      }
      else if (row.refused++ == 0)
        std::printf("%s refused at event %d: %s\n", drag.gesture.c_str(), i, dragged.message().c_str());
    }
    std::printf("%s: %.1f solver iterations an event, the vertex at most %.2g from its target, strain at most "
                "%.2g\n", drag.gesture.c_str(), static_cast<double>(iterations) / kEvents, off_target, strain);
    rows_.push_back(row);
  }

  /// (b) Flat fold preview frames: the interaction's animation, 1/8 … 1 of the fold, 25 times.
  void flatFoldFrames(const FlatFoldRequest& fold)
  {
    Row row("flat_fold_frame");
    Session session(paper_);
    session.setSolver(springSolverDefault());
    constexpr int frames = 8;
    for (int i = -kWarmup; i < kEvents; ++i)
    {
      const double fraction = static_cast<double>((((i % frames) + frames) % frames) + 1) / frames;
      const Timer timer;
      const Expected<FlatFoldResult> frame = session.flatFold(fold, false, fraction);
      if (frame)
        bytes_ += serialized(paperMarkers(*session.preview(), marker_style_, ros::Time::now()));
      const double ms = timer.ms();
      if (i < 0)
        continue;
      row.ms.push_back(ms);
      if (!frame && row.refused++ == 0)
        std::printf("flat fold frame refused at %g: %s\n", fraction, frame.message().c_str());
    }
    rows_.push_back(row);
  }

  /// (c) Rotation through stacked layers: the ring seen from the side (not edge-on), the pointer
  /// where the pressed point turns to. False if the ring does not allow the turn.
  bool rotateStack(const RotateRequest& turn, const std::vector<double>& angles, const Vec3& axis_d)
  {
    Row row("rotate_stack");
    Session session(paper_);
    session.setSolver(springSolverDefault());
    const Vec3 view = (Vec3(0, 0, -0.6) + 0.8 * axis_d).normalized();
    Expected<RotationRing> ring = rotationRing(paper_, turn.click, view, turn.face, turn.axis_edge);
    if (!ring)
    {
      std::cerr << "gesture_bench: no ring for the turn: " << ring.message() << "\n";
      return false;
    }
    ring->edge_on = false;
    // The ring's limits are those of the stack the turn carries: the turn timed must lie within.
    std::printf("ring: face %d, axis %d, limits %.1f° to %.1f°\n", ring->face, ring->axis_edge,
                ring->min_angle * 180 / M_PI, ring->max_angle * 180 / M_PI);
    if (turn.angle < ring->min_angle - 1e-12 || turn.angle > ring->max_angle + 1e-12)
    {
      std::cerr << "gesture_bench: the ring does not allow the turn rotate() makes\n";
      return false;
    }
    int off_path = 0;
    double previous = 0.0;
    size_t carried = paper_.faces.size();
    for (int i = -kWarmup; i < kEvents; ++i)
    {
      const int k = std::max(i, 0);
      const Vec3 pointer = ringPoint(*ring, angles[k]);
      const Timer timer;
      const double angle = ringAngle(*ring, pointer, view, previous);
      bytes_ += serialized(rotationDragMarkers(*ring, angle, interaction_style_, ros::Time::now()));
      RotateRequest request = turn;
      request.click = ring->press;
      request.angle = angle;
      const Expected<RotateResult> turned = session.rotate(request, false);
      if (turned)
        bytes_ += serialized(paperMarkers(*session.preview(), marker_style_, ros::Time::now()));
      const double ms = timer.ms();
      previous = angle;
      if (i < 0)
        continue;
      row.ms.push_back(ms);
      if (turned)
        carried = std::min(carried, turned->moved_faces.size());
      if (std::abs(angle - angles[k]) > 1e-6 && off_path++ < 3)
        std::printf("  pointer at %.3f° gave %.3f°\n", angles[k] * 180 / M_PI, angle * 180 / M_PI);
      if (!turned && row.refused++ == 0)
        std::printf("rotation refused at %.2f°: %s\n", angle * 180 / M_PI, turned.message().c_str());
    }
    if (off_path)
      std::printf("rotation: the ring gave another angle than the pointer's at %d events\n", off_path);
    std::printf("rotation: every preview carried at least %zu faces\n", carried);
    rows_.push_back(row);
    return true;
  }

  // The interaction's own work on presses and clicks, looking straight down on the model.

  void pickVertex()
  {
    Row row("pick_vertex");
    for (int i = -kWarmup; i < kEvents; ++i)
    {
      const Vec3 at = paper_.vertices[std::max(i, 0) % paper_.vertices.size()].folded;
      const Timer timer;
      const std::vector<int> under = verticesUnder(paper_, at, kDown, radius_);
      bytes_ +=
          serialized(pickMarkers(paper_, -1, under.empty() ? -1 : under[0], interaction_style_, ros::Time::now()));
      const double ms = timer.ms();
      if (i >= 0)
      {
        row.ms.push_back(ms);
        row.refused += under.empty();
      }
    }
    rows_.push_back(row);
  }

  void pickFace()
  {
    Row row("pick_face");
    for (int i = -kWarmup; i < kEvents; ++i)
    {
      const Vec3 at = paper_.faceCentroid(std::max(i, 0) % paper_.faces.size());
      const Timer timer;
      const std::vector<int> under = facesUnder(paper_, at, kDown);
      bytes_ +=
          serialized(pickMarkers(paper_, under.empty() ? -1 : under[0], -1, interaction_style_, ros::Time::now()));
      const double ms = timer.ms();
      if (i >= 0)
      {
        row.ms.push_back(ms);
        row.refused += under.empty();
      }
    }
    rows_.push_back(row);
  }

  /// Clicks on the creases' midpoints in turn; the marks cleared every 7 clicks (a fold's worth).
  void markCrease(int fixed_face)
  {
    Row row("mark_crease");
    std::vector<int> creases;
    for (size_t e = 0; e < paper_.edges.size(); ++e)
      if (paper_.edges[e].isCrease())
        creases.push_back(static_cast<int>(e));
    CreaseMarks marks;
    for (int i = -kWarmup; i < kEvents; ++i)
    {
      const Edge& edge = paper_.edges[creases[std::max(i, 0) % creases.size()]];
      const Vec3 at = 0.5 * (paper_.vertices[edge.vertices[0]].folded + paper_.vertices[edge.vertices[1]].folded);
      if ((i + kWarmup) % 7 == 0)
        marks.clear();
      const Timer timer;
      const std::vector<int> under = creasesUnder(paper_, at, kDown, radius_);
      if (!under.empty())
        marks.mark(paper_, under[0], nextMark(marks.markOf(paper_, under[0])));
      bytes_ += serialized(chosenCreaseMarkers(paper_, marks.edges(paper_), under.empty() ? -1 : under[0], fixed_face,
                                               interaction_style_, ros::Time::now()));
      const double ms = timer.ms();
      if (i >= 0)
      {
        row.ms.push_back(ms);
        row.refused += under.empty();
      }
    }
    rows_.push_back(row);
  }

  /// The rows as CSV at `path` and as a table on stdout.
  void write(const char* path, int layers) const
  {
    std::ofstream csv(path);
    csv << "gesture,vertices,faces,layers,events,median_ms,p95_ms,max_ms,refused\n";
    std::printf("%-16s %7s %9s %9s %9s %s\n", "gesture", "events", "median", "p95", "max", "refused/missed");
    for (const Row& row : rows_)
    {
      const double median = percentile(row.ms, 0.5), p95 = percentile(row.ms, 0.95),
                   max = *std::max_element(row.ms.begin(), row.ms.end());
      csv << row.gesture << ',' << paper_.vertices.size() << ',' << paper_.faces.size() << ',' << layers << ','
          << row.ms.size() << ',' << median << ',' << p95 << ',' << max << ',' << row.refused << '\n';
      std::printf("%-16s %7zu %7.3f ms %7.3f ms %7.3f ms %d\n", row.gesture.c_str(), row.ms.size(), median, p95, max,
                  row.refused);
    }
    std::printf("(%zu bytes of markers serialized)\n", bytes_);
  }

private:
  const Paper& paper_;
  MarkerStyle marker_style_;
  InteractionStyle interaction_style_;
  const double radius_;
  std::vector<Row> rows_;
  size_t bytes_ = 0;  // kept so the serialization is not optimised away
};
}  // namespace

int main(int argc, char** argv)
{
  if (argc < 3)
  {
    std::cerr << "usage: gesture_bench OUT.csv CRANE.json\n";
    return 2;
  }
  ros::Time::init();
  const Expected<FoldSequence> sequence = readSequence(argv[2]);
  if (!sequence)
  {
    std::cerr << "gesture_bench: " << argv[2] << ": " << sequence.message() << "\n";
    return 1;
  }
  Session folding(Paper::square(sequence->size));
  const Expected<std::vector<Paper>> states = foldSequence(*sequence, folding, makeSolver(sequence->solver));
  if (!states)
  {
    std::cerr << "gesture_bench: the crane does not fold: " << states.message() << "\n";
    return 1;
  }
  const MostLayered chosen = mostLayered(*states);
  const Paper paper = (*states)[chosen.state];
  std::printf("most layered: state %zu, %d layers, %zu vertices, %zu faces\n", chosen.state, chosen.layers,
              paper.vertices.size(), paper.faces.size());

  const FlatFoldRequest* fold = foldOfState(*sequence, paper);
  if (!fold)
  {
    std::cerr << "gesture_bench: no flat fold of the sequence folds the most layered state\n";
    return 1;
  }
  const int fixed_face = faceContaining(paper, fold->fixed_point);
  const StackTurn turn = turnCarryingMost(paper);
  if (turn.flap.empty())
  {
    std::cerr << "gesture_bench: no flap of that fold turns rigidly with a stack\n";
    return 1;
  }
  std::printf("rotation: face %d about edge %d (fold angle %.1f°), %zu faces carried\n", turn.request.face,
              turn.request.axis_edge, paper.edges[turn.request.axis_edge].fold_angle * 180 / M_PI, turn.flap.size());

  // The pointer's path of the turn: event i turns the flap i/N of a right angle.
  std::vector<double> angles(kEvents);
  for (int i = 0; i < kEvents; ++i)
    angles[i] = turn.request.angle * (i + 1) / kEvents;
  const Edge& axis = paper.edges[turn.request.axis_edge];
  const Vec3 axis_d = (paper.vertices[axis.vertices[1]].folded - paper.vertices[axis.vertices[0]].folded).normalized();
  std::vector<DragPath> drags = dragVertices(paper, *fold, turn, axis_d);
  if (!followPaths(paper, *fold, turn.request, angles, drags))
    return 1;

  GestureTiming timing(paper);
  for (const DragPath& drag : drags)
    timing.vertexDrag(drag);
  timing.flatFoldFrames(*fold);
  if (!timing.rotateStack(turn.request, angles, axis_d))
    return 1;
  timing.pickVertex();
  timing.pickFace();
  timing.markCrease(fixed_face);
  timing.write(argv[1], chosen.layers);
  return 0;
}
