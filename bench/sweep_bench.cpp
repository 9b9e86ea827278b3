// Speed against accuracy for the rigid-face solvers (issue 8): error against wall time over
// iteration budgets, the seed scheme's stability map over Δt × stiffness, and time per step
// against vertex count beside the physical floor of the same machine, measured in the same
// run (a STREAM triad for bandwidth, one Eigen SimplicialLDLT of the spring stiffness).
// Writes CSV; bench/plot_charts.py draws the charts and the tables of docs/BENCHMARKS.md.
//
//   sweep_bench [out_dir]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <Eigen/SparseCholesky>

#include "virtual_origami/core/metrics.h"
#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/face_springs.h"
#include "virtual_origami/core/positions.h"
#include "virtual_origami/solvers/seed_spring_solver.h"
#include "virtual_origami/solvers/solver_factory.h"
#include "bench_common.h"

using namespace virtual_origami::core;
using virtual_origami::bench::now;

namespace
{
constexpr double kGamma = M_PI / 3;

int miuraId(int columns, int i, int j)
{
  return j * (columns + 1) + i;
}

/// The solver's task of solver_bench's miura_12x10 step: the corner face turned by −0.05 rad
/// about its straight crease, it and the face across held, the rest to follow.
Paper turnedMiura(int columns, int rows, std::vector<char>& fixed)
{
  Paper paper = miuraOri(columns, rows, 1.0, 1.3, kGamma);
  foldToAngles(paper, miuraFoldAngles(paper, columns, rows, kGamma, 0.5));
  const int axis_edge = paper.findEdge(miuraId(columns, 0, 1), miuraId(columns, 1, 1));
  const Edge& hinge = paper.edges[axis_edge];
  const Vec3 a = paper.vertices[hinge.vertices[0]].folded;
  const Vec3 axis = (paper.vertices[hinge.vertices[1]].folded - a).normalized();
  const double turn = hinge.faces[0] == 0 ? -0.05 : 0.05;
  fixed.assign(paper.vertices.size(), 0);
  for (int v : paper.faces[0].vertices)
  {
    fixed[v] = 1;
    paper.vertices[v].folded = a + Eigen::AngleAxisd(turn, axis) * (paper.vertices[v].folded - a);
  }
  for (int v : paper.faces[hinge.otherFace(0)].vertices)
    fixed[v] = 1;
  return paper;
}

double maxDistance(const Positions& a, const Positions& b)
{
  return (a - b).colwise().norm().maxCoeff();
}

/// Error against wall time: each solver stopped at a range of iteration budgets (tolerance 0,
/// so the budget is what stops it), error as max strain and as the largest vertex distance to
/// rigid_kinematics converged to 1e-13 (zero strain by construction: the ground truth).
void sweepErrorTime(const std::string& dir)
{
  std::vector<char> fixed;
  const Paper task = turnedMiura(12, 10, fixed);
  Paper truth = task;
  std::unique_ptr<ShapeSolver> reference = makeSolver("rigid_kinematics");
  reference->setLimits({ 1e-13, 1000, 0.0 });
  const SolveReport truth_report = reference->solve(truth, fixed);
  const Positions truth_x = foldedPositions(truth);
  std::cout << "ground truth: rigid_kinematics " << truth_report.iterations << " iterations, strain "
            << truth_report.max_strain << "\n";

  std::ofstream csv(dir + "/error_time.csv");
  csv << "scene,solver,budget,iterations,seconds,max_strain,position_error,diverged\n";
  struct Sweep
  {
    std::string solver;
    std::vector<int> budgets;
  };
  const std::vector<Sweep> sweeps = {
    { "newton", { 1, 2, 3, 4, 5, 6, 8 } },
    { "rigid_kinematics", { 1, 2, 4, 8, 12, 16, 22, 30 } },
    { "shape_matching", { 1, 3, 10, 30, 100, 300, 1000, 1500, 3000 } },
    { "seed_spring", { 10, 30, 100, 300, 1000, 3000, 10000, 30000, 100000, 300000 } },
  };
  SeedSpringOptions stable;
  stable.d = 0.95 * 2.0 / springStiffnessMax(task, {}, 500);
  for (const Sweep& sweep : sweeps)
    for (int budget : sweep.budgets)
    {
      // Median of three by time; the solve itself is deterministic.
      std::vector<double> times;
      Paper paper = task;
      SolveReport report;
      for (int r = 0; r < 3; ++r)
      {
        std::unique_ptr<ShapeSolver> solver = sweep.solver == "seed_spring" ?
                                                  std::make_unique<SeedSpringSolver>(stable) :
                                                  makeSolver(sweep.solver);
        solver->setLimits({ 0.0, budget, 0.0 });
        paper = task;
        const double start = now();
        report = solver->solve(paper, fixed);
        times.push_back(now() - start);
      }
      std::sort(times.begin(), times.end());
      const ShapeMetrics m = measureShape(paper);
      csv << "miura_12x10," << sweep.solver << ',' << budget << ',' << report.iterations << ',' << times[1] << ','
          << m.strain.max << ',' << maxDistance(foldedPositions(paper), truth_x) << ',' << report.diverged << '\n';
    }
}

/// A regular n-gon face nudged in its plane: its spring stiffness is λ = n at rest.
Paper polygonFace(int n)
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
  return paper;
}

