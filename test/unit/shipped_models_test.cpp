// The shipped fold sequences end in the models they name: shapes, layer counts, strain,
// validity, and their FOLD files read back.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/core/layers.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/core/validity.h"

using namespace virtual_origami::core;

namespace
{
std::vector<Paper> foldShipped(const std::string& name, size_t* operations = nullptr)
{
  std::ifstream in(std::string(VO_SOURCE_DIR) + "/sequences/" + name);
  std::stringstream text;
  text << in.rdbuf();
  const Expected<FoldSequence> sequence = parseFoldSequence(text.str());
  EXPECT_TRUE(sequence.ok()) << sequence.message();
  if (!sequence)
    return {};
  if (operations)
  {
    *operations = 0;
    for (const FoldStep& step : sequence->steps)
      *operations += static_cast<size_t>(step.repeat);
  }
  Session session;
  const Expected<std::vector<Paper>> states = foldSequence(*sequence, session);
  EXPECT_TRUE(states.ok()) << states.message();
  return states ? *states : std::vector<Paper>{};
}

Vec3 foldedAt(const Paper& paper, const Vec2& crease_pattern_point)
{
  for (const Vertex& v : paper.vertices)
    if ((v.crease_pattern - crease_pattern_point).norm() < 1e-12)
      return v.folded;
  ADD_FAILURE() << "no vertex at " << crease_pattern_point.transpose();
  return Vec3::Constant(NAN);
}

/// Written as FOLD and read back: the same vertices, each where it was within 1e-9.
void expectFoldRoundTrip(const Paper& paper)
{
  const Expected<FoldDocument> read = parseFold(formatFold(paper, "round trip"));
  ASSERT_TRUE(read.ok()) << read.message();
  const Paper& back = read->frames.back();
  ASSERT_EQ(back.vertices.size(), paper.vertices.size());
  EXPECT_EQ(back.faces.size(), paper.faces.size());
  for (size_t v = 0; v < paper.vertices.size(); ++v)
  {
    EXPECT_LT((back.vertices[v].folded - paper.vertices[v].folded).norm(), 1e-9) << "vertex " << v;
    EXPECT_LT((back.vertices[v].crease_pattern - paper.vertices[v].crease_pattern).norm(), 1e-9) << "vertex " << v;
  }
}

/// The multi-frame FOLD of a sequence: one frame per state (the flat sheet, then one per
/// operation), each read back where it was.
void expectFramesRoundTrip(const std::vector<Paper>& states, size_t operations)
{
  ASSERT_EQ(states.size(), operations + 1);
  const Expected<FoldDocument> read = parseFold(formatFoldSequence(states, "frames"));
  ASSERT_TRUE(read.ok()) << read.message();
  ASSERT_EQ(read->frames.size(), states.size());
  for (size_t k = 0; k < states.size(); ++k)
  {
    ASSERT_EQ(read->frames[k].vertices.size(), states[k].vertices.size()) << "frame " << k;
    for (size_t v = 0; v < states[k].vertices.size(); ++v)
      EXPECT_LT((read->frames[k].vertices[v].folded - states[k].vertices[v].folded).norm(), 1e-9)
          << "frame " << k << " vertex " << v;
  }
}

void expectRigidAndValid(const Paper& paper)
{
  EXPECT_LT(edgeStrain(paper).max, 1e-12);
  const ValidityReport report = checkValidity(paper);
  EXPECT_TRUE(report.ok()) << report.summary();
}
}  // namespace

