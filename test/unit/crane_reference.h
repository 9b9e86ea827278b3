// The crane of test/data/crane_reference.json (the script written before the mouse could fold
// it): its sequence, and the states it folds through (flat, up to eight layers), for the unit
// tests that check geometry on a traditional model.
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
inline Expected<FoldSequence> craneReference()
{
  std::ifstream file(std::string(VO_SOURCE_DIR) + "/test/data/crane_reference.json");
  std::stringstream text;
  text << file.rdbuf();
  return parseFoldSequence(text.str());
}

/// The paper after every step (index 8: the square base, 13: the bird base, 19: the crane
/// before its wings).
inline Expected<std::vector<Paper>> craneStates()
{
  const Expected<FoldSequence> sequence = craneReference();
  if (!sequence)
    return Expected<std::vector<Paper>>::failure(sequence.message());
  Session session;
  return foldSequence(*sequence, session, makeSolver(sequence->solver));
}

}  // namespace virtual_origami::core::test