/// Stability map: the seed's explicit scheme (d = 0.2) over Δt × stiffness λ, against its
/// bound d·λ·Δt² < 2; the implicit solvers (no step size) on the same faces.
void sweepStability(const std::string& dir)
{
  std::ofstream csv(dir + "/stability_map.csv");
  csv << "solver,dt,d,stiffness,bound,converged,diverged,iterations\n";
  for (int n = 3; n <= 24; ++n)
  {
    const Paper face = polygonFace(n);
    const double lambda = springStiffnessMax(face, {}, 2000);
    for (int k = 0; k <= 24; ++k)
    {
      SeedSpringOptions options;
      options.dt = 0.5 + 0.1 * k;  // 0.5 … 2.9
      SeedSpringSolver solver(options);
      solver.setLimits({ 1e-9, 20000, 0.0 });
      Paper paper = face;
      const SolveReport report = solver.solve(paper, {});
      csv << "seed_spring," << options.dt << ',' << options.d << ',' << lambda << ','
          << options.d * lambda * options.dt * options.dt << ',' << report.converged << ',' << report.diverged << ','
          << report.iterations << '\n';
    }
    for (const char* name : { "newton", "shape_matching" })
    {
      std::unique_ptr<ShapeSolver> solver = makeSolver(name);
      solver->setLimits({ 1e-9, 20000, 0.0 });
      Paper paper = face;
      const SolveReport report = solver->solve(paper, {});
      csv << name << ",," << "," << lambda << ",," << report.converged << ',' << report.diverged << ','
          << report.iterations << '\n';
    }
  }
}

/// The triad bandwidth (bench_common.h), recorded in the floor CSV.
double triadBandwidth(std::ofstream& csv)
{
  double check = 0;
  const double bandwidth = virtual_origami::bench::triadBandwidth(&check);
  csv << "triad_bytes_per_second," << bandwidth << ",check " << check << '\n';
  return bandwidth;
}

/// A flat w × h grid of unit squares (each its own face) nudged off its rest shape, the
/// corner face held: the sheet the scaling runs on.
Paper gridSheet(int w, int h, std::vector<char>& fixed)
{
  std::vector<Vec2> vertices;
  std::vector<std::vector<int>> faces;
  for (int j = 0; j <= h; ++j)
    for (int i = 0; i <= w; ++i)
      vertices.emplace_back(i, j);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
    {
      const int v = j * (w + 1) + i;
      faces.push_back({ v, v + 1, v + w + 2, v + w + 1 });
    }
  Paper paper = *patternPaper(vertices, faces);
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    paper.vertices[v].folded += 1e-3 * Vec3(std::sin(3.1 * v + 0.3), std::cos(1.7 * v + 0.1), std::sin(0.7 * v));
  fixed.assign(paper.vertices.size(), 0);
  for (int v : paper.faces[0].vertices)
    fixed[v] = 1;
  return paper;
}

