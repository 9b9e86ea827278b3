// Stacked layers move together (seed Fig. 15): the layer order of flat folds is kept, and a
// rotation carries the layers in its way.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "test_models.h"
#include "virtual_origami/core/face_orders.h"
#include "virtual_origami/core/layers.h"
#include "virtual_origami/core/rotate.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
constexpr double kTolerance = 1e-7;

/// Where `other` lies from `face` along world +z by the recorded order: +1, −1 or 0.
int worldSide(const Paper& paper, int face, int other)
{
  const int order = faceOrder(paper, face, other);
  return paper.faceNormal(face).z() > 0 ? order : -order;
}

/// The face whose crease-pattern centroid is nearest `c`.
int faceFrom(const Paper& paper, const Vec2& c)
{
  int best = -1;
  double best_distance = INFINITY;
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    Vec2 centroid = Vec2::Zero();
    for (int v : paper.faces[f].vertices)
      centroid += paper.vertices[v].crease_pattern;
    centroid /= static_cast<double>(paper.faces[f].vertices.size());
    if ((centroid - c).norm() < best_distance)
    {
      best_distance = (centroid - c).norm();
      best = static_cast<int>(f);
    }
  }
  return best;
}

/// Every pair of faces lying flat on each other has a recorded order.
void expectEveryStackedPairOrdered(const Paper& paper)
{
  for (size_t f = 0; f < paper.faces.size(); ++f)
    for (size_t g = f + 1; g < paper.faces.size(); ++g)
    {
      const bool stacked = facesStacked(paper, static_cast<int>(f), static_cast<int>(g), kTolerance);
      EXPECT_EQ(stacked, faceOrder(paper, static_cast<int>(f), static_cast<int>(g)) != 0)
          << "faces " << f << " and " << g;
    }
}

/// The four-layer stack of stackOfLayers(2) creased across at y = 0.25. Each layer's strip
/// below the crease is joined to one other strip (along x = 0.5): two 2-layer flaps.
struct Quartered
{
  Paper paper;
  std::vector<int> strips;  // the four strips, bottom layer first
  std::vector<int> rest;    // the four pieces above the crease, bottom layer first
};

Quartered fourLayersCreasedAtAQuarter()
{
  Quartered q;
  q.paper = stackOfLayers(2);
  const std::vector<int> levels = stackLevels(q.paper);
  std::vector<Vec2> quarters(4);  // crease-pattern centre of each layer, bottom first
  for (const Vec2& c : { Vec2(0.25, 0.25), Vec2(0.75, 0.25), Vec2(0.25, 0.75), Vec2(0.75, 0.75) })
    quarters[levels[faceFrom(q.paper, c)]] = c;
  creaseLine(q.paper, p3(-0.1, 0.25), p3(0.6, 0.25));
  EXPECT_EQ(q.paper.faces.size(), 8u);
  // A layer's strip is the half of its quarter that lies in y < 0.25 once folded.
  for (const Vec2& c : quarters)
  {
    const Vec2 up(0.0, 0.125);
    const int a = faceFrom(q.paper, c - up), b = faceFrom(q.paper, c + up);
    const bool a_below = q.paper.faceCentroid(a).y() < 0.25;
    q.strips.push_back(a_below ? a : b);
    q.rest.push_back(a_below ? b : a);
  }
  return q;
}

/// The fold angle that swings `face` up (+z) about its crease: valley for a face whose front
/// looks up.
double upwards(const Paper& paper, int face)
{
  return paper.faceNormal(face).z() > 0 ? M_PI : -M_PI;
}

int hingeOf(const Paper& paper, int face)
{
  for (int e : paper.faces[face].edges)
  {
    const Edge& edge = paper.edges[e];
    if (edge.isCrease() && std::abs(paper.vertices[edge.vertices[0]].folded.y() - 0.25) < 1e-12 &&
        std::abs(paper.vertices[edge.vertices[1]].folded.y() - 0.25) < 1e-12)
      return e;
  }
  return -1;
}

