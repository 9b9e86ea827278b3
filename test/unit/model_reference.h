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

#include "rigid_fit.h"
#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/solvers/solver_factory.h"

namespace virtual_origami::core::test
{
/// A fold sequence in `folder` of the source tree.
inline Expected<FoldSequence> sequenceIn(const std::string& folder, const std::string& file)
{
  std::ifstream in(std::string(VO_SOURCE_DIR) + "/" + folder + "/" + file);
  if (!in)
    return Expected<FoldSequence>::failure("cannot read " + folder + "/" + file);
  std::stringstream text;
  text << in.rdbuf();
  return parseFoldSequence(text.str());
}

/// `file` in test/data (e.g. "frog_base_reference.json").
inline Expected<FoldSequence> modelReference(const std::string& file)
{
  return sequenceIn("test/data", file);
}

/// `file` in sequences (e.g. "frog_base.json"): what the mouse issues.
inline Expected<FoldSequence> shippedSequence(const std::string& file)
{
  return sequenceIn("sequences", file);
}

/// The paper after every step of the script (index 0: the flat sheet).
inline Expected<std::vector<Paper>> modelStates(const FoldSequence& sequence)
{
  Session session;
  return foldSequence(sequence, session, makeSolver(sequence.solver));
}

}  // namespace virtual_origami::core::test
