// Fuzz target: random sequences of Session operations (crease, rotate and its preview,
// squash, undo, redo, reset, load, flat fold on chosen creases, vertex drag) on a few starting papers with each solver, parameters
// bounded but sometimes NaN, infinite or huge. After every step: the model's invariants hold
// (checkValidity), a refused operation changed nothing (paper bit-exact, revision, history),
// a committed one made exactly one revision, and undo/redo walk a shadow history. At the end:
// the operation log re-applied on a fresh session gives the same paper bit for bit (SPEC §7),
// and the journal's JSON and FOLD round-trip the paper.
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_input.h"
#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/session_journal.h"
#include "virtual_origami/core/validity.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;
using virtual_origami::fuzz::ByteReader;

namespace
{
constexpr int kMaxSteps = 32;
constexpr size_t kMaxFaces = 128;  // past this the sequence stops: speed, not correctness
/// What Session::load accepts.
const ValidityTolerance kLoadTolerance{ 1e-4, 1e-6, 1e-12 };

struct Setup
{
  Paper initial;
  std::string solver;  // empty: none
};

Setup decodeSetup(ByteReader& in)
{
  Setup s;
  switch (in.byte() % 6)
  {
    case 3:
    {
      static const double sizes[] = { 1e-3, 0.2, 7.0, 1e3 };
      s.initial = Paper::square(sizes[in.byte() % 4]);
      break;
    }
    case 4:
    {
      // A flat-foldable degree-4 vertex (sectors α, β, π − α, π − β), maybe folded.
      const double alpha = in.range(0.3, 1.4), beta = in.range(0.3, 1.4);
      s.initial = degree4Vertex({ alpha, beta, M_PI - alpha, M_PI - beta });
      const double rho = in.range(-2.5, 2.5);
      const auto angles = degree4FoldAngles(alpha, beta, rho, 1 + in.byte() % 2);
      std::vector<double> fold(s.initial.edges.size(), 0.0);
      int k = 0;
      for (size_t e = 0; e < s.initial.edges.size() && k < 4; ++e)
        if (s.initial.edges[e].isCrease())
          fold[e] = angles[k++];
      if (in.flag())
        (void)foldToAngles(s.initial, fold);  // refused when they do not close: stays flat
      break;
    }
    case 5:
    {
      const int columns = 1 + in.byte() % 3, rows = 1 + in.byte() % 3;
      const double gamma = in.range(0.3, 1.2);
      s.initial = miuraOri(columns, rows, 1.0, 1.0, gamma);
      if (in.flag())
        (void)foldToAngles(s.initial, miuraFoldAngles(s.initial, columns, rows, gamma, in.range(-2.0, 2.0)));
      break;
    }
    default:
      s.initial = Paper::square(1.0);
  }
  static const char* solvers[] = { "newton", "shape_matching", "rigid_kinematics", "seed_spring", "" };
  s.solver = solvers[in.byte() % 5];
  return s;
}

std::shared_ptr<ShapeSolver> makeBoundedSolver(const std::string& name)
{
  if (name.empty())
    return nullptr;
  std::shared_ptr<ShapeSolver> solver = makeSolver(name);
  // Iterations only, never wall time: runs must be reproducible. Small budgets keep the
  // fuzzer fast; a solve that runs out refuses the operation, which is tested too.
  SolveLimits limits;
  limits.max_iterations = name == "seed_spring" ? 400 : name == "shape_matching" ? 150 : 25;
  solver->setLimits(limits);
  return solver;
}

/// A point for a crease end or a click: mostly on or near the folded paper (vertices, points
/// along edges between vertices, centroids, a grid), sometimes anywhere, non-finite or huge.
Vec3 decodePoint(ByteReader& in, const Paper& paper)
{
  const int vertices = static_cast<int>(paper.vertices.size());
  const double scale = paper.scale();
  switch (in.byte() % 12)
  {
    case 4:
    case 5:
      return paper.vertices[in.index(vertices)].folded;
    case 6:
    case 7:
    {
      const Vec3& a = paper.vertices[in.index(vertices)].folded;
      const Vec3& b = paper.vertices[in.index(vertices)].folded;
      return a + in.unit() * (b - a);
    }
    case 8:
      return paper.faceCentroid(in.index(static_cast<int>(paper.faces.size())));
    case 9:
      return Vec3(in.flag() ? in.special() : 0.5 * scale, in.flag() ? in.special() : 0.5 * scale,
                  in.flag() ? in.special() : 0.0);
    case 10:
      return Vec3((in.byte() % 9) / 8.0 * scale, (in.byte() % 9) / 8.0 * scale, 0.0);
    case 11:
    {
      // Just off a vertex: where tolerances decide.
      const double offsets[] = { 1e-12, 1e-10, 1e-9, 1e-8, 1e-7, 1e-6 };
      Vec3 p = paper.vertices[in.index(vertices)].folded;
      p[in.byte() % 3] += (in.flag() ? 1 : -1) * offsets[in.byte() % 6] * scale;
      return p;
    }
    default:
    {
      // Anywhere in the folded model's box, a fifth wider on each side.
      Vec3 lo = paper.vertices[0].folded, hi = lo;
      for (const Vertex& v : paper.vertices)
      {
        lo = lo.cwiseMin(v.folded);
        hi = hi.cwiseMax(v.folded);
      }
      const Vec3 pad = Vec3::Constant(0.2 * scale);
      lo -= pad;
      hi += pad;
      return Vec3(in.range(lo.x(), hi.x()), in.range(lo.y(), hi.y()), in.flag() ? 0.0 : in.range(lo.z(), hi.z()));
    }
  }
}

double decodeAngle(ByteReader& in)
{
  switch (in.byte() % 6)
  {
    case 0:
      return (static_cast<int>(in.byte() % 17) - 8) * M_PI / 4;  // multiples of 45°, up to ±360°
    case 1:
      return (in.flag() ? 1 : -1) * (M_PI + (in.flag() ? 1e-10 : -1e-10));  // at the 180° limit
    case 2:
      return in.special();
    default:
      return in.range(-M_PI, M_PI);
  }
}

int decodeId(ByteReader& in, int count)
{
  switch (in.byte() % 8)
  {
    case 0:
      return -1;
    case 1:
      return count + in.byte();  // out of range
    case 2:
      return -2 - in.byte();
    default:
      return in.index(count);
  }
}

std::string describe(const Vec3& p)
{
  std::ostringstream s;
  s.precision(17);
  s << '(' << p.x() << ", " << p.y() << ", " << p.z() << ')';
  return s.str();
}

class Runner
{
public:
  explicit Runner(const Setup& setup) : setup_(setup), session_(setup.initial)
  {
    session_.setSolver(makeBoundedSolver(setup.solver));
    trace_.precision(17);
  }

