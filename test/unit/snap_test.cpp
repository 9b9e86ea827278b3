#include <gtest/gtest.h>

#include <map>
#include <set>

#include "crane_reference.h"
#include "test_models.h"
#include "virtual_origami/core/snap.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

TEST(Snap, ToANearVertex)
{
  const Paper paper = Paper::square(1.0);
  const Snap s = snapPoint(paper, p3(0.98, 1.01), SnapSettings{});
  EXPECT_EQ(s.kind, SnapKind::Vertex);
  EXPECT_EQ(s.vertex, 2);
  EXPECT_EQ(s.point, paper.vertices[2].folded);
}

TEST(Snap, ToEdgeDivisionPointsWithTheirGuide)
{
  const Paper paper = Paper::square(1.0);
  SnapSettings settings;
  const Snap half = snapPoint(paper, p3(0.51, 0.01), settings);
  EXPECT_EQ(half.kind, SnapKind::EdgeDivision);
  EXPECT_EQ(half.edge, 0);
  EXPECT_EQ(half.divisions, 2);  // 1/2 wins over 2/4, the same point
  EXPECT_TRUE(half.point.isApprox(p3(0.5, 0)));
  ASSERT_EQ(half.guide_points.size(), 1u);
  const Snap quarter = snapPoint(paper, p3(0.99, 0.74), settings);
  EXPECT_EQ(quarter.kind, SnapKind::EdgeDivision);
  EXPECT_EQ(quarter.divisions, 4);
  EXPECT_EQ(quarter.index, 3);
  EXPECT_TRUE(quarter.point.isApprox(p3(1, 0.75)));
  ASSERT_EQ(quarter.guide_points.size(), 3u);  // the edge's three quarter points
  EXPECT_TRUE(quarter.guide_points[0].isApprox(p3(1, 0.25)));
  // Thirds only when asked for.
  settings.edge_divisions = { 3 };
  const Snap third = snapPoint(paper, p3(0.34, 0.02), settings);
  EXPECT_EQ(third.kind, SnapKind::EdgeDivision);
  EXPECT_NEAR(third.point.x(), 1.0 / 3, 1e-15);
}

TEST(Snap, ToAngleDivisionsFromAStartVertex)
{
  const Paper paper = Paper::square(1.0);
  // From corner 0 the right angle splits at 45° (n = 2) and 22.5°, 67.5° (n = 4).
  const Snap diagonal = snapPoint(paper, p3(0.6, 0.62), SnapSettings{}, 0);
  EXPECT_EQ(diagonal.kind, SnapKind::AngleDivision);
  EXPECT_EQ(diagonal.vertex, 0);
  EXPECT_EQ(diagonal.divisions, 2);
  EXPECT_TRUE(diagonal.point.isApprox(p3(1, 1), 1e-12));  // on to where the direction leaves the face
  ASSERT_EQ(diagonal.guide_lines.size(), 1u);
  EXPECT_TRUE(diagonal.guide_lines[0].a.isApprox(p3(0, 0)));
  EXPECT_TRUE(diagonal.guide_lines[0].b.isApprox(p3(1, 1), 1e-12));

  const double a = M_PI / 8;  // 22.5°
  const Snap eighth = snapPoint(paper, p3(0.5 * std::cos(a) + 0.005, 0.5 * std::sin(a)), SnapSettings{}, 0);
  EXPECT_EQ(eighth.kind, SnapKind::AngleDivision);
  EXPECT_EQ(eighth.divisions, 4);
  EXPECT_EQ(eighth.index, 1);
  EXPECT_NEAR(std::atan2(eighth.point.y(), eighth.point.x()), a, 1e-12);
  EXPECT_NEAR(eighth.point.x(), 1.0, 1e-12);  // at the right side
  EXPECT_EQ(eighth.guide_lines.size(), 3u);
  // Without a start vertex the angle rule is off.
  EXPECT_EQ(snapPoint(paper, p3(0.6, 0.62), SnapSettings{}).kind, SnapKind::None);
}

