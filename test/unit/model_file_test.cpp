#include <gtest/gtest.h>

#include <string>

#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/model_file.h"

using namespace virtual_origami::core;

namespace
{
/// A FOLD square sheet divided into n × n squares: (n + 1)² vertices.
std::string gridFold(int n)
{
  std::string coords, faces;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      coords += (coords.empty() ? "" : ",") + std::string("[") + std::to_string(double(i) / n) + "," +
                std::to_string(double(j) / n) + "]";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      const int a = j * (n + 1) + i;
      faces += (faces.empty() ? "" : ",") + std::string("[") + std::to_string(a) + "," + std::to_string(a + 1) + "," +
               std::to_string(a + n + 2) + "," + std::to_string(a + n + 1) + "]";
    }
  return R"({"file_spec":1.1,"vertices_coords":[)" + coords + R"(],"faces_vertices":[)" + faces + "]}";
}
}  // namespace

TEST(ModelFile, FormatsByName)
{
  EXPECT_EQ(modelFormat("a.fold"), ModelFormat::Fold);
  EXPECT_EQ(modelFormat("a.CP"), ModelFormat::OripaCp);
  EXPECT_EQ(modelFormat("dir/a.opx"), ModelFormat::OripaOpx);
  EXPECT_EQ(modelFormat("dir/pattern.Svg"), ModelFormat::Svg);
  EXPECT_FALSE(modelFormat("session_origami.jsonl"));
  EXPECT_FALSE(modelFormat("folding.bag"));
  EXPECT_FALSE(modelFormat("folding.bag.active"));
}

// Found by the round-3 probe: a 200,000-vertex polygon FOLD got no answer in 780 s. The sizes
// are refused before the parse, by the counts the file declares.
TEST(ModelFile, ALargeModelIsRefusedBeforeItIsParsed)
{
  const std::string grid = gridFold(10);  // 121 vertices
  EXPECT_TRUE(checkModelSize(grid, ModelFormat::Fold, { 121, 4 }));
  const Status refused = checkModelSize(grid, ModelFormat::Fold, { 120, 4 });
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.message().find("max_load_vertices"), std::string::npos) << refused.message();
  EXPECT_TRUE(checkModelSize(grid, ModelFormat::Fold, { 0, 0 }));  // no limits
  const Status big_face = checkModelSize(grid, ModelFormat::Fold, { 121, 3 });
  ASSERT_FALSE(big_face);
  EXPECT_NE(big_face.message().find("max_face_vertices"), std::string::npos) << big_face.message();
  const Expected<Paper> paper = parseModel(grid, ModelFormat::Fold, 1.0);
  ASSERT_TRUE(paper) << paper.message();
  EXPECT_EQ(paper->vertices.size(), 121u);
  EXPECT_TRUE(checkFaceSizes(*paper, { 0, 4 }));
  EXPECT_FALSE(checkFaceSizes(*paper, { 0, 3 }));
  // A frame of file_frames counts too.
  const std::string framed = R"({"file_spec":1.1,"vertices_coords":[[0,0],[1,0],[1,1]],"faces_vertices":[[0,1,2]],)"
                             R"("file_frames":[{"vertices_coords":[[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}]})";
  EXPECT_FALSE(checkModelSize(framed, ModelFormat::Fold, { 3, 0 }));
  // ORIPA: two vertices a line, blank lines aside.
  const std::string cp = "1 0 0 1 0\n\n1 1 0 1 1\n1 1 1 0 1\n1 0 1 0 0\n2 0 0 1 1\n";
  EXPECT_TRUE(checkModelSize(cp, ModelFormat::OripaCp, { 10, 0 }));
  EXPECT_FALSE(checkModelSize(cp, ModelFormat::OripaCp, { 9, 0 }));
  // SVG: one vertex a pair of runs of digits (1.5 is one, 1e-3 two, #000 one: an upper bound).
  const std::string svg = R"(<svg><polygon stroke="black" points="0,0 1.5,0 1.5,1 0,1e-3"/></svg>)";
  EXPECT_TRUE(checkModelSize(svg, ModelFormat::Svg, { 4, 0 }));
  EXPECT_FALSE(checkModelSize(svg, ModelFormat::Svg, { 3, 0 }));
  // Broken text is the parser's to refuse, with its own message.
  EXPECT_TRUE(checkModelSize("not json", ModelFormat::Fold, { 1, 1 }));
  EXPECT_FALSE(parseModel("not json", ModelFormat::Fold, 1.0));
}
