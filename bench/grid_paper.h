// A flat sheet of many vertices for the benchmarks that measure cost against model size.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <vector>

#include "virtual_origami/core/reference_patterns.h"
#include "virtual_origami/core/validity.h"

namespace virtual_origami::bench
{
/// A flat unit sheet of w × w square faces, every inner edge a flat ('F') crease; exits with a
/// message naming `program` if it is not a valid model.
inline core::Paper gridPaper(int w, const char* program)
{
  std::vector<core::Vec2> vertices;
  std::vector<std::vector<int>> faces;
  for (int j = 0; j <= w; ++j)
    for (int i = 0; i <= w; ++i)
      vertices.emplace_back(double(i) / w, double(j) / w);
  for (int j = 0; j < w; ++j)
    for (int i = 0; i < w; ++i)
    {
      const int v = j * (w + 1) + i;
      faces.push_back({ v, v + 1, v + w + 2, v + w + 1 });
    }
  core::Expected<core::Paper> paper = core::patternPaper(vertices, faces);
  if (!paper)
  {
    std::fprintf(stderr, "%s: grid %d: %s\n", program, w, paper.message().c_str());
    std::exit(1);
  }
  for (core::Edge& e : paper->edges)
    if (e.isCrease())
      e.assignment = core::Assignment::Flat;
  const core::ValidityReport report = core::checkValidity(*paper);
  if (!report.ok())
  {
    std::fprintf(stderr, "%s: grid %d is not valid: %s\n", program, w, report.summary().c_str());
    std::exit(1);
  }
  return *paper;
}

}  // namespace virtual_origami::bench
