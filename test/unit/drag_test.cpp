#include <gtest/gtest.h>

#include <cmath>

#include "crane_reference.h"
#include "test_models.h"
#include "virtual_origami/core/drag.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
const Vec3 kFromAbove(0, 0, -1);

/// The unit square creased along its diagonal from corner 0 (0,0) to corner 2 (1,1).
Paper diagonalSquare()
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0, 0), p3(1, 1));
  return paper;
}

int diagonalEdge(const Paper& paper)
{
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
      return static_cast<int>(e);
  return -1;
}

/// Applies the drag's angle with the core operation, as the service would.
Paper turned(const Paper& paper, const RotationRing& ring, double angle)
{
  Paper next = paper;
  RotateRequest request;
  request.face = ring.face;
  request.axis_edge = ring.axis_edge;
  request.click = ring.press;
  request.angle = angle;
  const Expected<RotateResult> result = rotate(next, request);
  EXPECT_TRUE(result.ok()) << result.message();
  return next;
}

}  // namespace

TEST(CreaseDrag, SnapsBothEndsToTheCornersOfADiagonal)
{
  const Paper paper = Paper::square(1.0);
  const CreaseDrag drag = creaseDrag(paper, p3(0.012, 0.02), p3(0.985, 0.99), SnapSettings{});
  EXPECT_EQ(drag.start.kind, SnapKind::Vertex);
  EXPECT_EQ(drag.end.kind, SnapKind::Vertex);
  EXPECT_EQ(drag.start.point, paper.vertices[0].folded);
  EXPECT_EQ(drag.end.point, paper.vertices[2].folded);
  const CreaseRequest request = drag.request();
  EXPECT_FALSE(request.snap);  // what was drawn is what is creased
  EXPECT_EQ(request.start, paper.vertices[0].folded);
  EXPECT_NEAR(drag.length(), std::sqrt(2.0), 1e-15);
}

TEST(CreaseDrag, TheEndSnapsToAngleDivisionsOnlyFromAVertex)
{
  const Paper paper = Paper::square(1.0);
  // From corner 0 the pointer near the diagonal snaps onto it (n = 2), with its guide.
  const CreaseDrag from_corner = creaseDrag(paper, p3(0.01, 0.0), p3(0.6, 0.62), SnapSettings{});
  EXPECT_EQ(from_corner.end.kind, SnapKind::AngleDivision);
  EXPECT_NEAR(from_corner.end.point.x(), from_corner.end.point.y(), 1e-12);
  EXPECT_FALSE(from_corner.end.guide_lines.empty());
  // From the middle of the sheet nothing snaps.
  const CreaseDrag free = creaseDrag(paper, p3(0.3, 0.4), p3(0.6, 0.62), SnapSettings{});
  EXPECT_EQ(free.start.kind, SnapKind::None);
  EXPECT_EQ(free.end.kind, SnapKind::None);
  EXPECT_EQ(free.end.point, p3(0.6, 0.62));
}

TEST(CreaseDrag, AnEdgeDivisionPointIsShownAsGuide)
{
  const Paper paper = Paper::square(1.0);
  const CreaseDrag drag = creaseDrag(paper, p3(0.49, 0.01), p3(0.51, 0.98), SnapSettings{});
  EXPECT_EQ(drag.start.kind, SnapKind::EdgeDivision);
  EXPECT_EQ(drag.end.kind, SnapKind::EdgeDivision);
  EXPECT_TRUE(drag.start.point.isApprox(p3(0.5, 0)));
  EXPECT_TRUE(drag.end.point.isApprox(p3(0.5, 1)));
  EXPECT_FALSE(drag.end.guide_points.empty());
}

