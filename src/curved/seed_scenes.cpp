#include "virtual_origami/curved/seed_scenes.h"

#include <algorithm>
#include <cmath>

#include "virtual_origami/core/crease.h"
#include "virtual_origami/core/geometry.h"
#include "virtual_origami/core/rotate.h"
#include "virtual_origami/curved/paper_material.h"

namespace virtual_origami::core
{
Vec3 SeedScene::pullAt(double s) const
{
  return rotateAbout(paper.vertices[pulled].folded, axis_point, axis, s * M_PI) + s * lift * Vec3::UnitZ();
}

Expected<SeedScene> seedScene(int number, double size, double gap)
{
  using Failure = Expected<SeedScene>;
  if (number < 1 || number > 3)
    return Failure::failure("seed 002 has scenes 1, 2 and 3, not " + std::to_string(number));
  SeedScene scene;
  scene.paper = Paper::square(size);
  scene.lift = gap * size;
  const int a = 0, b = 1, c = 2, d = 3;  // Paper::square's corners, counter-clockwise from the origin
  const auto corner = [&](int v) { return scene.paper.vertices[v].folded; };
  if (number == 2)
  {
    CreaseRequest request;  // the diagonal bd
    request.start = corner(b);
    request.end = corner(d);
    const Expected<CreaseResult> creased = crease(scene.paper, request);
    if (!creased.ok())
      return Failure::failure("scene 2: " + creased.message());
  }
  if (number == 3)
  {
    CreaseRequest request;  // de, e the midpoint of ab
    request.start = corner(d);
    request.end = 0.5 * (corner(a) + corner(b));
    const Expected<CreaseResult> creased = crease(scene.paper, request);
    if (!creased.ok() || creased->new_edges.size() != 1)
      return Failure::failure("scene 3: " + (creased.ok() ? std::string("de is not one crease") : creased.message()));
    RotateRequest fold;  // the triangle ade over onto the front
    fold.face = faceAt(scene.paper, Vec3(0.1 * size, 0.3 * size, 0.0), 1e-9 * size);
    fold.axis_edge = creased->new_edges[0];
    fold.angle = M_PI;
    const Expected<RotateResult> folded = rotate(scene.paper, fold);
    if (!folded.ok())
      return Failure::failure("scene 3: " + folded.message());
  }
  scene.name = "seed002_scene" + std::to_string(number);
  scene.pulled = number == 3 ? b : a;
  scene.fixed = c;
  const Vec3 p = corner(scene.pulled), q = corner(scene.fixed);
  scene.axis_point = 0.5 * (p + q);
  // In the sheet's plane, perpendicular to pulled→fixed, oriented so a positive turn lifts
  // the pulled corner off the front (+z).
  scene.axis = Vec3::UnitZ().cross(q - p).normalized();
  return scene;
}

bool SeedSceneRun::passed() const
{
  for (const SeedSceneStep& step : steps)
    if (!step.report.converged || step.report.diverged || step.metrics.penetrations > 0)
      return false;
  return !steps.empty();
}

Expected<SeedSceneRun> runSeedScene(const SeedScene& scene, const SeedSceneOptions& options)
{
  Expected<CurvedMesh> mesh = bubbleMesh(scene.paper, options.mesh);
  if (!mesh.ok())
    return Expected<SeedSceneRun>::failure(scene.name + ": " + mesh.message());
  return runSeedSceneOn(scene, std::move(*mesh), options);
}

SeedSceneRun runSeedSceneOn(const SeedScene& scene, CurvedMesh mesh, const SeedSceneOptions& options)
{
  SeedSceneRun run;
  run.mesh = std::move(mesh);
  run.positions = placeNodes(run.mesh, scene.paper);
  CurvedSolver solver(run.mesh, scene.paper, options.material, options.contact, options.solve);
  const int fixed = run.mesh.vertex_nodes[scene.fixed], pulled = run.mesh.vertex_nodes[scene.pulled];
  const Vec3 hold = run.positions.col(fixed);
  for (int k = 1; k <= options.steps; ++k)
  {
    SeedSceneStep step;
    step.fraction = options.until * k / options.steps;
    step.report = solver.solve(run.positions, { { fixed, hold }, { pulled, scene.pullAt(step.fraction) } });
    step.metrics = measureCurved(run.mesh, scene.paper, run.positions);
    run.steps.push_back(step);
    if (step.report.diverged)
      break;
  }
  return run;
}

SeedSceneOptions refinementPullOptions(double bend, double pull)
{
  SeedSceneOptions options;
  options.until = pull;
  options.steps = std::max(1, static_cast<int>(std::lround(pull / 0.05)));
  options.material.bend = bend;
  options.material.plate_bending = true;
  options.material.poisson_ratio = 0.3;
  options.material.plate_smoothing = kPaperPlateSmoothing;
  options.solve.max_iterations = 2000;
  options.solve.tolerance = 1e-11;
  options.solve.check_stability = true;
  return options;
}

Positions sheetOnGrid(const CurvedMesh& mesh, const Positions& positions, double side, int per_side)
{
  CurvedMesh points;
  const double inset = 1e-3 * side, step = (side - 2 * inset) / std::max(1, per_side - 1);
  for (int i = 0; i < per_side; ++i)
    for (int j = 0; j < per_side; ++j)
    {
      MeshNode node;
      node.crease_pattern = Vec2(inset + step * i, inset + step * j);
      points.nodes.push_back(node);
    }
  return transferNodes(mesh, positions, points, Positions::Zero(3, static_cast<Eigen::Index>(points.nodes.size())));
}

}  // namespace virtual_origami::core