std::vector<int> sorted(std::vector<int> v)
{
  std::sort(v.begin(), v.end());
  return v;
}
}  // namespace

TEST(FaceOrders, AHalfFoldPutsTheFoldedHalfOnTheSideItSwungTo)
{
  const Paper paper = stackOfLayers(1);  // valley: the right half swings up over the left
  ASSERT_EQ(paper.faces.size(), 2u);
  const int left = faceFrom(paper, Vec2(0.25, 0.5)), right = faceFrom(paper, Vec2(0.75, 0.5));
  EXPECT_EQ(worldSide(paper, left, right), 1);  // above along +z
  EXPECT_EQ(faceOrder(paper, left, right), 1);  // above along the left half's normal (+z)
  EXPECT_EQ(faceOrder(paper, right, left), 1);  // the right half faces down: the left is on its front
  EXPECT_EQ(paper.face_orders.size(), 1u);
}

TEST(FaceOrders, CreasingAStackSplitsItsOrders)
{
  Paper paper = stackOfLayers(1);
  creaseLine(paper, p3(-0.1, 0.5), p3(0.6, 0.5));
  ASSERT_EQ(paper.faces.size(), 4u);
  expectEveryStackedPairOrdered(paper);
  for (double y : { 0.25, 0.75 })
  {
    const int lower = faceFrom(paper, Vec2(0.25, y)), upper = faceFrom(paper, Vec2(0.75, y));
    EXPECT_EQ(worldSide(paper, lower, upper), 1);
  }
  EXPECT_EQ(paper.face_orders.size(), 2u);  // the pieces that no longer overlap have none
}

TEST(FaceOrders, FoldingInHalfTwiceStacksFourLayersInOrder)
{
  const Paper paper = stackOfLayers(2);
  ASSERT_EQ(paper.faces.size(), 4u);
  expectEveryStackedPairOrdered(paper);
  const std::vector<int> levels = stackLevels(paper);
  const int ll = levels[faceFrom(paper, Vec2(0.25, 0.25))], rl = levels[faceFrom(paper, Vec2(0.75, 0.25))];
  const int lu = levels[faceFrom(paper, Vec2(0.25, 0.75))], ru = levels[faceFrom(paper, Vec2(0.75, 0.75))];
  // The first fold lays the right half on the left; the second turns the upper half's two
  // layers over onto the lower half's, above or below it, their order reversed.
  EXPECT_EQ(rl, ll + 1);
  const bool over = lu > rl;
  EXPECT_EQ(std::vector<int>({ ll, rl, lu, ru }),
            over ? std::vector<int>({ 0, 1, 3, 2 }) : std::vector<int>({ 2, 3, 1, 0 }));
}

TEST(Flap, FoldingTheTopFlapOverMovesExactlyItsLayers)
{
  Quartered q = fourLayersCreasedAtAQuarter();
  Paper& paper = q.paper;
  expectEveryStackedPairOrdered(paper);
  // The top strip's flap is the two top layers (layer 4's strip is joined to layer 3's).
  const std::vector<int> flap{ q.strips[3], q.strips[2] };
  const Paper before = paper;
  RotateRequest request;
  request.face = q.strips[3];
  request.axis_edge = hingeOf(paper, request.face);
  ASSERT_GE(request.axis_edge, 0);
  request.angle = upwards(paper, request.face);  // up and over the top of the stack
  const Expected<RotateResult> r = rotate(paper, request);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_FALSE(r->used_solver);
  EXPECT_EQ(sorted(r->moved_faces), sorted(flap));
  expectValid(paper);
  expectEveryStackedPairOrdered(paper);

  // Layers that stayed keep their order, the flap's two layers are reversed, and both now
  // lie above every layer they cover: no face lies between two layers it was not between.
  std::vector<int> staying = q.rest;
  staying.push_back(q.strips[0]);
  staying.push_back(q.strips[1]);
  for (int a : staying)
    for (int b : staying)
      if (a != b)
      {
        EXPECT_EQ(worldSide(paper, a, b), worldSide(before, a, b));
      }
  EXPECT_EQ(worldSide(paper, flap[0], flap[1]), -worldSide(before, flap[0], flap[1]));
  for (int s : q.rest)
    for (int m : flap)
      EXPECT_EQ(worldSide(paper, s, m), 1) << "face " << m << " should lie above face " << s;
  const std::vector<int> levels = stackLevels(paper);
  EXPECT_EQ(levels[q.strips[3]], 4);  // just above the top layer it is hinged to
  EXPECT_EQ(levels[q.strips[2]], 5);
  // The lower flap did not move.
  for (int f : { q.strips[0], q.strips[1] })
    EXPECT_TRUE(paper.faceCentroid(f) == before.faceCentroid(f)) << "face " << f;
}

