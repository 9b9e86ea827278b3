// The reference scripts of the traditional models folded by mouse (test/data/<model>_reference.json:
// creases, turns and flat folds with notes, written before the mouse folded them): the sequence,
// and the states it folds through, for the unit tests that check folds by one drag and the
// walkthroughs of docs/INTERACTION.md against them.
#pragma once

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/core/geometry.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/solvers/solver_factory.h"

namespace virtual_origami::core::test
{
/// `file` in test/data (e.g. "frog_base_reference.json").
inline Expected<FoldSequence> modelReference(const std::string& file)
{
  std::ifstream in(std::string(VO_SOURCE_DIR) + "/test/data/" + file);
  if (!in)
    return Expected<FoldSequence>::failure("cannot read test/data/" + file);
  std::stringstream text;
  text << in.rdbuf();
  return parseFoldSequence(text.str());
}

/// `file` in sequences (e.g. "frog_base.json"): what the mouse issues.
inline Expected<FoldSequence> shippedSequence(const std::string& file)
{
  std::ifstream in(std::string(VO_SOURCE_DIR) + "/sequences/" + file);
  if (!in)
    return Expected<FoldSequence>::failure("cannot read sequences/" + file);
  std::stringstream text;
  text << in.rdbuf();
  return parseFoldSequence(text.str());
}

/// Largest distance between the vertices of `a` and `b` (matched by crease-pattern position)
/// after the rigid motion that fits `a` onto `b` best; infinity when their vertices differ.
inline double rigidFitDistance(const Paper& a, const Paper& b)
{
  if (a.vertices.size() != b.vertices.size())
    return INFINITY;
  Positions pa(3, static_cast<Eigen::Index>(a.vertices.size())), pb(3, static_cast<Eigen::Index>(a.vertices.size()));
  for (size_t i = 0; i < a.vertices.size(); ++i)
  {
    const int j = b.vertexAt(a.vertices[i].crease_pattern, 1e-9);
    if (j < 0)
      return INFINITY;
    pa.col(static_cast<Eigen::Index>(i)) = a.vertices[i].folded;
    pb.col(static_cast<Eigen::Index>(i)) = b.vertices[j].folded;
  }
  return shapeDistance(pa, pb).largest;
}

/// The paper after every step of the script (index 0: the flat sheet).
inline Expected<std::vector<Paper>> modelStates(const FoldSequence& sequence)
{
  Session session;
  return foldSequence(sequence, session, makeSolver(sequence.solver));
}

}  // namespace virtual_origami::core::test
