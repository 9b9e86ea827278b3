// A face turn as a drag makes it, in process (docs/SOLVERS.md "Turns at scale"): the corner face
// of a generated Miura-ori previewed at 2°, 4°, … and committed at the last angle, through
// Session::rotate with the newton solver (spring_solver's limits) and the quasi_newton driver as
// paper_model sets them. CPU and wall time per call, the solver's iterations and strain.
//
//   turn_bench [vertices ...]   (default 1681 5000 10000; a CSV row per call on stdout)
//   TURN_DEGREES (10), TURN_STEP (2), TURN_TOLERANCE (1e-10), TURN_COMMIT_ONLY: see below;
//   TURN_PREVIEW_TOLERANCE: the previews' looser balance (paper_model's turn_preview_tolerance).
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "bench_common.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami::core;
using virtual_origami::bench::cornerAxis;
using virtual_origami::bench::cpuNow;
using virtual_origami::bench::now;

namespace
{
void turnDrag(long vertices, double last_degrees, double step_degrees)
{
  const Expected<Tessellation> pattern = tessellationWithVertices(TessellationKind::Miura, vertices);
  if (!pattern)
  {
    std::fprintf(stderr, "%s\n", pattern.message().c_str());
    return;
  }
  Session session(pattern->paper);
  std::shared_ptr<ShapeSolver> solver = makeSolver("newton");
  SolveLimits limits;  // spring_solver's defaults (cfg/SpringSolver.cfg)
  limits.tolerance = std::getenv("TURN_TOLERANCE") ? std::atof(std::getenv("TURN_TOLERANCE")) : 1e-10;
  limits.max_iterations = 1000;
  solver->setLimits(limits);
  session.setSolver(solver);
  std::shared_ptr<CreaseDriver> driver = makeCreaseDriver("quasi_newton");
  std::shared_ptr<CreaseDriver> preview_driver = driver->clone();
  session.setCreaseDrivers(driver, preview_driver);
  if (std::getenv("TURN_PREVIEW_TOLERANCE"))
    session.setTurnPreviewTolerance(std::atof(std::getenv("TURN_PREVIEW_TOLERANCE")));

  RotateRequest request;
  request.face = 0;
  request.axis_edge = cornerAxis(session.paper());
  const long n = static_cast<long>(session.paper().vertices.size());
  // TURN_COMMIT_ONLY: the commit alone, from the flat sheet (a release with no preview on show).
  const double first = std::getenv("TURN_COMMIT_ONLY") ? last_degrees : step_degrees;
  for (double degrees = first; degrees <= last_degrees + 1e-9; degrees += step_degrees)
  {
    const bool commit = degrees + step_degrees > last_degrees + 1e-9;
    for (int pass = 0; pass < (commit ? 2 : 1); ++pass)
    {
      const bool committing = commit && pass == 1;
      request.angle = degrees * M_PI / 180;
      const double cpu = cpuNow(), wall = now();
      const Expected<RotateResult> r = session.rotate(request, committing);
      const double cpu_s = cpuNow() - cpu, wall_s = now() - wall;
      const Paper& shown = committing ? session.paper() : (session.preview() ? *session.preview() : session.paper());
      std::printf("%ld,%s,%g,%.4f,%.4f,%d,%s,%.3g,%.3g,\"%s\"\n", n, committing ? "commit" : "preview", degrees, cpu_s,
                  wall_s, r ? r->solve.iterations : -1, r ? "ok" : "refused", r ? r->solve.max_strain : -1.0,
                  r ? edgeStrain(shown).max : -1.0, r ? "" : r.message().c_str());
      std::fflush(stdout);
    }
  }
}
}  // namespace

int main(int argc, char** argv)
{
  std::vector<long> sizes;
  for (int i = 1; i < argc; ++i)
    sizes.push_back(std::atol(argv[i]));
  if (sizes.empty())
    sizes = { 1681, 5000, 10000 };
  const char* last = std::getenv("TURN_DEGREES");
  const char* step = std::getenv("TURN_STEP");
  std::printf("vertices,call,degrees,cpu_s,wall_s,iterations,result,solver_strain,edge_strain,message\n");
  for (long n : sizes)
    turnDrag(n, last ? std::atof(last) : 10.0, step ? std::atof(step) : 2.0);
  return 0;
}