// The crane sequence as far as it folds with rotations: the sheet creased for the square
// base and folded in half on both diagonals, a right triangle of four layers with the
// sheet's centre at its right angle.
TEST(ShippedCrane, EndsInTheFourLayerTriangleOfTheSquareBase)
{
  size_t operations = 0;
  const std::vector<Paper> states = foldShipped("crane.json", &operations);
  ASSERT_FALSE(states.empty());
  const Paper& crane = states.back();
  expectRigidAndValid(crane);
  EXPECT_EQ(crane.faces.size(), 8u);  // the eight 45° sectors of the square base's creases
  for (const Vec3& inside : { Vec3(0.9, 0.3, 0), Vec3(0.9, 0.7, 0), Vec3(0.8, 0.45, 0) })
    EXPECT_EQ(layerCount(crane, inside), 4) << inside.transpose();
  EXPECT_EQ(layerCount(crane, Vec3(0.3, 0.2, 0)), 0);
  EXPECT_EQ(layerCount(crane, Vec3(0.9, 0.3, 0.01)), 0);  // flat: nothing off the table
  // Corners and midpoints of the sheet on the triangle's corners and hypotenuse.
  EXPECT_LT((foldedAt(crane, Vec2(0.5, 0.5)) - Vec3(0.5, 0.5, 0)).norm(), 1e-12);
  for (const Vec2& corner : { Vec2(0, 0), Vec2(1, 1) })
    EXPECT_LT((foldedAt(crane, corner) - Vec3(1, 1, 0)).norm(), 1e-12);
  for (const Vec2& corner : { Vec2(1, 0), Vec2(0, 1) })
    EXPECT_LT((foldedAt(crane, corner) - Vec3(1, 0, 0)).norm(), 1e-12);
  for (const Vec2& midpoint : { Vec2(0.5, 0), Vec2(1, 0.5), Vec2(0.5, 1), Vec2(0, 0.5) })
    EXPECT_LT((foldedAt(crane, midpoint) - Vec3(1, 0.5, 0)).norm(), 1e-12);
  expectFoldRoundTrip(crane);
  expectFramesRoundTrip(states, operations);
}

// The penguin: feet folded up, both sides folded in as wings, folded in half behind on the
// centre line, the head folded down along (.75,.75)-(1,.8).
TEST(ShippedPenguin, HasItsHeadFeetAndWingsWhereTheFoldsPutThem)
{
  size_t operations = 0;
  const std::vector<Paper> states = foldShipped("penguin.json", &operations);
  ASSERT_FALSE(states.empty());
  const Paper& penguin = states.back();
  expectRigidAndValid(penguin);
  // The head: corner (1,1) mirrored across the head crease.
  const Vec2 a(0.75, 0.75), d = Vec2(0.25, 0.05).normalized();
  const Vec2 tip = 2 * (a + (Vec2(1, 1) - a).dot(d) * d) - Vec2(1, 1);
  EXPECT_LT((foldedAt(penguin, Vec2(1, 1)) - Vec3(tip.x(), tip.y(), 0)).norm(), 1e-12);
  // The feet: corner (0,0) folded up to (.4,.4) on the centre line.
  EXPECT_LT((foldedAt(penguin, Vec2(0, 0)) - Vec3(0.4, 0.4, 0)).norm(), 1e-12);
  // Wings: the side corners meet at (.55,.45), one on each side of the body.
  EXPECT_LT((foldedAt(penguin, Vec2(1, 0)) - Vec3(0.55, 0.45, 0)).norm(), 1e-12);
  EXPECT_LT((foldedAt(penguin, Vec2(0, 1)) - Vec3(0.55, 0.45, 0)).norm(), 1e-12);
  // Layers: the body is the sheet doubled (2), four where the wings lie on it, four where the
  // feet do, and nothing on the far side of the centre line.
  EXPECT_EQ(layerCount(penguin, Vec3(0.7, 0.6, 0)), 2);
  EXPECT_EQ(layerCount(penguin, Vec3(0.8, 0.3, 0)), 4);
  EXPECT_EQ(layerCount(penguin, Vec3(0.35, 0.3, 0)), 4);
  EXPECT_EQ(layerCount(penguin, Vec3(0.3, 0.6, 0)), 0);
  expectFoldRoundTrip(penguin);
  expectFramesRoundTrip(states, operations);
}