TEST(RotationRing, PressOnAHalfPicksTheDiagonalAsAxis)
{
  const Paper paper = diagonalSquare();
  const Expected<RotationRing> ring = rotationRing(paper, p3(0.8, 0.3), kFromAbove);
  ASSERT_TRUE(ring.ok()) << ring.message();
  EXPECT_EQ(ring->axis_edge, diagonalEdge(paper));
  EXPECT_TRUE(ring->edge_on);  // from straight above, the ring is seen edge-on
  EXPECT_TRUE(ring->centre.isApprox(p3(0.55, 0.55)));
  EXPECT_NEAR(ring->radius, 0.25 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(ring->press_angle, 0.0, 1e-12);
  EXPECT_TRUE(ring->w.isApprox(Vec3(0, 0, 1)));  // towards the eye
  EXPECT_EQ(ring->moving_faces.size(), 1u);      // the half turns rigidly
  EXPECT_NEAR(ring->min_angle, -M_PI, 1e-12);
  EXPECT_NEAR(ring->max_angle, M_PI, 1e-12);
}

// A half turn dragged to the mirror image lands on 180° exactly, not at 179° (a flap left
// short of flat makes the next half turn over it crumple the model); 10° short stays short.
TEST(RotationRing, AHalfTurnWithinThreeDegreesSnapsToOne)
{
  const Paper paper = diagonalSquare();
  const RotationRing ring = *rotationRing(paper, p3(0.8, 0.3), kFromAbove);
  const Vec3 u = (p3(0.8, 0.3) - ring.centre).normalized();
  const auto pointerAt = [&](double degrees) {  // seen edge-on, the distance maps onto the angle
    return Vec3(ring.centre + ring.radius * (1.0 - 2.0 * degrees / 180.0) * u);
  };
  EXPECT_EQ(std::abs(ringAngle(ring, pointerAt(178.0), kFromAbove)), M_PI);
  EXPECT_EQ(std::abs(ringAngle(ring, pointerAt(179.5), kFromAbove)), M_PI);
  EXPECT_NEAR(std::abs(ringAngle(ring, pointerAt(170.0), kFromAbove)), 170.0 * M_PI / 180.0, 1e-12);
  EXPECT_NEAR(std::abs(ringAngle(ring, pointerAt(90.0), kFromAbove)), M_PI / 2, 1e-12);
}

TEST(RotationRing, DraggingTowardsTheAxisLiftsTheHalfTowardsTheEye)
{
  const Paper paper = diagonalSquare();
  const RotationRing ring = *rotationRing(paper, p3(0.8, 0.3), kFromAbove);
  // Not moved: no turn. Over the axis: a quarter turn. At the mirror image: a half turn.
  EXPECT_NEAR(ringAngle(ring, p3(0.8, 0.3), kFromAbove), 0.0, 1e-12);
  const double quarter = ringAngle(ring, p3(0.55, 0.55), kFromAbove);
  EXPECT_NEAR(std::abs(quarter), M_PI / 2, 1e-12);
  EXPECT_NEAR(std::abs(ringAngle(ring, p3(0.3, 0.8), kFromAbove)), M_PI, 1e-12);
  EXPECT_NEAR(std::abs(ringAngle(ring, p3(0.0, 1.0), kFromAbove)), M_PI, 1e-12);  // clamped
  // Along the axis nothing changes; linear in between.
  EXPECT_NEAR(ringAngle(ring, p3(0.9, 0.4), kFromAbove), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(ringAngle(ring, p3(0.675, 0.425), kFromAbove)), M_PI / 4, 1e-12);

  // The core turns the half as the ring said: up towards the eye, a valley fold.
  const Paper up = turned(paper, ring, quarter);
  EXPECT_NEAR(up.edges[ring.axis_edge].fold_angle, M_PI / 2, 1e-9);
  const Vec3 corner = up.vertices[up.vertexAt(Vec2(1, 0))].folded;
  EXPECT_GT(corner.z(), 0.5);
  EXPECT_TRUE(ringPoint(ring, quarter).isApprox(p3(0.55, 0.55, 0.25 * std::sqrt(2.0))));
  // The other half stays.
  EXPECT_EQ(up.vertices[up.vertexAt(Vec2(0, 1))].folded, p3(0, 1));
}

TEST(RotationRing, PressOnTheOtherHalfTurnsItTheSameWay)
{
  const Paper paper = diagonalSquare();
  const RotationRing ring = *rotationRing(paper, p3(0.2, 0.7), kFromAbove);
  const double angle = ringAngle(ring, p3(0.45, 0.45), kFromAbove);
  const Paper up = turned(paper, ring, angle);
  EXPECT_NEAR(up.edges[ring.axis_edge].fold_angle, M_PI / 2, 1e-9);
  EXPECT_GT(up.vertices[up.vertexAt(Vec2(0, 1))].folded.z(), 0.5);
  EXPECT_EQ(up.vertices[up.vertexAt(Vec2(1, 0))].folded, p3(1, 0));
}

TEST(RotationRing, SeenFromTheSideTheAngleFollowsThePointerAroundTheRing)
{
  const Paper paper = diagonalSquare();
  // Looking along the diagonal (the axis), slightly down: the ring is seen nearly round.
  const Vec3 view = Vec3(1, 1, -0.5).normalized();
  const RotationRing ring = *rotationRing(paper, p3(0.8, 0.3), view);
  EXPECT_FALSE(ring.edge_on);
  for (double target : { 0.3, 1.2, 2.5, -0.7 })
  {
    // A pointer anywhere on the ray through the ring point at `target` gives `target`.
    const Vec3 on_ring = ringPoint(ring, target);
    EXPECT_NEAR(ringAngle(ring, on_ring - 0.4 * view, view, target * 0.9), target, 1e-9) << target;
  }
  // Unwrapped next to the previous angle, clamped to the fold limits; within 3° of a half turn,
  // a half turn.
  EXPECT_NEAR(ringAngle(ring, ringPoint(ring, M_PI - 0.1), view, 3.0), M_PI - 0.1, 1e-9);
  EXPECT_EQ(ringAngle(ring, ringPoint(ring, M_PI - 0.01), view, 3.0), M_PI);
}

TEST(RotationRing, AFoldedFlapUnfoldsTowardsTheEyeWithinItsLimits)
{
  Paper paper = diagonalSquare();
  const RotationRing first = *rotationRing(paper, p3(0.8, 0.3), kFromAbove);
  paper = turned(paper, first, M_PI);  // lower-right half over the upper-left one
  // The flap now lies over the upper-left half; its pressed point is the mirror image.
  const Expected<RotationRing> ring = rotationRing(paper, p3(0.3, 0.8, 0.0), kFromAbove);
  ASSERT_TRUE(ring.ok()) << ring.message();
  EXPECT_EQ(ring->face, first.face);  // the top layer
  // Only back towards unfolded: the crease is at 180° already.
  const double back = ringAngle(*ring, p3(0.55, 0.55), kFromAbove);
  EXPECT_NEAR(back, -M_PI / 2, 1e-9);
  EXPECT_NEAR(ring->min_angle, -2 * M_PI, 1e-9);
  EXPECT_NEAR(ring->max_angle, 0.0, 1e-9);
  const Paper opened = turned(paper, *ring, back);
  EXPECT_NEAR(opened.edges[ring->axis_edge].fold_angle, M_PI / 2, 1e-9);
}

TEST(RotationRing, RefusesWithAMessage)
{
  const Paper square = Paper::square(1.0);
  const auto no_crease = rotationRing(square, p3(0.5, 0.4), kFromAbove);
  EXPECT_FALSE(no_crease.ok());
  EXPECT_FALSE(no_crease.message().empty());
  const Paper paper = diagonalSquare();
  EXPECT_FALSE(rotationRing(paper, p3(1.5, 0.4), kFromAbove).ok());    // off the sheet
  EXPECT_FALSE(rotationRing(paper, p3(0.5, 0.5), kFromAbove).ok());    // on the axis
  EXPECT_FALSE(rotationRing(paper, p3(0.8, 0.3), Vec3::Zero()).ok());  // no view
}

namespace
{
/// Every face pressed at its centroid and turned about each of its creases by a small angle
/// each way: the ring allows the turn exactly when rotate() makes it (a turn refused only for
/// want of a solver says nothing about the ring's limits).
void expectRingLimitsAsRotateTurns(const Paper& paper, bool carry_stack, int& checked)
{
  for (size_t f = 0; f < paper.faces.size(); ++f)
    for (int e : paper.faces[f].edges)
    {
      if (!paper.edges[e].isCrease())
        continue;
      const int face = static_cast<int>(f);
      const Vec3 press = paper.faceCentroid(face);
      const Expected<RotationRing> ring = rotationRing(paper, press, kFromAbove, face, e, carry_stack);
      if (!ring)
        continue;
      for (double angle : { 0.1, -0.1 })
      {
        Paper turned = paper;
        RotateRequest request;
        request.face = face;
        request.axis_edge = e;
        request.click = press;
        request.angle = angle;
        request.carry_stack = carry_stack;
        const Expected<RotateResult> result = rotate(turned, request);
        if (!result && result.message().find("past 180") == std::string::npos)
          continue;
        const bool allowed = angle >= ring->min_angle && angle <= ring->max_angle;
        EXPECT_EQ(allowed, result.ok()) << "face " << face << " about edge " << e << " by " << angle << ": "
                                        << (result ? "turned" : result.message()) << "; ring limits ["
                                        << ring->min_angle << ", " << ring->max_angle << "]";
        ++checked;
      }
    }
}
}  // namespace

TEST(RotationRing, ItsLimitsAreThoseOfTheLayersTheTurnCarries)
{
  int checked = 0;
  for (int times : { 1, 2, 3 })
    for (bool carry : { true, false })
      expectRingLimitsAsRotateTurns(stackOfLayers(times), carry, checked);
  // The crane's flat states, up to eight layers (the script folds them).
  const Expected<std::vector<Paper>> states = craneStates();
  ASSERT_TRUE(states.ok()) << states.message();
  for (size_t i : { size_t(8), size_t(13), size_t(19) })  // the square base, the bird base, the crane before its wings
    for (bool carry : { true, false })
      expectRingLimitsAsRotateTurns((*states)[i], carry, checked);
  EXPECT_GT(checked, 200);
}