  void run(ByteReader& in)
  {
    trace_ << "start: " << setup_.initial.vertices.size() << " vertices, " << setup_.initial.faces.size()
           << " faces, solver \"" << setup_.solver << "\"\n";
    const ValidityReport start = checkValidity(session_.paper(), tolerance_);
    if (!start.ok())
      return;  // a starting pattern the decoder could not fold cleanly: nothing to test
    for (int step = 0; step < kMaxSteps && !in.empty() && session_.paper().faces.size() <= kMaxFaces; ++step)
      this->step(in);
    finish();
    if (std::getenv("VO_FUZZ_TRACE"))  // to see what an input does
      std::fprintf(stderr, "%s", trace_.str().c_str());
  }

private:
  struct Before
  {
    Paper paper;
    uint64_t revision;
    size_t log, undo, redo;
  };

  Before snapshot() const
  {
    const History& h = session_.history();
    return { h.paper, h.revision, h.log.size(), h.undo.size(), h.redo.size() };
  }

  void check(bool ok, const std::string& what) const
  {
    if (!ok)
      virtual_origami::fuzz::fail(what, trace_.str());
  }

  void expectValid(const Paper& paper, const std::string& what) const
  {
    const ValidityReport report = checkValidity(paper, tolerance_);
    if (report.ok())
      return;
    // The worst length error, to full precision: the report rounds to six digits.
    double worst = 0.0;
    for (const Face& f : paper.faces)
      for (int a : f.vertices)
        for (int b : f.vertices)
          if (a < static_cast<int>(paper.vertices.size()) && b < static_cast<int>(paper.vertices.size()))
            worst = std::max(worst, std::abs((paper.vertices[a].folded - paper.vertices[b].folded).norm() -
                                             (paper.vertices[a].crease_pattern - paper.vertices[b].crease_pattern).norm()));
    std::ostringstream detail;
    detail << " (worst length error " << worst << ", tolerance " << tolerance_.length * paper.scale() << ")";
    check(false, what + detail.str() + ": " + report.summary());
  }

