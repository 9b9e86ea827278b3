// The reference scripts of the traditional models folded by mouse (test/data/<model>_reference.json:
// creases, turns and flat folds with notes, written before the mouse folded them): the sequence,
// and the states it folds through, for the unit tests that check folds by one drag and the
// walkthroughs of docs/INTERACTION.md against them.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "virtual_origami/core/fold_sequence.h"
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

/// The paper after every step of the script (index 0: the flat sheet).
inline Expected<std::vector<Paper>> modelStates(const FoldSequence& sequence)
{
  Session session;
  return foldSequence(sequence, session, makeSolver(sequence.solver));
}

}  // namespace virtual_origami::core::test
