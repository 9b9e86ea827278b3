// The traditional crane of sequences/crane.json, folded as the sequence folds it.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/solvers/solver_factory.h"

namespace virtual_origami::core
{
inline Paper foldedCrane()
{
  std::ifstream in(std::string(VO_SOURCE_DIR) + "/sequences/crane.json");
  std::stringstream text;
  text << in.rdbuf();
  const Expected<FoldSequence> sequence = parseFoldSequence(text.str());
  EXPECT_TRUE(sequence.ok()) << sequence.message();
  Session session;
  const Expected<std::vector<Paper>> states = foldSequence(*sequence, session, makeSolver(sequence->solver));
  EXPECT_TRUE(states.ok()) << states.message();
  return states->back();
}
}  // namespace virtual_origami::core
