// The shipped fold sequences end in the models they name: shapes, layer counts, strain,
// validity, and their FOLD files read back.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/core/layers.h"
#include "virtual_origami/core/metrics.h"
#include "virtual_origami/core/validity.h"
#include "virtual_origami/solvers/solver_factory.h"

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
  const Expected<std::vector<Paper>> states = foldSequence(*sequence, session, makeSolver(sequence->solver));
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

/// Layers summed over a grid of cells covering [0, 1]²: the folded model's area counted
/// with its layers, which must be the sheet's.
double layeredArea(const Paper& paper, int cells)
{
  double sum = 0.0;
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j)
      sum += layerCount(paper, Vec3((i + 0.5) / cells, (j + 0.5) / cells, 0));
  return sum / (cells * cells);
}

// The crane sequence: square base (two diagonal folds, two squash folds), bird base (edge
// and top creases, petal folds front and back), then the two lower flaps inside-reverse
// folded up and out as neck and tail, the head reverse folded down at the neck's end, and the
// two upper flaps opened to right angles as wings.
// The body lies in the table plane z = 0, its up direction u = (-1,1)/√2 (from the slit's
// bottom at (1,0) towards the petals' points); the wings' hinge crosses the body at the top of
// the slit, (1 - √½/2, √½/2).
TEST(ShippedCrane, EndsInACraneWithNeckTailHeadAndWings)
{
  size_t operations = 0;
  const std::vector<Paper> states = foldShipped("crane.json", &operations);
  ASSERT_FALSE(states.empty());
  const Paper& crane = states.back();
  expectRigidAndValid(crane);
  const double h = std::sqrt(0.5);
  const Vec3 slit_top(1 - h / 2, h / 2, 0), up(-h, h, 0), across(-h, -h, 0);
  const Vec3 head = foldedAt(crane, Vec2(1, 0)), tail = foldedAt(crane, Vec2(0, 1));
  const Vec3 crown = foldedAt(crane, Vec2(0.88, 0));  // where the head's crease meets the neck's top
  const Vec3 centre = foldedAt(crane, Vec2(0.5, 0.5));
  // Neck and tail: each lower flap (half a unit long) turned by its reverse fold from straight
  // down to 45° above the horizontal, on either side of the body; the neck's top edge then
  // runs to the crown, 0.38 from the slit, where the head turns down.
  const Vec3 neck_direction = h * up + h * across;
  EXPECT_LT((crown - (slit_top + 0.38 * neck_direction)).norm(), 1e-12);
  EXPECT_LT((tail - (slit_top + 0.5 * (h * up - h * across))).norm(), 1e-12);
  EXPECT_NEAR((crown - slit_top).dot(up), 0.38 * h, 1e-12);  // raised above the wings' hinge
  EXPECT_NEAR((tail - slit_top).dot(up), 0.5 * h, 1e-12);
  EXPECT_GT((crown - centre).dot(up), 0.06);  // and above the sheet's centre, the body's middle
  EXPECT_GT((tail - centre).dot(up), 0.14);
  // The head: the neck's last 0.12 mirrored across its crease (22.5° from the neck's top edge,
  // towards its lower edge): it points 45° below the neck.
  const Vec3 unfolded_tip = slit_top + 0.5 * neck_direction;
  const Eigen::AngleAxisd turn(M_PI / 8, Vec3::UnitZ());  // from the neck towards its lower edge
  const Vec3 crease_direction = turn * neck_direction;
  const Vec3 foot = crown + (unfolded_tip - crown).dot(crease_direction) * crease_direction;
  EXPECT_LT((head - (2 * foot - unfolded_tip)).norm(), 1e-12);
  EXPECT_NEAR((head - crown).norm(), 0.12, 1e-12);
  EXPECT_NEAR((head - crown).normalized().dot(neck_direction), std::cos(M_PI / 4), 1e-12);
  // Wings: the petals' points half a unit off the body plane, on opposite sides, each turned
  // away from the body: the front flap (corner (0, 0), all its layers on top) up, the back down.
  const Vec3 wing_a = foldedAt(crane, Vec2(0, 0)), wing_b = foldedAt(crane, Vec2(1, 1));
  EXPECT_LT((wing_a - (slit_top + Vec3(0, 0, 0.5))).norm(), 1e-12);
  EXPECT_LT((wing_b - (slit_top - Vec3(0, 0, 0.5))).norm(), 1e-12);
  EXPECT_LT(wing_a.z() * wing_b.z(), 0.0);
  EXPECT_NEAR((wing_a - wing_b).norm(), 1.0, 1e-12);
  // Layers: 4 in the neck and the tail (the flaps' four layers), 8 in the body below the
  // hinge where both flaps' roots lie, 2 in each wing.
  // (Probed just off the slit's edges, which now run along the tops of neck and tail.)
  EXPECT_EQ(layerCount(crane, slit_top + 0.3 * (h * up + h * across) - Vec3(0, 0.02, 0)), 4);
  EXPECT_EQ(layerCount(crane, slit_top + 0.3 * (h * up - h * across) + Vec3(0.02, 0, 0)), 4);
  EXPECT_EQ(layerCount(crane, Vec3(0.75, 0.45, 0)), 8);
  const Vec3 hinge(h, h, 0);  // along the wings' hinge
  EXPECT_EQ(layerCount(crane, slit_top - 0.08 * hinge - Vec3(0, 0, 0.1)), 2);
  EXPECT_EQ(layerCount(crane, slit_top - 0.08 * hinge + Vec3(0, 0, 0.1)), 2);
  // The sheet's area: the wings' four layers of triangles (base √2 - 1, the top crease;
  // height ½) stand off the table; what lies on it sums to the rest.
  const double wings = 4 * 0.5 * (std::sqrt(2.0) - 1) * 0.5;
  EXPECT_NEAR(layeredArea(crane, 400), 1.0 - wings, 0.01);  // a 1/400 grid misses its edge cells
  expectFoldRoundTrip(crane);
  expectFramesRoundTrip(states, operations);
}

