// Origami Simulator's example patterns (bench/patterns/origami-simulator, MIT), loaded in tests as
// paper_model's `load` loads them.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "virtual_origami/core/model_file.h"

namespace virtual_origami::core::test
{
/// The library's pattern `name` (a path under its folder); an empty paper, with a test failure,
/// when it does not load.
inline Paper libraryPattern(const std::string& name)
{
  const std::string path = std::string(VO_SOURCE_DIR) + "/bench/patterns/origami-simulator/" + name;
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  const Expected<Paper> paper = parseModel(text.str(), *modelFormat(path), 1.0);
  EXPECT_TRUE(paper) << name << ": " << paper.message();
  return paper ? *paper : Paper{};
}

}  // namespace virtual_origami::core::test
