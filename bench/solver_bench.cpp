// Rigid-face solvers on one fold step of crane-scale models (SPEC §6, issue 3): iterations
// and time to max strain < 1e-9 per solver, as ratios to the seed's spring scheme in the same
// run; the seed scheme's reachable accuracy against its iteration budget; and its stability
// against face size. Writes CSV; timings belong here, never in the unit tests.
//
//   solver_bench [out.csv] [repeats]
#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "virtual_origami/core/metrics.h"
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
  std::function<double(const Paper&)> angle_error;  // against the closed form; NaN if none
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

/// The scene's step as rotate() sets it up for a solver: the face turned, it and the face
/// across the axis held. Used where rotate() refuses a result, to report where a solver got.
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

/// One fold step from the scene's state, then (warm) the next step of the same drag.
Run runStep(const Scene& scene, const SolverMaker& make, int max_iterations, double max_seconds)
{
  std::unique_ptr<ShapeSolver> solver = make();
  solver->setLimits({ kTolerance, max_iterations, max_seconds });
  Paper paper = scene.paper;
  Run run;
  const Expected<RotateResult> result = rotate(paper, scene.step, solver.get());
  if (!result)
  {
    // Refused (the model is unchanged): solve the same setup by hand to report the solver.
    run.message = result.message();
    std::vector<char> fixed;
    Paper attempt = turnedAndHeld(scene, fixed);
    std::unique_ptr<ShapeSolver> again = make();
    again->setLimits(solver->limits());
    const SolveReport report = again->solve(attempt, fixed);
    run.diverged = report.diverged;
    run.iterations = report.iterations;
    run.seconds = report.seconds;
    run.metrics = measureShape(attempt);
    return run;
  }
  run.converged = result->solve.converged;
  run.iterations = result->solve.iterations;
  run.seconds = result->solve.seconds;
  run.metrics = measureShape(paper);
  run.angle_error = scene.angle_error(paper);
  Paper next = paper;
  const Expected<RotateResult> warm = rotate(next, scene.step, solver.get());
  if (warm && warm->solve.converged)
    run.warm_seconds = warm->solve.seconds;
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

std::string number(double x)
{
  std::ostringstream out;
  out << std::setprecision(4) << x;
  return out.str();
}

/// The seed's scheme with d lowered to 95 % of its stability limit on this model.
SeedSpringOptions stableSeed(const Paper& paper)
{
  SeedSpringOptions options;
  options.d = 0.95 * 2.0 / springStiffnessMax(paper, {}, 500);
  return options;
}

void benchFoldSteps(const std::string& dir, int repeats)
{
  std::ofstream csv(dir + "/solvers.csv");
  csv << "scene,vertices,faces,solver,converged,diverged,iterations,seconds,warm_seconds,max_strain,mean_strain,"
         "planarity,"
         "fold_angle_error,seed_reference,iteration_ratio_vs_seed,speedup_vs_seed,warm_speedup_vs_seed,note\n";
  for (const Scene& scene : { miuraScene(12, 10), triangulatedMiuraScene(12, 10) })
  {
    std::cout << scene.name << ": " << scene.paper.vertices.size() << " vertices, " << scene.paper.faces.size()
              << " faces, spring stiffness max " << springStiffnessMax(scene.paper, {}, 500) << "\n";
    std::vector<std::pair<std::string, Run>> runs;
    runs.emplace_back("seed_spring", medianRun(
                                         scene, [] { return makeSolver("seed_spring"); }, 1, 2000000, 120.0));
    const SeedSpringOptions stable = stableSeed(scene.paper);
    runs.emplace_back("seed_spring_d=" + number(stable.d),
                      medianRun(
                          scene, [&] { return std::make_unique<SeedSpringSolver>(stable); }, 1, 2000000, 120.0));
    for (const std::string& name : solverNames())
      if (name != "seed_spring")
        runs.emplace_back(name, medianRun(
                                    scene, [&] { return makeSolver(name); }, repeats, 100000, 30.0));
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
  benchFoldSteps(dir, repeats);
  benchSeedAccuracy(dir);
  benchSeedStability(dir);
  std::cout << "wrote " << dir << "/solvers.csv, seed_accuracy.csv, seed_stability.csv\n";
  return 0;
}