  void expectUnchanged(const Before& b, const std::string& message) const
  {
    const History& h = session_.history();
    check(!message.empty(), "a refusal without a message");
    check(h.paper == b.paper, "a refused operation changed the paper");
    check(h.revision == b.revision && h.log.size() == b.log && h.undo.size() == b.undo && h.redo.size() == b.redo,
          "a refused operation changed the revision or the history");
  }

  /// A committed change: one revision, one log entry, the previous paper on the undo stack.
  void expectCommitted(const Before& b)
  {
    const History& h = session_.history();
    check(h.revision == b.revision + 1 && h.log.size() == b.log + 1, "a commit did not make exactly one revision");
    check(h.log.back().revision == h.revision, "the log entry does not carry its revision");
    expectValid(h.paper, "invariants after " + std::string(kindName(h.log.back().kind)));
    check(!h.undo.empty() && h.undo.back() == b.paper, "the undo stack does not hold the paper before the change");
    check(h.redo.empty(), "a new change left something to redo");
  }

  void step(ByteReader& in)
  {
    const Before before = snapshot();
    const Paper& paper = session_.paper();
    switch (in.byte() % 8)
    {
      case 0:
      case 1:
      {
        CreaseRequest r;
        r.start = decodePoint(in, paper);
        r.end = decodePoint(in, paper);
        if (in.byte() % 4 == 0)
          r.eye = in.flag() ? Vec3(decodePoint(in, paper) + Vec3(0, 0, in.range(0.1, 5.0) * paper.scale()))
                            : decodePoint(in, paper);
        r.snap = in.flag();
        trace_ << "crease " << describe(r.start) << " -> " << describe(r.end)
               << (r.eye ? " eye " + describe(*r.eye) : std::string()) << (r.snap ? " snap" : "");
        const auto result = session_.crease(r);
        outcome(result.ok(), result.message());
        if (result)
        {
          expectCommitted(before);
          for (int e : result->new_edges)
            check(e >= 0 && e < static_cast<int>(session_.paper().edges.size()) &&
                      session_.paper().edges[e].isCrease(),
                  "crease reported an edge that is not a crease");
        }
        else
          expectUnchanged(before, result.message());
        break;
      }
      case 2:
      case 3:
      {
        RotateRequest r;
        r.face = decodeId(in, static_cast<int>(paper.faces.size()));
        r.axis_edge = decodeId(in, static_cast<int>(paper.edges.size()));
        r.click = decodePoint(in, paper);
        r.angle = decodeAngle(in);
        r.carry_stack = in.byte() % 8 != 0;
        const bool commit = in.byte() % 4 != 0;
        trace_ << (commit ? "rotate" : "preview") << " face " << r.face << " axis " << r.axis_edge << " click "
               << describe(r.click) << " angle " << r.angle << (r.carry_stack ? "" : " alone");
        const auto result = session_.rotate(r, commit);
        outcome(result.ok(), result.message());
        if (result && result->used_solver)
          trace_ << " [solver: " << result->solve.iterations << " iterations, max strain " << result->solve.max_strain
                 << "]";
        else if (result)
          trace_ << " [rigid, " << result->moved_faces.size() << " faces]";
        if (!result)
          expectUnchanged(before, result.message());
        else if (commit)
        {
          expectCommitted(before);
          check(result->face >= 0 && result->axis_edge >= 0, "a committed rotation without face or axis");
        }
        else
        {
          expectUnchanged(before, "preview");
          check(session_.preview().has_value(), "a successful preview left no preview");
          expectValid(*session_.preview(), "invariants of a preview");
        }
        break;
      }
      case 4:
      {
        trace_ << "squash";
        const auto result = session_.squash();
        outcome(result.ok(), result.message());
        if (result)
          expectCommitted(before);
        else
          expectUnchanged(before, result.message());
        break;
      }
      case 5:
      case 6:
      {
        const bool undo = in.byte() % 8 < 5;
        trace_ << (undo ? "undo" : "redo");
        const std::vector<Paper>& from = undo ? session_.history().undo : session_.history().redo;
        const std::optional<Paper> target = from.empty() ? std::nullopt : std::optional<Paper>(from.back());
        const Status status = undo ? session_.undo() : session_.redo();
        outcome(status.ok(), status.message());
        check(status.ok() == target.has_value(), "undo/redo refused with history there, or done without");
        if (status)
        {
          const History& h = session_.history();
          check(h.paper == *target, "undo/redo did not restore the paper it stored");
          check(h.revision == before.revision + 1, "undo/redo did not make one revision");
          check((undo ? h.redo.back() : h.undo.back()) == before.paper, "undo/redo lost the paper it left");
          expectValid(h.paper, "invariants after undo/redo");
        }
        else
          expectUnchanged(before, status.message());
        break;
      }
      default:
      {
        // One byte picks among the rest: flat fold, vertex drag, and reset or load by its low
        // bit, the flag that picked them before (half of those picks now fold or drag).
        const uint8_t pick = in.byte();
        if (pick % 4 == 2)
        {
          flatFold(in, before);
          break;
        }
        if (pick % 4 == 3)
        {
          drag(in, before);
          break;
        }
        if (pick % 2 == 1)
        {
          static const double sizes[] = { 1.0, 0.5, 3.0, 0.0, -1.0 };
          const double size = in.byte() % 4 == 0 ? in.special() : sizes[in.byte() % 5];
          trace_ << "reset " << size;
          const Status status = session_.reset(size);
          outcome(status.ok(), status.message());
          if (status)
          {
            expectCommitted(before);
            check(session_.paper() == Paper::square(size), "reset did not give the square");
          }
          else
            expectUnchanged(before, status.message());
        }
        else
          load(in, before);
      }
    }
    trace_ << '\n';
  }

