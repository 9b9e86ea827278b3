// A vertex folded flat obeys Maekawa, Kawasaki and big-little-big; checkFlatVertices refuses the
// first vertex that does not, naming it, the rule and a crease to change.
#include <gtest/gtest.h>

#include <regex>

#include <cmath>

#include "single_vertex.h"
#include "test_models.h"
#include "virtual_origami/core/flat_vertices.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
/// Signs of `degree` creases from the bits of `mask` (bit set: valley).
std::vector<int> signsOf(int mask, int degree)
{
  std::vector<int> signs;
  for (int i = 0; i < degree; ++i)
    signs.push_back((mask >> i) & 1 ? 1 : -1);
  return signs;
}

int valleys(const std::vector<int>& signs)
{
  int count = 0;
  for (int s : signs)
    count += s > 0;
  return count;
}
}  // namespace

// Eight creases 45° apart (the square base's centre): every sector equals its neighbours, so an
// assignment folds flat exactly when the valleys and mountains differ by two (5:3 or 3:5), 112
// of the 256.
TEST(FlatVertices, EightEqualSectorsFoldExactlyWhenMaekawaHolds)
{
  const Paper paper = singleVertex({ 0, 45, 90, 135, 180, 225, 270, 315 });
  int folding = 0;
  for (int mask = 0; mask < 256; ++mask)
  {
    const std::vector<int> signs = signsOf(mask, 8);
    const bool maekawa = std::abs(2 * valleys(signs) - 8) == 2;
    const Status checked = checkFlatVertices(paper, spokeAngles(paper, signs));
    EXPECT_EQ(checked.ok(), maekawa) << "mask " << mask << ": " << checked.message();
    folding += checked.ok();
    if (!maekawa)
    {
      EXPECT_NE(checked.message().find("Maekawa"), std::string::npos) << checked.message();
    }
  }
  EXPECT_EQ(folding, 112);
}

// Creases at 0°, 70°, 180°, 290°: sectors 70, 110, 110, 70, Kawasaki holds. Three creases of one
// kind and one of the other (Maekawa), and the lone one must not be the 180° crease, which alone
// does not bound a smallest sector: else the two 70° flaps beside it lie folded the same way
// around a smaller one (big-little-big). Six of the sixteen fold.
TEST(FlatVertices, ADegreeFourVertexFoldsWhenTheLoneCreaseBoundsASmallestAngle)
{
  const Paper paper = singleVertex({ 0, 70, 180, 290 });
  int folding = 0;
  for (int mask = 0; mask < 16; ++mask)
  {
    const std::vector<int> signs = signsOf(mask, 4);
    const int v = valleys(signs);
    const bool maekawa = v == 1 || v == 3;
    const int lone_sign = v == 1 ? 1 : -1;
    const bool lone_is_opposite_crease = maekawa && signs[2] == lone_sign;
    const Status checked = checkFlatVertices(paper, spokeAngles(paper, signs));
    EXPECT_EQ(checked.ok(), maekawa && !lone_is_opposite_crease) << "mask " << mask << ": " << checked.message();
    folding += checked.ok();
    if (lone_is_opposite_crease)
    {
      EXPECT_NE(checked.message().find("big-little-big"), std::string::npos) << checked.message();
    }
  }
  EXPECT_EQ(folding, 6);
}

TEST(FlatVertices, AnglesThatDoNotAlternateTo180AreRefusedByKawasaki)
{
  const Paper paper = singleVertex({ 0, 60, 160, 260 });  // sectors 60, 100, 100, 100: 160 and 200
  const Status checked = checkFlatVertices(paper, spokeAngles(paper, { 1, 1, 1, -1 }));
  ASSERT_FALSE(checked.ok());
  EXPECT_NE(checked.message().find("Kawasaki"), std::string::npos) << checked.message();
  EXPECT_NE(checked.message().find("vertex 0 at (0, 0)"), std::string::npos) << checked.message();
}

