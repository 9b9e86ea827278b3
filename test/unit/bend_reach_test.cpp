// Where bent paper can take a dragged vertex: no farther from a held vertex than the two lie
// apart on the sheet.
#include <gtest/gtest.h>

#include <cmath>

#include "test_models.h"
#include "virtual_origami/core/bend_reach.h"

using namespace virtual_origami::core;

namespace
{
/// The unit square's corner at (x, y) in the crease pattern.
int cornerAt(const Paper& paper, double x, double y)
{
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    if ((paper.vertices[v].crease_pattern - Vec2(x, y)).norm() < 1e-12)
      return static_cast<int>(v);
  return -1;
}
}  // namespace

TEST(BendingReaches, AnywhereWithinTheSheetsDistanceOfEveryPin)
{
  const Paper paper = Paper::square(1.0);
  const int a = cornerAt(paper, 0, 0), b = cornerAt(paper, 1, 0), c = cornerAt(paper, 1, 1), d = cornerAt(paper, 0, 1);
  ASSERT_TRUE(a >= 0 && b >= 0 && c >= 0 && d >= 0);
  // Three corners held flat: the fourth lifts off the table as bent paper (no rigid face can).
  EXPECT_TRUE(bendingReaches(paper, { c, Vec3(0.9, 0.9, 0.3) }, { a, b, d }).ok());
  // Straight up from where it lies: at once farther from b and d than the sheet lets it.
  const Status up = bendingReaches(paper, { c, Vec3(1, 1, 0.2) }, { a, b, d });
  ASSERT_FALSE(up.ok());
  EXPECT_NE(up.message().find("does not stretch"), std::string::npos) << up.message();
  // Full stretch from the one pin (the diagonal, stood up) is reached; a little past it is not.
  const double diagonal = std::sqrt(2.0);
  EXPECT_TRUE(bendingReaches(paper, { c, Vec3(0, 0, diagonal) }, { a }).ok());
  const Status past = bendingReaches(paper, { c, Vec3(0, 0, diagonal * (1 + 1e-6)) }, { a });
  ASSERT_FALSE(past.ok());
  EXPECT_NE(past.message().find("pinned vertex " + std::to_string(a)), std::string::npos) << past.message();
  // Nothing held: anywhere.
  EXPECT_TRUE(bendingReaches(paper, { c, Vec3(5, -3, 2) }, {}).ok());
}

TEST(BendingReaches, DistancesAlongTheSheetNotInTheFoldedModel)
{
  // Folded in half on x = 0.5, the right half over the left: the corner (1, 0) lies on (0, 0). It may move up to 1 from the
  // pinned (0, 0) — its distance on the sheet — though the two now touch.
  const Paper paper = test::stackOfLayers(1);
  const int a = cornerAt(paper, 0, 0), b = cornerAt(paper, 1, 0);
  ASSERT_TRUE(a >= 0 && b >= 0);
  EXPECT_TRUE(bendingReaches(paper, { b, paper.vertices[a].folded + Vec3(0, 0, 0.99) }, { a }).ok());
  EXPECT_FALSE(bendingReaches(paper, { b, paper.vertices[a].folded + Vec3(0, 0, 1.01) }, { a }).ok());
}

TEST(BendingReaches, RefusesBadInput)
{
  const Paper paper = Paper::square(1.0);
  EXPECT_FALSE(bendingReaches(paper, { 99, Vec3(0, 0, 0) }, {}).ok());
  EXPECT_FALSE(bendingReaches(paper, { -1, Vec3(0, 0, 0) }, {}).ok());
  EXPECT_FALSE(bendingReaches(paper, { 0, Vec3(std::nan(""), 0, 0) }, {}).ok());
  const Status pinned = bendingReaches(paper, { 0, Vec3(0, 0, 0.1) }, { 0 });
  ASSERT_FALSE(pinned.ok());
  EXPECT_NE(pinned.message().find("is pinned"), std::string::npos) << pinned.message();
}
