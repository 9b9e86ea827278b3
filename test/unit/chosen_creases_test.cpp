// Marks on creases become a flat fold (SPEC §3.7).
#include <gtest/gtest.h>

#include "test_models.h"
#include "virtual_origami/core/chosen_creases.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

TEST(ChosenCreases, AClickCyclesValleyMountainUnfoldNone)
{
  EXPECT_EQ(nextMark(CreaseMark::None), CreaseMark::Valley);
  EXPECT_EQ(nextMark(CreaseMark::Valley), CreaseMark::Mountain);
  EXPECT_EQ(nextMark(CreaseMark::Mountain), CreaseMark::Unfold);
  EXPECT_EQ(nextMark(CreaseMark::Unfold), CreaseMark::None);
  EXPECT_EQ(markAngle(CreaseMark::Valley), M_PI);
  EXPECT_EQ(markAngle(CreaseMark::Mountain), -M_PI);
  EXPECT_EQ(markAngle(CreaseMark::Unfold), 0.0);
  EXPECT_EQ(markAngle(CreaseMark::Valley, M_PI / 2), M_PI / 2);
}

TEST(ChosenCreases, MarksFollowTheCreaseNotItsIdAndUnmarkingForgetsIt)
{
  Paper paper = Paper::square(1.0);
  const CreaseResult diagonal = creaseLine(paper, p3(0, 0), p3(1, 1));
  ASSERT_EQ(diagonal.new_edges.size(), 1u);
  CreaseMarks marks;
  marks.mark(paper, diagonal.new_edges[0], CreaseMark::Mountain);
  EXPECT_EQ(marks.markOf(paper, diagonal.new_edges[0]), CreaseMark::Mountain);
  marks.mark(paper, 0, CreaseMark::Valley);  // a boundary edge is no crease: no mark
  EXPECT_EQ(marks.marks().size(), 1u);
  // The other diagonal cuts the first in two: neither half is the crease that was marked.
  creaseLine(paper, p3(1, 0), p3(0, 1));
  EXPECT_TRUE(marks.edges(paper).empty());
  Paper fresh = Paper::square(1.0);
  const CreaseResult again = creaseLine(fresh, p3(0, 0), p3(1, 1));
  marks.clear();
  marks.mark(fresh, again.new_edges[0], CreaseMark::Valley);
  marks.mark(fresh, again.new_edges[0], CreaseMark::None);
  EXPECT_TRUE(marks.empty());
}

TEST(ChosenCreases, AValleyMarkFoldsTheHalfOverTheFaceThatStays)
{
  Paper paper = Paper::square(1.0);
  const int crease = creaseLine(paper, p3(0.5, 0), p3(0.5, 1)).new_edges.at(0);
  int left = -1;
  for (size_t f = 0; f < paper.faces.size(); ++f)
    if (paper.faceCentroid(static_cast<int>(f)).x() < 0.5)
      left = static_cast<int>(f);
  CreaseMarks marks;
  EXPECT_FALSE(chosenCreasesFold(paper, marks, left));
  marks.mark(paper, crease, CreaseMark::Valley);
  const std::optional<FlatFoldRequest> request = chosenCreasesFold(paper, marks, left);
  ASSERT_TRUE(request);
  Paper folded = paper;
  const Expected<FlatFoldResult> result = flatFold(folded, *request);
  ASSERT_TRUE(result.ok()) << result.message();
  for (const Vertex& v : folded.vertices)  // the right half lies over the left, the left stayed
    EXPECT_LE(v.folded.x(), 0.5 + 1e-12);
  EXPECT_NEAR(folded.edges[crease].fold_angle, M_PI, 1e-12);
  EXPECT_EQ(faceContaining(paper, creasePatternPoint(paper, left)), left);
  EXPECT_EQ(faceContaining(paper, Vec2(1.5, 0.5)), -1);
  // No face picked: refused as off the sheet, the paper unchanged.
  Paper untouched = paper;
  EXPECT_FALSE(flatFold(untouched, *chosenCreasesFold(paper, marks, -1)).ok());
  EXPECT_EQ(untouched.vertices[0].folded, paper.vertices[0].folded);
}
