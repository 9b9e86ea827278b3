#include <gtest/gtest.h>

#include "test_models.h"
#include "virtual_origami/core/rotate.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
void expectRejected(Paper& paper, const RotateRequest& request, const std::string& words)
{
  const Paper before = paper;
  const Expected<RotateResult> result = rotate(paper, request);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message().find(words), std::string::npos) << result.message();
  EXPECT_TRUE(paper == before);
}

int onlyCrease(const Paper& paper)
{
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
      return static_cast<int>(e);
  return -1;
}
}  // namespace

TEST(Rotate, TurnsTheFaceByTheAngle)
{
  for (double angle : { M_PI / 2, -M_PI / 3, M_PI })
  {
    Paper paper = Paper::square(1.0);
    creaseLine(paper, p3(0.5, -1), p3(0.5, 2));
    RotateRequest request;
    request.click = p3(0.8, 0.5);  // the right half; its only crease is the axis
    request.angle = angle;
    const Expected<RotateResult> r = rotate(paper, request);
    ASSERT_TRUE(r.ok()) << r.message();
    EXPECT_EQ(r->axis_edge, onlyCrease(paper));
    EXPECT_EQ(r->moved_faces.size(), 1u);
    EXPECT_NEAR(paper.edges[r->axis_edge].fold_angle, angle, 1e-12);
    // The far edge of the right half turned about x = 0.5 (valley lifts it towards +z).
    for (const Vertex& v : paper.vertices)
      if (v.crease_pattern.x() > 0.75)
      {
        EXPECT_NEAR(v.folded.x(), 0.5 + 0.5 * std::cos(angle), 1e-12);
        EXPECT_NEAR(v.folded.z(), 0.5 * std::sin(angle), 1e-12);
      }
      else
      {
        EXPECT_EQ(v.folded.z(), 0.0);  // the other half stays exactly
      }
    expectValid(paper);
  }
}

TEST(Rotate, FoldedFlatLayersCoincide)
{
  Paper paper = stackOfLayers(1);
  for (const Vertex& v : paper.vertices)
  {
    const Vec2& c = v.crease_pattern;
    const double x = c.x() <= 0.5 ? c.x() : 1.0 - c.x();
    EXPECT_LT((v.folded - p3(x, c.y())).norm(), 1e-15);
  }
  const int hinge = onlyCrease(paper);
  EXPECT_NEAR(paper.edges[hinge].fold_angle, M_PI, 1e-15);
  EXPECT_EQ(paper.edges[hinge].assignment, Assignment::Valley);
  expectValid(paper);
}

TEST(Rotate, AFlapCarriesEveryLayerConnectedToIt)
{
  // Folded in half: two layers over [0, 0.5] × [0, 1], joined along x = 0.5. Folding the top
  // half down carries both layers (joined by the first fold), and nothing else.
  Paper paper = stackOfLayers(1);
  const CreaseResult c = creaseLine(paper, p3(-0.1, 0.5), p3(0.6, 0.5));
  ASSERT_EQ(c.new_edges.size(), 2u);
  RotateRequest request;
  request.click = p3(0.3, 0.8);
  request.face = faceAt(paper, request.click, 1e-9);
  for (int e : c.new_edges)
    if (paper.edges[e].faces[0] == request.face || paper.edges[e].faces[1] == request.face)
      request.axis_edge = e;
  request.angle = M_PI;
  const Paper before = paper;
  const Expected<RotateResult> r = rotate(paper, request);
  ASSERT_TRUE(r.ok()) << r.message();
  EXPECT_EQ(r->moved_faces.size(), 2u);
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const bool moved = std::find(r->moved_faces.begin(), r->moved_faces.end(), f) != r->moved_faces.end();
    const Vec3 was = before.faceCentroid(static_cast<int>(f));
    const Vec3 now = paper.faceCentroid(static_cast<int>(f));
    EXPECT_EQ(moved, was.y() > 0.5) << "face " << f;
    if (moved)
      EXPECT_NEAR(now.y(), 1.0 - was.y(), 1e-12);  // mirrored over y = 0.5
    else
      EXPECT_TRUE(now == was);
  }
  for (int e : c.new_edges)
    EXPECT_NEAR(std::abs(paper.edges[e].fold_angle), M_PI, 1e-12);
  expectValid(paper);
}

TEST(Rotate, LockedFacesNeedASolver)
{
  // A crease across the sheet and one from its midpoint to a corner: turning the lower right
  // face about the diagonal drags the left half, which holds the upper right face too.
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -1), p3(0.5, 2));
  const CreaseResult diagonal = creaseLine(paper, p3(0.5, 0.5), p3(1, 1));
  ASSERT_EQ(diagonal.new_edges.size(), 1u);
  RotateRequest request;
  request.face = faceAt(paper, p3(0.9, 0.3), 1e-9);
  request.axis_edge = diagonal.new_edges[0];
  request.angle = 0.3;
  EXPECT_TRUE(flapOf(paper, request.face, request.axis_edge).empty());
  expectRejected(paper, request, "solver");
}

TEST(Rotate, PastHalfATurnIsRejected)
{
  Paper paper = stackOfLayers(1);
  RotateRequest request;
  request.face = faceAt(paper, p3(0.25, 0.5, 0.0), 1e-9);
  request.axis_edge = onlyCrease(paper);
  request.angle = 0.1;  // already at 180°
  expectRejected(paper, request, "past 180");
  request.angle = -M_PI;  // unfolding is fine
  EXPECT_TRUE(rotate(paper, request).ok());
  EXPECT_NEAR(paper.edges[request.axis_edge].fold_angle, 0.0, 1e-12);
  expectValid(paper);
}

TEST(Rotate, BadInputChangesNothing)
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0.5, -1), p3(0.5, 2));
  RotateRequest request;
  request.click = p3(0.8, 0.5);
  request.angle = NAN;
  expectRejected(paper, request, "not finite");
  request.angle = 1.0;
  request.face = 7;
  expectRejected(paper, request, "face 7 does not exist");
  request.face = -1;
  request.axis_edge = 99;
  expectRejected(paper, request, "edge 99 does not exist");
  request.axis_edge = 0;  // a boundary edge
  expectRejected(paper, request, "boundary");
  request.axis_edge = -1;
  request.click = p3(3, 3);
  expectRejected(paper, request, "no face");
  request.click = p3(0.8, INFINITY);
  expectRejected(paper, request, "non-finite");
  Paper flat = Paper::square(1.0);
  request.click = p3(0.5, 0.5);
  expectRejected(flat, request, "no crease");
}
