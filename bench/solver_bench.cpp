// Rigid-face solvers on one fold step of the rigid reference scenes (SPEC §6, issue 3): single
// crease, degree-4 vertex in both modes, Miura-ori (quads and triangulated), the crane's bird
// base and a 180° flat fold, fold-angle errors against their closed forms; iterations and time
// to max strain < 1e-9 per solver, as ratios to the seed's spring scheme in the same
// run; the seed scheme's reachable accuracy against its iteration budget; and its stability
// against face size. Writes CSV; timings belong here, never in the unit tests.
//
//   solver_bench [out_dir] [repeats] [scene]
//
// With `scene`, only the fold-step scenes whose name contains it, into out_dir/solvers.csv, and
// no seed accuracy or stability sweep.
#include <algorithm>
#include <array>
#include <cstdlib>
#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/core/pull.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/rotate.h"
#include "virtual_origami/solvers/seed_spring_solver.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;

namespace
{
constexpr double kTolerance = 1e-9;
constexpr double kGamma = M_PI / 3;

/// A reference model partly folded, and the fold step to take on it.
struct Scene
{
  std::string name;
  Paper paper;
  RotateRequest step;
  /// When set, the step is a pull instead: these vertices carried to their points, `held`
  /// vertices kept, the solver moving the rest; `pull_next` is the warm step (none: no warm).
  std::vector<PullTarget> pull, pull_next;
  std::vector<int> held;
  std::function<double(const Paper&)> angle_error;  // against the closed form; NaN if none
  /// Budgets: the seed scheme's (both d), and every other solver's.
  int seed_iterations = 2000000;
  double seed_seconds = 120.0;
  bool repeat_seed = false;  // cheap enough to take the seed scheme's median of the repeats too
  int max_iterations = 100000;
  double max_seconds = 30.0;
};

int miuraId(int columns, int i, int j)
{
  return j * (columns + 1) + i;
}

/// Largest deviation of a Miura-ori from tan(ρ_zigzag/2) = −tan(ρ_straight/2)/cos γ.
double miuraError(const Paper& paper, int columns, int rows)
{
  double worst = 0;
  for (int j = 1; j < rows; ++j)
    for (int i = 1; i < columns; ++i)
    {
      const int v = miuraId(columns, i, j);
      const bool right = j % 2 == 0;
      const int c1 = paper.findEdge(v, miuraId(columns, right ? i + 1 : i - 1, j));
      const int c2 = paper.findEdge(v, miuraId(columns, i, right ? j + 1 : j - 1));
      const double zigzag = 2 * std::atan(-std::tan(paper.edges[c1].fold_angle / 2) / std::cos(kGamma));
      worst = std::max(worst, std::abs(paper.edges[c2].fold_angle - zigzag));
    }
  return worst;
}

/// Miura-ori folded to ρ = 0.5 along its rigid folding; the step turns the corner face by
/// −0.05 rad about its straight crease, the face across held, every other face following.
Scene miuraScene(int columns, int rows)
{
  Scene scene;
  scene.name = "miura_" + std::to_string(columns) + "x" + std::to_string(rows);
  scene.paper = miuraOri(columns, rows, 1.0, 1.3, kGamma);
  foldToAngles(scene.paper, miuraFoldAngles(scene.paper, columns, rows, kGamma, 0.5));
  scene.step.face = 0;
  scene.step.axis_edge = scene.paper.findEdge(miuraId(columns, 0, 1), miuraId(columns, 1, 1));
  scene.step.angle = -0.05;
  scene.angle_error = [columns, rows](const Paper& p) { return miuraError(p, columns, rows); };
  return scene;
}

/// The same with each parallelogram split by a diagonal crease into two triangles (the
/// diagonals start flat): faces the seed's springs hold rigidly to first order.
Scene triangulatedMiuraScene(int columns, int rows)
{
  const Paper quads = miuraOri(columns, rows, 1.0, 1.3, kGamma);
  std::vector<Vec2> vertices;
  for (const Vertex& v : quads.vertices)
    vertices.push_back(v.crease_pattern);
  std::vector<std::vector<int>> faces;
  for (const Face& f : quads.faces)
  {
    faces.push_back({ f.vertices[0], f.vertices[1], f.vertices[2] });
    faces.push_back({ f.vertices[0], f.vertices[2], f.vertices[3] });
  }
  Scene scene;
  scene.name = "miura_" + std::to_string(columns) + "x" + std::to_string(rows) + "_triangulated";
  scene.paper = *patternPaper(vertices, faces);
  std::vector<double> angles(scene.paper.edges.size(), 0.0);
  const std::vector<double> quad_angles = miuraFoldAngles(quads, columns, rows, kGamma, 0.5);
  for (size_t e = 0; e < quads.edges.size(); ++e)
  {
    const int t = scene.paper.findEdge(quads.edges[e].vertices[0], quads.edges[e].vertices[1]);
    angles[t] = quad_angles[e];
  }
  foldToAngles(scene.paper, angles);
  // Face 0 is the lower triangle of the corner parallelogram; its straight crease is on top
  // of face 1, so turn face 1 (vertices 0, 2', 3') about that crease.
  scene.step.axis_edge = scene.paper.findEdge(miuraId(columns, 0, 1), miuraId(columns, 1, 1));
  scene.step.face =
      scene.paper.edges[scene.step.axis_edge].faces[0] == 1 || scene.paper.edges[scene.step.axis_edge].faces[1] == 1 ?
          1 :
          0;
  scene.step.angle = -0.05;
  scene.angle_error = [](const Paper&) { return NAN; };
  return scene;
}

/// Budgets of the small scenes (a few faces): tight enough to keep the run short, and cheap
/// enough to take the seed scheme's median of the repeats as well.
void useSmallSceneBudgets(Scene& scene)
{
  scene.seed_iterations = 200000;
  scene.seed_seconds = 5.0;
  scene.repeat_seed = true;
  scene.max_iterations = 20000;
  scene.max_seconds = 2.0;
}

/// Stops the benchmark when a scene does not start where its closed form puts it.
void expectStart(const std::string& name, double error)
{
  std::cout << name << ": start state against its closed form " << error << " rad\n";
  if (!(error < 1e-9))
  {
    std::cerr << name << ": the start state is off its closed form by " << error << " rad\n";
    std::exit(1);
  }
}

/// The unit square with its crease x = 1/2 (faces: left half 0, right half 1) folded to
/// `from`, face 0 in place.
Paper halvedSquare(double from, int& crease)
{
  const std::vector<Vec2> vertices = { { 0, 0 }, { 0.5, 0 }, { 1, 0 }, { 1, 1 }, { 0.5, 1 }, { 0, 1 } };
  Paper paper = *patternPaper(vertices, { { 0, 1, 4, 5 }, { 1, 2, 3, 4 } });
  crease = paper.findEdge(1, 4);
  std::vector<double> angles(paper.edges.size(), 0.0);
  angles[crease] = from;
  if (!foldToAngles(paper, angles))
  {
    std::cerr << "the halved square does not fold to " << from << " rad\n";
    std::exit(1);
  }
  return paper;
}

/// One crease: the unit square folded on its middle line x = 1/2 to `from`, the right half
/// turned on to `to` (warm: on to `next`, none when NaN). rotate() would turn the half rigidly
/// (its crease parts the sheet: exact, no solver), so the step is a pull as a gripper makes
/// it: corner (1, 1) carried along its arc, the left half held, and the solver bringing
/// corner (1, 0) after it (three springs hold it; the mirror solution is the far one).
Scene creaseScene(const std::string& name, double from, double to, double next)
{
  Scene scene;
  scene.name = name;
  int crease = -1;
  scene.paper = halvedSquare(from, crease);
  expectStart(name, std::abs(measuredFoldAngles(scene.paper)[crease] - from));
  scene.pull = { { 3, halvedSquare(to, crease).vertices[3].folded } };
  if (std::isfinite(next))
    scene.pull_next = { { 3, halvedSquare(next, crease).vertices[3].folded } };
  scene.held = { 0, 1, 4, 5 };
  scene.angle_error = [crease, to](const Paper& p) { return std::abs(measuredFoldAngles(p)[crease] - to); };
  useSmallSceneBudgets(scene);
  return scene;
}

/// Sectors α, π − α − … of the degree-4 vertex: α = 50°, β = 70° (π − α = 130°, π − β = 110°);
/// no two creases are collinear.
constexpr double kAlpha4 = 50 * M_PI / 180, kBeta4 = 70 * M_PI / 180;

/// Largest difference between the measured fold angles of the degree-4 vertex and its closed
/// form in `mode` at crease 1's angle `rho1`.
double degree4Error(const Paper& paper, int mode, double rho1)
{
  const std::vector<double> measured = measuredFoldAngles(paper);
  const std::array<double, 4> expected = degree4FoldAngles(kAlpha4, kBeta4, rho1, mode);
  double worst = 0;
  for (int k = 0; k < 4; ++k)
    worst = std::max(worst, std::abs(measured[paper.findEdge(0, k + 1)] - expected[k]));
  return worst;
}

/// The flat-foldable degree-4 vertex placed at crease 1's angle `rho1` in `mode` by its closed
/// form; the step turns face 3 (between creases 4 and 1) about crease 1 by 0.05 rad, rotate()
/// holding it and face 0 across: the solver moves vertex 3, which sets creases 2, 3 and 4.
Scene degree4Scene(int mode, double rho1)
{
  Scene scene;
  scene.name = "degree4_mode" + std::to_string(mode);
  scene.paper = degree4Vertex({ kAlpha4, kBeta4, M_PI - kAlpha4, M_PI - kBeta4 });
  const std::array<double, 4> start = degree4FoldAngles(kAlpha4, kBeta4, rho1, mode);
  std::vector<double> angles(scene.paper.edges.size(), 0.0);
  for (int k = 0; k < 4; ++k)
    angles[scene.paper.findEdge(0, k + 1)] = start[k];
  if (!foldToAngles(scene.paper, angles))
  {
    std::cerr << scene.name << ": the closed form does not close\n";
    std::exit(1);
  }
  expectStart(scene.name, degree4Error(scene.paper, mode, rho1));
  scene.step.face = 3;
  scene.step.axis_edge = scene.paper.findEdge(0, 1);
  scene.step.angle = 0.05;
  const double rho1_next = rho1 + scene.step.angle;
  scene.angle_error = [mode, rho1_next](const Paper& p) { return degree4Error(p, mode, rho1_next); };
  useSmallSceneBudgets(scene);
  return scene;
}

/// sequences/crane.json: from the working directory (make bench runs in the source tree),
/// else beside this file.
std::string craneSequenceText()
{
  const std::string file = __FILE__;
  for (const std::string& path :
       { std::string("sequences/crane.json"), file.substr(0, file.rfind("/bench/") + 1) + "sequences/crane.json" })
  {
    std::ifstream in(path);
    if (in)
    {
      std::stringstream text;
      text << in.rdbuf();
      return text.str();
    }
  }
  std::cerr << "sequences/crane.json not found\n";
  std::exit(1);
}

/// The traditional bird (crane) base as the crane sequence folds it (state 13, after the back
/// petal fold: flat, 17 vertices, 24 faces, up to 8 layers), opened slightly: the front petal's
/// side flap, the triangle (0, 0), (½, 0), (½, t) (t = ½·tan 22.5°) tucked under the petal,
/// turned 0.05 rad out about the petal's edge crease (0, 0)–(½, t). rotate() carries the layers
/// in its way with it and holds the face across; the solver moves every other face. The base is
/// a mechanism of many degrees of freedom (no closed form): the step measures convergence from
/// a flat, stacked state, where the creases sit at ±180°.
Scene craneScene()
{
  Scene scene;
  scene.name = "crane_base";
  const Expected<FoldSequence> sequence = parseFoldSequence(craneSequenceText());
  Session session;
  const Expected<std::vector<Paper>> states =
      sequence ? foldSequence(*sequence, session, makeSolver(sequence->solver)) : Expected<std::vector<Paper>>::failure(sequence.message());
  if (!states || states->size() < 14)
  {
    std::cerr << "the crane sequence does not fold to its bird base: " << (states ? "too few states" : states.message())
              << "\n";
    std::exit(1);
  }
  scene.paper = (*states)[13];
  const double t = 0.5 * std::tan(M_PI / 8);
  const int corner = scene.paper.vertexAt(Vec2(0, 0), 1e-9), middle = scene.paper.vertexAt(Vec2(0.5, 0), 1e-9),
            root = scene.paper.vertexAt(Vec2(0.5, t), 1e-9);
  scene.step.axis_edge = corner < 0 || root < 0 ? -1 : scene.paper.findEdge(corner, root);
  if (scene.step.axis_edge < 0 || middle < 0)
  {
    std::cerr << "the bird base has no crease (0, 0)-(0.5, " << t << ")\n";
    std::exit(1);
  }
  for (int f : scene.paper.edges[scene.step.axis_edge].faces)
    if (f >= 0 && std::count(scene.paper.faces[f].vertices.begin(), scene.paper.faces[f].vertices.end(), middle))
      scene.step.face = f;
  if (scene.step.face < 0)
  {
    std::cerr << "the bird base has no flap (0, 0), (0.5, 0), (0.5, " << t << ")\n";
    std::exit(1);
  }
  scene.step.angle = -0.05;
  scene.angle_error = [](const Paper&) { return NAN; };
  useSmallSceneBudgets(scene);
  return scene;
}

/// The scene's step as rotate() sets it up for a solver: the face turned, it and the face
/// across the axis held (for the seed scheme's accuracy against its budget).
Paper turnedAndHeld(const Scene& scene, std::vector<char>& fixed)
{
  Paper turned = scene.paper;
  const Edge& hinge = turned.edges[scene.step.axis_edge];
  const Vec3 a = turned.vertices[hinge.vertices[0]].folded;
  const Vec3 axis = (turned.vertices[hinge.vertices[1]].folded - a).normalized();
  const double turn = hinge.faces[0] == scene.step.face ? scene.step.angle : -scene.step.angle;
  fixed.assign(turned.vertices.size(), 0);
  for (int v : turned.faces[scene.step.face].vertices)
  {
    fixed[v] = 1;
    turned.vertices[v].folded = a + Eigen::AngleAxisd(turn, axis) * (turned.vertices[v].folded - a);
  }
  for (int v : turned.faces[hinge.otherFace(scene.step.face)].vertices)
    fixed[v] = 1;
  return turned;
}

struct Run
{
  bool converged = false;
  bool diverged = false;
  int iterations = 0;
  double seconds = 0;
  double warm_seconds = NAN;  // the next step of the same drag, the solver's setup kept
  ShapeMetrics metrics;
  double angle_error = NAN;
  std::string message;
};

using SolverMaker = std::function<std::unique_ptr<ShapeSolver>()>;

std::string number(double x)
{
  std::ostringstream out;
  out << std::setprecision(4) << x;
  return out.str();
}

/// Passes every solve to the solver it wraps and keeps the last report and shape: where
/// rotate() or pull() refuses a solve, the benchmark still reports what the solver did in
/// that very setup (the layers carried, the vertices held).
class RecordingSolver : public ShapeSolver
{
public:
  explicit RecordingSolver(std::unique_ptr<ShapeSolver> inner) : inner_(std::move(inner))
  {}
  std::string name() const override
  {
    return inner_->name();
  }
  SolveReport solve(Paper& paper, const std::vector<char>& fixed) override
  {
    inner_->setLimits(limits());
    report = inner_->solve(paper, fixed);
    shape = paper;
    return report;
  }
  SolveReport report;
  Paper shape;

private:
  std::unique_ptr<ShapeSolver> inner_;
};

/// One fold step from the scene's state, then (warm) the next step of the same drag.
Run runStep(const Scene& scene, const SolverMaker& make, int max_iterations, double max_seconds)
{
  RecordingSolver solver(make());
  solver.setLimits({ kTolerance, max_iterations, max_seconds });
  Paper paper = scene.paper;
  Run run;
  bool done = false;
  if (scene.pull.empty())
  {
    const Expected<RotateResult> result = rotate(paper, scene.step, &solver);
    done = result.ok();
    if (!result)
      run.message = result.message();
    else if (!result->used_solver)
      run.message = "rigid turn, no solve";
  }
  else
  {
    const Expected<PullResult> result = pull(paper, scene.pull, &solver, scene.held);
    done = result.ok();
    if (!result)
      run.message = result.message();
    else if (result->residual > 1e-12)
      run.message = "pulled vertex off its target by " + number(result->residual);
  }
  run.converged = done && solver.report.converged;
  run.diverged = solver.report.diverged;
  run.iterations = solver.report.iterations;
  run.seconds = solver.report.seconds;
  if (!done)
  {
    // Refused, the model unchanged: measure the shape the solver left (rolled back if diverged).
    run.metrics = measureShape(solver.shape);
    return run;
  }
  run.metrics = measureShape(paper);
  run.angle_error = scene.angle_error(paper);
  Paper next = paper;
  if (scene.pull.empty())
  {
    const Expected<RotateResult> warm = rotate(next, scene.step, &solver);
    if (warm && warm->used_solver && warm->solve.converged)
      run.warm_seconds = warm->solve.seconds;
  }
  else if (!scene.pull_next.empty())
  {
    const Expected<PullResult> warm = pull(next, scene.pull_next, &solver, scene.held);
    if (warm && warm->solve.converged)
      run.warm_seconds = warm->solve.seconds;
  }
  return run;
}

/// The median of the repeats by time (machines are noisy); everything else is deterministic.
Run medianRun(const Scene& scene, const SolverMaker& make, int repeats, int max_iterations, double max_seconds)
{
  std::vector<Run> samples;
  for (int r = 0; r < repeats; ++r)
    samples.push_back(runStep(scene, make, max_iterations, max_seconds));
  std::vector<double> warm;
  for (const Run& s : samples)
    warm.push_back(s.warm_seconds);
  std::sort(samples.begin(), samples.end(), [](const Run& a, const Run& b) { return a.seconds < b.seconds; });
  std::sort(warm.begin(), warm.end());
  Run median = samples[samples.size() / 2];
  median.warm_seconds = warm[warm.size() / 2];
  return median;
}

/// The seed's scheme with d lowered to 95 % of its stability limit on this model.
SeedSpringOptions stableSeed(const Paper& paper)
{
  SeedSpringOptions options;
  options.d = 0.95 * 2.0 / springStiffnessMax(paper, {}, 500);
  return options;
}

void benchFoldSteps(const std::string& dir, int repeats, const std::string& only)
{
  std::ofstream csv(dir + "/solvers.csv");
  csv << "scene,vertices,faces,solver,converged,diverged,iterations,seconds,warm_seconds,max_strain,mean_strain,"
         "planarity,"
         "fold_angle_error,seed_reference,iteration_ratio_vs_seed,speedup_vs_seed,warm_speedup_vs_seed,note\n";
  std::vector<Scene> scenes;
  scenes.push_back(miuraScene(12, 10));
  scenes.push_back(triangulatedMiuraScene(12, 10));
  scenes.push_back(creaseScene("single_crease", 0.5, 0.55, 0.6));
  scenes.push_back(degree4Scene(1, 0.5));
  scenes.push_back(degree4Scene(2, 0.3));
  scenes.push_back(craneScene());
  scenes.push_back(creaseScene("flat_fold_180", 170 * M_PI / 180, M_PI, NAN));
  for (const Scene& scene : scenes)
  {
    if (scene.name.find(only) == std::string::npos)
      continue;
    std::cout << scene.name << ": " << scene.paper.vertices.size() << " vertices, " << scene.paper.faces.size()
              << " faces, spring stiffness max " << springStiffnessMax(scene.paper, {}, 500) << "\n";
    std::vector<std::pair<std::string, Run>> runs;
    const int seed_repeats = scene.repeat_seed ? repeats : 1;
    runs.emplace_back("seed_spring", medianRun(
                                         scene, [] { return makeSolver("seed_spring"); }, seed_repeats,
                                         scene.seed_iterations, scene.seed_seconds));
    const SeedSpringOptions stable = stableSeed(scene.paper);
    runs.emplace_back("seed_spring_d=" + number(stable.d),
                      medianRun(
                          scene, [&] { return std::make_unique<SeedSpringSolver>(stable); }, seed_repeats,
                          scene.seed_iterations, scene.seed_seconds));
    for (const std::string& name : solverNames())
      if (name != "seed_spring")
        runs.emplace_back(
            name, medianRun(
                      scene, [&] { return makeSolver(name); }, repeats, scene.max_iterations, scene.max_seconds));
    // Ratios against the seed scheme at its own constants where it converges, else against
    // the same scheme at the largest stable d.
    const auto& reference = runs[0].second.converged ? runs[0] : runs[1];
    for (const auto& [name, run] : runs)
    {
      const bool comparable = reference.second.converged && run.converged;
      csv << scene.name << ',' << scene.paper.vertices.size() << ',' << scene.paper.faces.size() << ',' << name << ','
          << run.converged << ',' << run.diverged << ',' << run.iterations << ',' << run.seconds << ','
          << run.warm_seconds << ',' << run.metrics.strain.max << ',' << run.metrics.strain.mean << ','
          << run.metrics.planarity << ',' << run.angle_error << ',' << reference.first << ','
          << (comparable ? number(static_cast<double>(reference.second.iterations) / std::max(1, run.iterations)) : "")
          << ',' << (comparable ? number(reference.second.seconds / run.seconds) : "") << ','
          << (comparable && std::isfinite(run.warm_seconds) ? number(reference.second.seconds / run.warm_seconds) : "")
          << ",\"" << run.message << "\"\n";
      std::cout << "  " << std::setw(22) << name << (run.converged ? "  converged" : "  NOT converged")
                << "  iterations " << std::setw(8) << run.iterations << "  " << std::setw(9)
                << number(run.seconds * 1e3) << " ms (warm " << number(run.warm_seconds * 1e3) << " ms)  strain "
                << number(run.metrics.strain.max) << "  angle error " << number(run.angle_error)
                << (comparable ?
                        "  speed-up vs " + reference.first + " " + number(reference.second.seconds / run.seconds) :
                        "")
                << "\n";
      if (!run.message.empty())
        std::cout << "      " << run.message << "\n";
    }
  }
}

/// How close the seed's scheme gets within a budget (at the largest stable d).
void benchSeedAccuracy(const std::string& dir)
{
  std::ofstream csv(dir + "/seed_accuracy.csv");
  csv << "scene,d,iterations,max_strain,planarity,diverged\n";
  for (const Scene& scene : { miuraScene(12, 10), triangulatedMiuraScene(12, 10) })
    for (double d : { 0.2, stableSeed(scene.paper).d })
      for (int budget : { 100, 1000, 10000, 100000, 1000000 })
      {
        SeedSpringOptions options;
        options.d = d;
        SeedSpringSolver solver(options);
        solver.setLimits({ 0.0, budget, 0.0 });
        // rotate() refuses a shape short of the tolerance: let the scheme run its whole budget.
        std::vector<char> fixed;
        Paper turned = turnedAndHeld(scene, fixed);
        const SolveReport report = solver.solve(turned, fixed);
        const ShapeMetrics m = measureShape(turned);
        csv << scene.name << ',' << d << ',' << report.iterations << ',' << m.strain.max << ',' << m.planarity << ','
            << report.diverged << '\n';
        if (report.diverged)
          break;
      }
}

/// Where the seed's scheme diverges: one regular n-gon face, nudged in its plane.
void benchSeedStability(const std::string& dir)
{
  std::ofstream csv(dir + "/seed_stability.csv");
  csv << "face_vertices,stiffness_max,stability_limit,converged,diverged,iterations\n";
  for (int n = 3; n <= 16; ++n)
  {
    std::vector<Vec2> vertices;
    std::vector<int> cycle;
    for (int k = 0; k < n; ++k)
    {
      vertices.emplace_back(std::cos(2 * M_PI * k / n), std::sin(2 * M_PI * k / n));
      cycle.push_back(k);
    }
    Paper paper = *patternPaper(vertices, { cycle });
    for (size_t v = 0; v < paper.vertices.size(); ++v)
      paper.vertices[v].folded += 1e-3 * Vec3(std::sin(3.1 * v + 0.3), std::cos(1.7 * v + 0.1), 0.0);
    SeedSpringSolver solver;
    solver.setLimits({ kTolerance, 100000, 0.0 });
    const SolveReport report = solver.solve(paper, {});
    csv << n << ',' << springStiffnessMax(paper, {}, 2000) << ',' << seedStabilityLimit(solver.options()) << ','
        << report.converged << ',' << report.diverged << ',' << report.iterations << '\n';
  }
}
}  // namespace

int main(int argc, char** argv)
{
  const std::string dir = argc > 1 ? argv[1] : "docs/bench";
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 11;
  const std::string only = argc > 3 ? argv[3] : "";
  benchFoldSteps(dir, repeats, only);
  if (!only.empty())
    return 0;
  benchSeedAccuracy(dir);
  benchSeedStability(dir);
  std::cout << "wrote " << dir << "/solvers.csv, seed_accuracy.csv, seed_stability.csv\n";
  return 0;
}