// The bird base on the way: a diamond along the line from the lower flaps' points, the
// corners (1,0) and (0,1), at the bottom (1,0) to the petals' points, the corners (0,0) and
// (1,1), at (1 - √½, √½): as long as the sheet's side.
TEST(ShippedCrane, PassesThroughTheBirdBase)
{
  const std::vector<Paper> states = foldShipped("crane.json");
  ASSERT_GE(states.size(), 14u);
  const Paper& bird = states[13];  // the state after the back petal fold, the 13th step
  expectRigidAndValid(bird);
  const double h = std::sqrt(0.5), t = 0.5 * std::tan(M_PI / 8);  // t: where the edge creases meet the midlines
  for (const Vec2& petal_point : { Vec2(0, 0), Vec2(1, 1) })
    EXPECT_LT((foldedAt(bird, petal_point) - Vec3(1 - h, h, 0)).norm(), 1e-12);
  for (const Vec2& leg_point : { Vec2(1, 0), Vec2(0, 1) })
    EXPECT_LT((foldedAt(bird, leg_point) - Vec3(1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((foldedAt(bird, Vec2(0.5, 0.5)) - Vec3(0.5, 0.5, 0)).norm(), 1e-12);
  EXPECT_LT((foldedAt(bird, Vec2(0.5, t)) - Vec3(0.5, t, 0)).norm(), 1e-12);
  EXPECT_LT((foldedAt(bird, Vec2(t, 0.5)) - Vec3(1 - t, 0.5, 0)).norm(), 1e-12);
  // Layers: 4 in the lower flaps, 8 in the body where the petals lie over the flaps' roots,
  // 4 in the petals above the sheet's centre, none outside the diamond; all sum to the sheet.
  EXPECT_EQ(layerCount(bird, Vec3(0.8, 0.15, 0)), 4);
  EXPECT_EQ(layerCount(bird, Vec3(0.55, 0.4, 0)), 8);
  EXPECT_EQ(layerCount(bird, Vec3(0.38, 0.58, 0)), 4);
  EXPECT_EQ(layerCount(bird, Vec3(0.3, 0.3, 0)), 0);
  EXPECT_EQ(layerCount(bird, Vec3(0.8, 0.15, 0.01)), 0);  // flat: nothing off the table
  EXPECT_NEAR(layeredArea(bird, 400), 1.0, 0.01);
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