TEST(Flap, FoldingTheTopLayerUnderCarriesEveryLayerBelowIt)
{
  Quartered q = fourLayersCreasedAtAQuarter();
  Paper& paper = q.paper;
  const Paper before = paper;
  RotateRequest request;
  request.face = q.strips[3];
  request.axis_edge = hingeOf(paper, request.face);
  request.angle = -upwards(paper, request.face);  // down, through the three layers below
  const Expected<RotateResult> r = rotate(paper, request);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(sorted(r->moved_faces), sorted(q.strips));
  expectValid(paper);
  expectEveryStackedPairOrdered(paper);
  for (int s : q.rest)
    for (int m : q.strips)
      EXPECT_EQ(worldSide(paper, s, m), -1) << "face " << m << " should lie below face " << s;
  for (int a : q.strips)
    for (int b : q.strips)
      if (a != b)
      {
        EXPECT_EQ(worldSide(paper, a, b), -worldSide(before, a, b));
      }
}

TEST(Flap, WithoutCarryingTheFaceTakesOnlyWhatItIsJoinedTo)
{
  // The seed's behaviour (Fig. 15): the pressed layer takes only its connected part. Pressed
  // from the bottom and swung up, the bottom flap (layers 1 and 2) would pass through the two
  // layers above it; carried, all four strips turn.
  Quartered q = fourLayersCreasedAtAQuarter();
  RotateRequest request;
  request.face = q.strips[0];
  request.axis_edge = hingeOf(q.paper, request.face);
  request.angle = upwards(q.paper, request.face);
  request.carry_stack = false;
  Paper seed_way = q.paper;
  const Expected<RotateResult> alone = rotate(seed_way, request);
  ASSERT_TRUE(alone.ok()) << alone.message();
  EXPECT_EQ(sorted(alone->moved_faces), sorted({ q.strips[0], q.strips[1] }));
  request.carry_stack = true;
  const Expected<RotateResult> carried = rotate(q.paper, request);
  ASSERT_TRUE(carried.ok()) << carried.message();
  EXPECT_EQ(sorted(carried->moved_faces), sorted(q.strips));
  // Swung down instead, the bottom flap has nothing in its way.
  Paper down = fourLayersCreasedAtAQuarter().paper;
  request.angle = -request.angle;
  const Expected<RotateResult> under = rotate(down, request);
  ASSERT_TRUE(under.ok()) << under.message();
  EXPECT_EQ(sorted(under->moved_faces), sorted({ q.strips[0], q.strips[1] }));
}

TEST(Flap, UnfoldingDropsTheOrdersOfLayersThatNoLongerOverlap)
{
  Paper paper = stackOfLayers(1);
  ASSERT_EQ(paper.face_orders.size(), 1u);
  RotateRequest request;
  request.face = faceFrom(paper, Vec2(0.75, 0.5));
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
      request.axis_edge = static_cast<int>(e);
  request.angle = -M_PI;
  ASSERT_TRUE(rotate(paper, request).ok());
  EXPECT_TRUE(paper.face_orders.empty());
  request.angle = M_PI / 2;
  ASSERT_TRUE(rotate(paper, request).ok());
  EXPECT_TRUE(paper.face_orders.empty());
}