  /// A fold on chosen creases: one to three segments of the crease pattern (through the paper's
  /// vertices mostly), each valley, mountain or unfold, sometimes a non-finite angle; the face
  /// that stays under a crease-pattern point. Committed, or a preview part of the way.
  void flatFold(ByteReader& in, const Before& before)
  {
    const Paper& paper = session_.paper();
    const auto patternPoint = [&](ByteReader& r) {
      if (!paper.vertices.empty() && r.byte() % 4 != 0)
        return Vec2(paper.vertices[r.index(static_cast<int>(paper.vertices.size()))].crease_pattern);
      return Vec2(decodePoint(r, paper).head<2>());
    };
    std::vector<int> creases;
    for (size_t e = 0; e < paper.edges.size(); ++e)
      if (paper.edges[e].isCrease())
        creases.push_back(static_cast<int>(e));
    FlatFoldRequest request;
    const int count = 1 + in.byte() % 3;
    for (int i = 0; i < count; ++i)
    {
      CreaseLineAngle crease;
      if (!creases.empty() && in.flag())  // along a crease there is: folds that can succeed
      {
        const Edge& edge = paper.edges[creases[in.index(static_cast<int>(creases.size()))]];
        crease.start = paper.vertices[edge.vertices[0]].crease_pattern;
        crease.end = paper.vertices[edge.vertices[1]].crease_pattern;
      }
      else
      {
        crease.start = patternPoint(in);
        crease.end = patternPoint(in);
      }
      static const double angles[] = { M_PI, -M_PI, 0.0, M_PI / 2 };
      crease.angle = in.byte() % 8 == 0 ? in.special() : angles[in.byte() % 4];
      request.creases.push_back(crease);
    }
    request.fixed_point = patternPoint(in);
    const bool commit = in.byte() % 4 != 0;
    const double fraction = commit ? 1.0 : in.byte() % 8 == 0 ? in.special() : in.range(0.0, 1.0);
    trace_ << (commit ? "flat_fold" : "flat_fold preview") << " of " << count << " creases, fixed "
           << describe(Vec3(request.fixed_point.x(), request.fixed_point.y(), 0));
    const auto result = session_.flatFold(request, commit, fraction);
    expectAnswered(before, result.ok(), result.message(), commit);
  }

