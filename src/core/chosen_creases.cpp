#include "virtual_origami/core/chosen_creases.h"

#include <algorithm>

namespace virtual_origami::core
{
namespace
{
/// The marked crease `edge` is, either way round, or -1.
int find(const std::vector<MarkedCrease>& marks, const Paper& paper, int edge)
{
  const Vec2& a = paper.vertices[paper.edges[edge].vertices[0]].crease_pattern;
  const Vec2& b = paper.vertices[paper.edges[edge].vertices[1]].crease_pattern;
  const double tolerance = 1e-9 * paper.scale();
  for (size_t i = 0; i < marks.size(); ++i)
    if (((marks[i].start - a).norm() < tolerance && (marks[i].end - b).norm() < tolerance) ||
        ((marks[i].start - b).norm() < tolerance && (marks[i].end - a).norm() < tolerance))
      return static_cast<int>(i);
  return -1;
}

bool isCrease(const Paper& paper, int edge)
{
  return edge >= 0 && static_cast<size_t>(edge) < paper.edges.size() && paper.edges[edge].isCrease();
}
}  // namespace

CreaseMark nextMark(CreaseMark mark)
{
  switch (mark)
  {
    case CreaseMark::None:
      return CreaseMark::Valley;
    case CreaseMark::Valley:
      return CreaseMark::Mountain;
    case CreaseMark::Mountain:
      return CreaseMark::Unfold;
    case CreaseMark::Unfold:
      return CreaseMark::None;
  }
  return CreaseMark::None;
}

CreaseMark CreaseMarks::markOf(const Paper& paper, int edge) const
{
  if (!isCrease(paper, edge))
    return CreaseMark::None;
  const int i = find(marks_, paper, edge);
  return i < 0 ? CreaseMark::None : marks_[i].mark;
}

void CreaseMarks::mark(const Paper& paper, int edge, CreaseMark mark)
{
  if (!isCrease(paper, edge))
    return;
  const int i = find(marks_, paper, edge);
  if (mark == CreaseMark::None)
  {
    if (i >= 0)
      marks_.erase(marks_.begin() + i);
    return;
  }
  if (i >= 0)
    marks_[i].mark = mark;
  else
    marks_.push_back({ paper.vertices[paper.edges[edge].vertices[0]].crease_pattern,
                       paper.vertices[paper.edges[edge].vertices[1]].crease_pattern, mark });
}

std::vector<std::pair<int, CreaseMark>> CreaseMarks::edges(const Paper& paper) const
{
  std::vector<std::pair<int, CreaseMark>> out;
  for (size_t e = 0; e < paper.edges.size(); ++e)
  {
    const CreaseMark m = markOf(paper, static_cast<int>(e));
    if (m != CreaseMark::None)
      out.emplace_back(static_cast<int>(e), m);
  }
  return out;
}

double markAngle(CreaseMark mark, double fold)
{
  return mark == CreaseMark::Valley ? fold : mark == CreaseMark::Mountain ? -fold : 0.0;
}

Vec2 creasePatternPoint(const Paper& paper, int face)
{
  Vec2 centroid = Vec2::Zero();
  for (int v : paper.faces[face].vertices)
    centroid += paper.vertices[v].crease_pattern;
  return centroid / static_cast<double>(paper.faces[face].vertices.size());
}

std::optional<FlatFoldRequest> chosenCreasesFold(const Paper& paper, const CreaseMarks& marks, int fixed_face,
                                                 double fold)
{
  if (marks.empty())
    return std::nullopt;
  FlatFoldRequest request;
  for (const MarkedCrease& m : marks.marks())
    request.creases.push_back({ m.start, m.end, markAngle(m.mark, fold) });
  if (fixed_face >= 0 && static_cast<size_t>(fixed_face) < paper.faces.size())
    request.fixed_point = creasePatternPoint(paper, fixed_face);
  else
    request.fixed_point = Vec2::Constant(-1.0 * paper.scale());  // off the sheet: flatFold says so
  return request;
}

}  // namespace virtual_origami::core
