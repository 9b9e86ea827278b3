#include "virtual_origami/curved/model_choice.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/contact.h"

namespace virtual_origami::core
{
namespace
{
/// Largest |l/l0 − 1| over the vertex pairs of one face.
double faceStrain(const Paper& paper, int face)
{
  const std::vector<int>& vs = paper.faces[face].vertices;
  double worst = 0.0;
  for (size_t a = 0; a < vs.size(); ++a)
    for (size_t b = a + 1; b < vs.size(); ++b)
    {
      const double rest = (paper.vertices[vs[a]].crease_pattern - paper.vertices[vs[b]].crease_pattern).norm();
      const double now = (paper.vertices[vs[a]].folded - paper.vertices[vs[b]].folded).norm();
      const double strain = std::abs(now / rest - 1.0);
      worst = std::isfinite(strain) ? std::max(worst, strain) : INFINITY;
    }
  return worst;
}
}  // namespace

Expected<ModelChoice> chooseModel(const Paper& paper, const std::vector<VertexPin>& pins, ShapeSolver& rigid,
                                  const ModelChoiceOptions& options)
{
  using Failure = Expected<ModelChoice>;
  for (const VertexPin& pin : pins)
    if (pin.first < 0 || pin.first >= static_cast<int>(paper.vertices.size()))
      return Failure::failure("pin names vertex " + std::to_string(pin.first) + ", which does not exist");
  ModelChoice choice;
  choice.spacing = options.spacing > 0 ? options.spacing : paper.scale() / 8;
  const size_t faces = paper.faces.size();
  if (options.mode == "rigid")
  {
    choice.reason = "rigid faces, as asked";
    return choice;
  }
  if (options.mode == "curved")
  {
    choice.model = PaperModel::Curved;
    choice.curved_faces.assign(faces, 1);
    choice.reason = "curved paper on every face, as asked";
    return choice;
  }
  if (options.mode != "auto")
    return Failure::failure("model mode must be auto, rigid or curved, not '" + options.mode + "'");

  Paper trial = paper;
  std::vector<char> fixed(paper.vertices.size(), 0);
  for (const VertexPin& pin : pins)
  {
    trial.vertices[pin.first].folded = pin.second;
    fixed[pin.first] = 1;
  }
  const SolveReport report = rigid.solve(trial, fixed);
  std::vector<double> strain(faces, 0.0);
  for (size_t f = 0; f < faces; ++f)
    strain[f] = report.diverged ? INFINITY : faceStrain(trial, static_cast<int>(f));
  choice.rigid_strain = *std::max_element(strain.begin(), strain.end());
  if (choice.rigid_strain <= options.rigid_tolerance)
  {
    std::ostringstream why;
    why << "the pins are reached with flat faces (" << rigid.name() << ", strain " << choice.rigid_strain << ")";
    choice.reason = why.str();
    return choice;
  }

  choice.model = PaperModel::Curved;
  choice.curved_faces.assign(faces, 0);
  for (size_t f = 0; f < faces; ++f)
    choice.curved_faces[f] = strain[f] > options.rigid_tolerance ? 1 : 0;
  // Layers stacked on a face that bends bend with it: spread along stacking until it stops.
  for (bool grew = true; grew;)
  {
    grew = false;
    for (size_t f = 0; f < faces; ++f)
      for (size_t g = 0; g < faces && !choice.curved_faces[f]; ++g)
        if (choice.curved_faces[g] && layerSide(paper, static_cast<int>(f), static_cast<int>(g)) != 0)
        {
          choice.curved_faces[f] = 1;
          grew = true;
        }
  }
  const int bent = static_cast<int>(std::count(choice.curved_faces.begin(), choice.curved_faces.end(), 1));
  std::ostringstream why;
  why << "flat faces cannot reach the pins (" << rigid.name() << " left strain " << choice.rigid_strain << "): "
      << bent << " of " << faces << " faces bend";
  choice.reason = why.str();
  return choice;
}

Expected<SpacingChoice> refineSpacing(const Paper& paper, const std::vector<char>& curved_faces, double start,
                                      double finest, double accuracy,
                                      const std::function<Expected<Positions>(const CurvedMesh&)>& solve)
{
  using Failure = Expected<SpacingChoice>;
  SpacingChoice choice;
  CurvedMesh previous_mesh;
  Positions previous;
  BubbleMeshOptions options;
  options.curved_faces = curved_faces;
  for (double spacing = start; spacing >= finest * (1 - 1e-12); spacing /= 2)
  {
    options.spacing = spacing;
    Expected<CurvedMesh> mesh = bubbleMesh(paper, options);
    if (!mesh.ok())
      return Failure::failure(mesh.message());
    Expected<Positions> x = solve(*mesh);
    if (!x.ok())
      return Failure::failure("at spacing " + std::to_string(spacing) + ": " + x.message());
    SpacingLevel level;
    level.spacing = spacing;
    level.nodes = static_cast<int>(mesh->nodes.size());
    level.change = std::numeric_limits<double>::infinity();
    if (!choice.levels.empty())
    {
      const Positions coarse = transferNodes(previous_mesh, previous, *mesh, *x);
      level.change = (coarse - *x).colwise().norm().maxCoeff();
    }
    choice.levels.push_back(level);
    if (level.change <= accuracy)
    {
      choice.spacing = previous_mesh.spacing;
      choice.met = true;
      return choice;
    }
    previous_mesh = std::move(*mesh);
    previous = std::move(*x);
  }
  choice.spacing = choice.levels.empty() ? start : choice.levels.back().spacing;
  return choice;
}

}  // namespace virtual_origami::core