  /// A vertex dragged to a point (mostly near the paper), committed or previewed.
  void drag(ByteReader& in, const Before& before)
  {
    const Paper& paper = session_.paper();
    PullTarget target;
    target.vertex = decodeId(in, static_cast<int>(paper.vertices.size()));
    target.position = decodePoint(in, paper);
    const bool commit = in.byte() % 4 != 0;
    trace_ << (commit ? "drag_vertex " : "drag_vertex preview ") << target.vertex << " to "
           << describe(target.position);
    const auto result = session_.dragVertex(target, commit);
    expectAnswered(before, result.ok(), result.message(), commit);
  }

  /// An operation that commits or previews: refused, it changed nothing; committed, it made one
  /// revision; previewed, it left the history as it was and a preview there.
  void expectAnswered(const Before& before, bool ok, const std::string& message, bool commit)
  {
    outcome(ok, message);
    if (!ok)
      expectUnchanged(before, message);
    else if (commit)
      expectCommitted(before);
    else
    {
      expectUnchanged(before, "preview");
      check(session_.preview().has_value(), "a successful preview left no preview");
    }
  }

  /// Loads the current paper again through FOLD (must succeed), or a damaged copy of it (a
  /// vertex moved, or a non-finite coordinate: must be refused).
  void load(ByteReader& in, const Before& before)
  {
    const std::string written = formatFold(session_.paper(), "fuzz");
    if (std::getenv("VO_FUZZ_DUMP"))
      std::fprintf(stderr, "%s\n", written.c_str());
    const Expected<FoldDocument> doc = parseFold(written);
    check(doc.ok() && !doc->frames.empty(), "a written FOLD file does not parse: " + doc.message());
    Paper paper = doc->frames.back();
    const int damage = in.byte() % 4;
    if (damage == 1 && !paper.vertices.empty())
      paper.vertices[in.index(static_cast<int>(paper.vertices.size()))].folded.x() += 0.01 * paper.scale();
    if (damage == 2 && !paper.vertices.empty())
      paper.vertices[in.index(static_cast<int>(paper.vertices.size()))].folded.y() = in.special();
    trace_ << "load" << (damage == 1 ? " (vertex moved)" : damage == 2 ? " (special coordinate)" : "");
    const Status status = session_.load(paper, "fuzz.fold");
    outcome(status.ok(), status.message());
    if (status)
    {
      // A loaded model need only be as exact as load asks (files of other tools are rounded);
      // from here on the session's papers are held to that.
      tolerance_ = kLoadTolerance;
      expectCommitted(before);
      loaded_.push_back(paper);
    }
    else
    {
      expectUnchanged(before, status.message());
      // Undamaged, it is refused only as the paper as it is (a load that changes nothing).
      check(damage != 0 || (paper == before.paper && status.message().find(kNothingLoaded) != std::string::npos),
            "the model refused its own FOLD file: " + status.message());
    }
  }

  void outcome(bool ok, const std::string& message)
  {
    trace_ << (ok ? "  -> ok" : "  -> refused: " + message) << " (revision " << session_.revision() << ")";
  }

  void finish()
  {
    const Paper& paper = session_.paper();
    // The journal's JSON is bit-exact.
    const Expected<Paper> json = parsePaperJson(formatPaperJson(paper));
    check(json.ok() && *json == paper, "the journal's JSON does not round-trip the paper");
    // Re-applying the log on a fresh session reproduces the paper exactly (SPEC §7).
    Session again(setup_.initial);
    again.setSolver(makeBoundedSolver(setup_.solver));
    size_t next_load = 0;
    for (const Operation& op : session_.log())
    {
      const Status status =
          op.kind == Operation::Kind::Load ? again.load(loaded_.at(next_load++), op.path) : again.apply(op);
      check(status.ok(), "re-applying the log: " + std::string(kindName(op.kind)) + " at revision " +
                             std::to_string(op.revision) + " failed: " + status.message());
    }
    check(again.revision() == session_.revision(), "re-applying the log gave another revision");
    check(again.paper() == paper, "re-applying the log gave another paper");
  }

  Setup setup_;
  Session session_;
  ValidityTolerance tolerance_;
  std::vector<Paper> loaded_;
  std::ostringstream trace_;
};
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  ByteReader in(data, size);
  const Setup setup = decodeSetup(in);
  Runner(setup).run(in);
  return 0;
}