TEST(Snap, ASnappedDirectionEndingInsideTheSheetCreasesAcrossIt)
{
  // Issue 23: a drag from a corner that ended just inside the sheet snapped to the 22.5° ray,
  // and the crease to its end was refused, short of the edge.
  Paper paper = Paper::square(1.0);
  const double a = M_PI / 8;
  const Vec3 end = p3(0.9 * std::cos(a) + 0.004, 0.9 * std::sin(a) - 0.003);  // inside the sheet
  const Snap snapped = snapPoint(paper, end, SnapSettings{}, 0);
  ASSERT_EQ(snapped.kind, SnapKind::AngleDivision);
  EXPECT_TRUE(snapped.point.isApprox(p3(1, std::tan(a)), 1e-12));
  creaseLine(paper, paper.vertices[0].folded, snapped.point);
  EXPECT_EQ(paper.faces.size(), 2u);
  // Past the edge the cursor's own distance stays: the line may go on over other layers.
  const Snap beyond = snapPoint(Paper::square(1.0), p3(1.3 * std::cos(a), 1.3 * std::sin(a) + 0.01), SnapSettings{}, 0);
  ASSERT_EQ(beyond.kind, SnapKind::AngleDivision);
  EXPECT_NEAR(beyond.point.norm(), 1.3, 0.01);
}

TEST(Snap, FarFromEverythingStaysPut)
{
  const Paper paper = Paper::square(1.0);
  const Snap s = snapPoint(paper, p3(0.3, 0.6), SnapSettings{}, 0);
  EXPECT_EQ(s.kind, SnapKind::None);
  EXPECT_EQ(s.point, p3(0.3, 0.6));
  EXPECT_TRUE(s.guide_points.empty());
  EXPECT_TRUE(s.guide_lines.empty());
}

TEST(Snap, VertexBeatsEdgeDivision)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -1), p3(0.5, 2));  // vertices at (0.5, 0) and (0.5, 1)
  const Snap s = snapPoint(paper, p3(0.51, 0.01), SnapSettings{});
  EXPECT_EQ(s.kind, SnapKind::Vertex);
  EXPECT_TRUE(s.point.isApprox(p3(0.5, 0)));
}

TEST(Snap, WhereLayersCornersCoincideEachOffersTheAnglesOfEveryLayer)
{
  // The bird base (crane step 13): its open point and other points are corners of several
  // layers. A line started there must be offered the same directions whichever layer's vertex
  // the press snapped to (one of the four corners at the open point missed 22.5°).
  const Expected<std::vector<Paper>> states = craneStates();
  ASSERT_TRUE(states.ok()) << states.message();
  const Paper& bird = (*states)[13];
  std::map<std::tuple<long, long, long>, std::vector<int>> at;  // vertices by folded point (1e-9 grid)
  for (size_t v = 0; v < bird.vertices.size(); ++v)
  {
    const Vec3& q = bird.vertices[v].folded;
    at[{ std::lround(q.x() * 1e9), std::lround(q.y() * 1e9), std::lround(q.z() * 1e9) }].push_back(static_cast<int>(v));
  }
  int groups = 0;
  for (const auto& [key, vertices] : at)
  {
    if (vertices.size() < 2)
      continue;
    ++groups;
    const Vec3 p = bird.vertices[vertices[0]].folded;
    // The directions a line from there snaps to, sampled all round in the plane of the model.
    std::vector<std::set<long>> offered;
    for (int v : vertices)
    {
      std::set<long> directions;
      for (int k = 0; k < 720; ++k)
      {
        const double a = 2 * M_PI * k / 720;
        const Snap s = snapPoint(bird, p + 0.2 * Vec3(std::cos(a), std::sin(a), 0), SnapSettings{}, v);
        if (s.kind == SnapKind::AngleDivision)
          directions.insert(std::lround(std::atan2((s.point - p).y(), (s.point - p).x()) * 1e6));
      }
      offered.push_back(directions);
    }
    for (size_t i = 1; i < offered.size(); ++i)
      EXPECT_EQ(offered[i], offered[0]) << "vertices " << vertices[0] << " and " << vertices[i] << " at ("
                                        << p.transpose() << ") offer different directions";
  }
  EXPECT_GT(groups, 3);
}