// The square base's centre with every crease valley folds "closed" (a turn by π is one by −π)
// but not flat: the refusal names the centre and a crease whose change makes it fold.
TEST(FlatVertices, AllValleysAtTheSquareBaseCentreNameTheCentreAndACreaseToChange)
{
  const Paper paper = creasedSquare();
  const int centre = paper.vertexAt(Vec2(0.5, 0.5));
  ASSERT_GE(centre, 0);
  std::vector<double> angles(paper.edges.size(), 0.0);
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
      angles[e] = M_PI;
  const Status checked = checkFlatVertices(paper, angles);
  ASSERT_FALSE(checked.ok());
  EXPECT_NE(checked.message().find("vertex " + std::to_string(centre) + " at (0.5, 0.5)"), std::string::npos)
      << checked.message();
  EXPECT_NE(checked.message().find("8 valley and 0 mountain"), std::string::npos) << checked.message();
  // Eight valleys are three flips from 5:3: no single crease makes it fold, and the refusal
  // names three whose flips do (issue 42: the crease to change, not only that one must).
  EXPECT_NE(checked.message().find("no change of a single crease"), std::string::npos) << checked.message();
  std::vector<double> told = angles;
  int named_creases = 0;
  const std::regex crease_named(R"(crease ([0-9]+) \([^)]*\)–\([^)]*\) (mountain|valley))");
  const std::string message = checked.message();
  for (auto it = std::sregex_iterator(message.begin(), message.end(), crease_named); it != std::sregex_iterator(); ++it)
  {
    const int e = std::stoi((*it)[1]);
    ASSERT_LT(e, static_cast<int>(told.size()));
    EXPECT_EQ((*it)[2], "mountain") << "a valley to make a mountain";
    told[e] = -M_PI;
    ++named_creases;
  }
  EXPECT_EQ(named_creases, 3) << message;
  EXPECT_TRUE(checkFlatVertices(paper, told).ok()) << checkFlatVertices(paper, told).message();

  // Six valleys and two mountains: one more mountain folds it, and the message names one.
  int flipped = 0;
  for (size_t e = 0; e < paper.edges.size() && flipped < 2; ++e)
    if (paper.edges[e].isCrease())
      angles[e] = -M_PI, ++flipped;
  const Status six = checkFlatVertices(paper, angles);
  ASSERT_FALSE(six.ok());
  const size_t at = six.message().find(": fold crease ");
  ASSERT_NE(at, std::string::npos) << six.message();
  const int named = std::stoi(six.message().substr(at + 14));
  ASSERT_GE(named, 0);
  ASSERT_LT(named, static_cast<int>(paper.edges.size()));
  EXPECT_GT(angles[named], 0) << "the crease named is a valley to make a mountain";
  EXPECT_NE(six.message().find("mountain instead"), std::string::npos) << six.message();
  angles[named] = -M_PI;
  EXPECT_TRUE(checkFlatVertices(paper, angles).ok());
}

// Vertices on the sheet's edge, and vertices with a crease at neither 0 nor ±π, are not judged.
TEST(FlatVertices, BoundaryVerticesAndFoldsNotFlatAreLeftAlone)
{
  const Paper paper = singleVertex({ 0, 70, 180, 290 });
  EXPECT_FALSE(checkFlatVertices(paper, spokeAngles(paper, { 1, 1, 1, 1 })).ok());
  std::vector<double> angles = spokeAngles(paper, { 1, 1, 1, 1 });
  angles[0] = M_PI / 2;  // not flat: the solver's business
  EXPECT_TRUE(checkFlatVertices(paper, angles).ok());
  // Only the ends of the edges named are checked.
  EXPECT_TRUE(checkFlatVertices(paper, spokeAngles(paper, { 1, 1, 1, 1 }), { 1 }).ok());   // a rim: boundary ends
  EXPECT_FALSE(checkFlatVertices(paper, spokeAngles(paper, { 1, 1, 1, 1 }), { 0 }).ok());  // a spoke: the centre
}
