// Headless demo: folds a square through the core's operations and writes what it made.
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/geometry.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/svg.h"
#include "virtual_origami/core/validity.h"

using namespace virtual_origami::core;

namespace
{
struct Step
{
  const char* what;
  Vec3 start, end;  // the crease line
  Vec3 click;       // on the face to turn
  double angle;     // radians, positive valley
};

/// Turns the face under the click about the crease just made by the step's angle.
Status foldStep(Session& session, const Step& step, const CreaseResult& creased)
{
  const Paper& paper = session.paper();
  RotateRequest rotate;
  rotate.click = step.click;
  rotate.angle = step.angle;
  rotate.face = faceAt(paper, step.click, 1e-6);
  for (int e : creased.new_edges)
    if (paper.edges[e].faces[0] == rotate.face || paper.edges[e].faces[1] == rotate.face)
      rotate.axis_edge = e;
  const auto result = session.rotate(rotate);
  return result ? success() : failure(result.message());
}
}  // namespace

int main(int argc, char** argv)
{
  std::string out = "output";
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--out") == 0)
      out = argv[i + 1];
  std::filesystem::create_directories(out);

  // A square folded into a triangle, the triangle in half, then the last fold opened to 90°.
  const std::vector<Step> steps = {
    { "fold the square along its diagonal", { -0.1, -0.1, 0 }, { 1.1, 1.1, 0 }, { 0.2, 0.8, 0 }, M_PI },
    { "fold the triangle in half", { 1.1, -0.1, 0 }, { 0.4, 0.6, 0 }, { 0.3, 0.1, 0 }, M_PI },
  };
  Session session;
  std::vector<Paper> frames{ session.paper() };
  for (const Step& step : steps)
  {
    CreaseRequest crease;
    crease.start = step.start;
    crease.end = step.end;
    const auto creased = session.crease(crease);
    if (!creased)
    {
      std::fprintf(stderr, "crease failed (%s): %s\n", step.what, creased.message().c_str());
      return 1;
    }
    frames.push_back(session.paper());
    const Status folded = foldStep(session, step, *creased);
    if (!folded)
    {
      std::fprintf(stderr, "fold failed (%s): %s\n", step.what, folded.message().c_str());
      return 1;
    }
    frames.push_back(session.paper());
    std::printf("%-36s faces %zu, revision %llu\n", step.what, session.paper().faces.size(),
                static_cast<unsigned long long>(session.revision()));
  }
  // Open the last fold half way, so the result stands in 3D.
  RotateRequest open = session.log().back().rotate;
  open.angle = -M_PI / 2;
  if (!session.rotate(open))
    return 1;
  frames.push_back(session.paper());

  const ValidityReport report = checkValidity(session.paper());
  if (!report.ok())
  {
    std::fprintf(stderr, "the folded model is invalid:\n%s", report.summary().c_str());
    return 1;
  }
  const std::string fold_path = out + "/demo.fold";
  const std::string steps_path = out + "/demo_steps.fold";
  const std::string svg_path = out + "/demo.svg";
  for (const auto& [path, text] : { std::pair{ fold_path, formatFold(session.paper(), "virtual_origami demo") },
                                    std::pair{ steps_path, formatFoldSequence(frames, "virtual_origami demo steps") },
                                    std::pair{ svg_path, paperSvg(session.paper(), "demo") } })
  {
    const Status written = writeTextFile(path, text);
    if (!written)
    {
      std::fprintf(stderr, "%s\n", written.message().c_str());
      return 1;
    }
  }
  const auto reloaded = loadPaper(fold_path);
  std::printf("wrote %s (%zu faces, loads back: %s)\n", fold_path.c_str(), session.paper().faces.size(),
              reloaded ? "yes" : reloaded.message().c_str());
  std::printf("wrote %s (%zu frames, one per step)\n", steps_path.c_str(), frames.size());
  std::printf("wrote %s (crease pattern and folded form)\n", svg_path.c_str());
  return reloaded ? 0 : 1;
}