/// The spring stiffness at rest as a sparse 3V × 3V matrix (one 3 × 3 block u uᵀ per spring),
/// plus a small shift so that it is definite: the system an implicit step factorises.
Eigen::SparseMatrix<double> springStiffness(const std::vector<Spring>& springs, const Positions& x)
{
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(springs.size() * 36 + x.cols() * 3);
  for (const Spring& s : springs)
  {
    const Vec3 u = (x.col(s.j) - x.col(s.i)).normalized();
    const Eigen::Matrix3d k = u * u.transpose();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
      {
        t.emplace_back(3 * s.i + r, 3 * s.i + c, k(r, c));
        t.emplace_back(3 * s.j + r, 3 * s.j + c, k(r, c));
        t.emplace_back(3 * s.i + r, 3 * s.j + c, -k(r, c));
        t.emplace_back(3 * s.j + r, 3 * s.i + c, -k(r, c));
      }
  }
  for (int i = 0; i < 3 * x.cols(); ++i)
    t.emplace_back(i, i, 1e-4);
  Eigen::SparseMatrix<double> k(3 * x.cols(), 3 * x.cols());
  k.setFromTriplets(t.begin(), t.end());
  return k;
}

/// Time per step against vertex count: one iteration of the seed's explicit scheme (the
/// difference of two budgets, so setup cancels) against its memory floor (compulsory bytes
/// per step / triad bandwidth), and one Newton iteration against one SimplicialLDLT of the
/// stiffness of the same sheet.
void sweepScaling(const std::string& dir)
{
  std::ofstream floor_csv(dir + "/machine_floor.csv");
  floor_csv << "quantity,value,note\n";
  const double bandwidth = triadBandwidth(floor_csv);
  std::cout << "triad bandwidth " << bandwidth / 1e9 << " GB/s\n";

  std::ofstream csv(dir + "/scaling.csv");
  csv << "vertices,springs,explicit_step_seconds,explicit_floor_seconds,explicit_bytes_per_step,"
         "newton_iteration_seconds,ldlt_seconds\n";
  for (int w : { 10, 22, 32, 45, 71, 100, 141, 224, 316 })
  {
    std::vector<char> fixed;
    const Paper sheet = gridSheet(w, w, fixed);
    const std::vector<Spring> springs = faceSprings(sheet);
    const size_t v = sheet.vertices.size();
    // At the largest stable d: at the seed's d = 0.2 a sheet whose vertices join four faces is
    // past the stability limit and the scheme stops at its divergence check.
    SeedSpringOptions stable;
    stable.d = 0.95 * 2.0 / springStiffnessMax(sheet, fixed, 200);
    auto seedTime = [&](int iterations, int& done) {
      SeedSpringSolver solver(stable);
      solver.setLimits({ 0.0, iterations, 0.0 });
      Paper paper = sheet;
      const double start = now();
      done = solver.solve(paper, fixed).iterations;
      return now() - start;
    };
    int few_done = 0, many_done = 0;
    const double few_time = seedTime(20, few_done);
    const double many_time = seedTime(60, many_done);
    const double step = (many_time - few_time) / std::max(1, many_done - few_done);
    // Compulsory traffic of one explicit step: the spring list (two indices, a rest length),
    // positions read, forces written and read back, positions read and written.
    const double bytes = 16.0 * springs.size() + 24.0 * v * 4;
    double newton = NAN;
    if (v <= 52000)
    {
      std::unique_ptr<ShapeSolver> solver = makeSolver("newton");
      solver->setLimits({ 0.0, 1, 0.0 });
      Paper paper = sheet;
      const double start = now();
      solver->solve(paper, fixed);
      newton = now() - start;
    }
    const Eigen::SparseMatrix<double> k = springStiffness(springs, foldedPositions(sheet));
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
    const double start = now();
    ldlt.compute(k);
    const double factor = now() - start;
    csv << v << ',' << springs.size() << ',' << step << ',' << bytes / bandwidth << ',' << bytes << ',' << newton
        << ',' << factor << '\n';
    std::cout << "  " << v << " vertices: explicit step " << step * 1e3 << " ms (floor " << bytes / bandwidth * 1e3
              << " ms), newton iteration " << newton * 1e3 << " ms, LDLT " << factor * 1e3 << " ms\n";
  }
}
}  // namespace

int main(int argc, char** argv)
{
  const std::string dir = argc > 1 ? argv[1] : "docs/bench";
  sweepErrorTime(dir);
  std::cout << "wrote " << dir << "/error_time.csv\n";
  sweepStability(dir);
  std::cout << "wrote " << dir << "/stability_map.csv\n";
  sweepScaling(dir);
  std::cout << "wrote " << dir << "/scaling.csv, machine_floor.csv\n";
  return 0;
}
