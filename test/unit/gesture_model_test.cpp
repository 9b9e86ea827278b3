// The mouse gestures without ROS (as tf2's BufferCore is tested without a master): presses,
// moves, releases and menu choices into the gesture model, the requests to paper_model and the
// drawings out, in order.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "crane_reference.h"
#include "flap_drags.h"
#include "test_models.h"
#include "virtual_origami/core/gesture_model.h"

using namespace virtual_origami::core;
using namespace virtual_origami::core::test;

namespace
{
/// Records what the model asks and shows; paper_model's replies are scripted (default: yes).
class RecordedOutputs : public GestureOutputs
{
public:
  PaperReply send(const PaperRequest& request) override
  {
    requests.push_back(request);
    return reply ? reply(request) : PaperReply{ true, true, "", 0, false };
  }
  void show(const GestureOutput& output) override
  {
    shown.push_back(output);
  }

  template <class T>
  std::vector<T> sent() const
  {
    std::vector<T> found;
    for (const PaperRequest& r : requests)
      if (const T* t = std::get_if<T>(&r))
        found.push_back(*t);
    return found;
  }
  template <class T>
  std::vector<T> drawn() const
  {
    std::vector<T> found;
    for (const GestureOutput& o : shown)
      if (const T* t = std::get_if<T>(&o))
        found.push_back(*t);
    return found;
  }
  std::string lastSaid() const
  {
    const std::vector<Message> said = drawn<Message>();
    return said.empty() ? "" : said.back().text;
  }
  void forget()
  {
    requests.clear();
    shown.clear();
  }

  std::vector<PaperRequest> requests;
  std::vector<GestureOutput> shown;
  std::function<PaperReply(const PaperRequest&)> reply;
};

class GestureModelTest : public ::testing::Test
{
protected:
  GestureModelTest() : model(GestureSettings{}, out, [this] { return now; })
  {}

  void load(Paper paper)
  {
    model.paperChanged(std::move(paper), ++revision, {});
    out.forget();
  }
  /// rviz's report of a point of the sheet seen from above: on the pickable copy over it.
  Pointer at(const Vec3& p) const
  {
    return Pointer{ Vec3(p + Vec3(0, 0, model.shownLift())), Vec3::Zero(), {} };
  }
  /// The marker dragged from `press` until the pointer is over `p`.
  Pointer dragged(const Vec3& press, const Vec3& p) const
  {
    return Pointer{ std::nullopt, p - press, {} };
  }
  void drag(const Vec3& from, const std::vector<Vec3>& through)
  {
    model.press(at(from));
    for (const Vec3& p : through)
    {
      now += 0.1;
      model.move(dragged(from, p));
      model.update();
    }
    model.release(dragged(from, through.empty() ? from : through.back()));
  }
  void click(const Vec3& p)
  {
    drag(p, {});
  }

  double now = 100.0;
  uint64_t revision = 0;
  RecordedOutputs out;
  GestureModel model;
};

Paper diagonalSquare()
{
  Paper paper = Paper::square(1.0);
  creaseLine(paper, p3(0, 0), p3(1, 1));
  return paper;
}
}  // namespace

TEST_F(GestureModelTest, ACreaseDragShowsTheSnappedLineAndCreasesItOnRelease)
{
  load(Paper::square(1.0));
  model.press(at(p3(0.012, 0.02)));
  EXPECT_EQ(model.state(), GestureState::DrawingLine);
  now += 0.5;
  EXPECT_DOUBLE_EQ(model.timeInState(), 0.5);
  model.move(dragged(p3(0.012, 0.02), p3(0.985, 0.99)));
  EXPECT_TRUE(out.requests.empty());  // moves wait for the update
  model.update();
  const std::vector<Guides> guides = out.drawn<Guides>();
  ASSERT_FALSE(guides.empty());
  ASSERT_TRUE(guides.back().line.has_value());
  EXPECT_TRUE(guides.back().line->start.point.isApprox(p3(0, 0)));  // the guide: snapped to the corners
  EXPECT_TRUE(guides.back().line->end.point.isApprox(p3(1, 1)));
  EXPECT_TRUE(out.requests.empty());  // nothing creased while drawing

  model.release(dragged(p3(0.012, 0.02), p3(0.985, 0.99)));
  const std::vector<CreaseCall> creases = out.sent<CreaseCall>();
  ASSERT_EQ(out.requests.size(), 1u);
  ASSERT_EQ(creases.size(), 1u);
  EXPECT_TRUE(creases[0].start.isApprox(p3(0, 0)));
  EXPECT_TRUE(creases[0].end.isApprox(p3(1, 1)));
  EXPECT_FALSE(creases[0].eye.has_value());  // no camera known
  EXPECT_EQ(model.state(), GestureState::Idle);
  EXPECT_FALSE(out.drawn<Guides>().back().line.has_value());  // the guides cleared
  EXPECT_EQ(out.drawn<SheetReleased>().size(), 1u);
}

TEST_F(GestureModelTest, WithoutSnappingTheLineIsCreasedAsDrawn)
{
  load(Paper::square(1.0));
  model.toggleSnapping(at(p3(0.5, 0.5)));
  EXPECT_FALSE(model.snapping());
  EXPECT_EQ(out.drawn<SheetShown>().size(), 1u);  // the menu's check mark
  drag(p3(0.012, 0.02), { p3(0.985, 0.99) });
  const std::vector<CreaseCall> creases = out.sent<CreaseCall>();
  ASSERT_EQ(creases.size(), 1u);
  EXPECT_TRUE(creases[0].start.isApprox(p3(0.012, 0.02)));
  EXPECT_TRUE(creases[0].end.isApprox(p3(0.985, 0.99)));
}

TEST_F(GestureModelTest, AClickInCreaseModeCreasesNothingAndARefusalIsSaid)
{
  load(Paper::square(1.0));
  click(p3(0.4, 0.4));
  EXPECT_TRUE(out.requests.empty());
  out.reply = [](const PaperRequest&) { return PaperReply{ true, false, "the line crosses no face", 0, false }; };
  drag(p3(0.1, 0.5), { p3(0.9, 0.5) });
  EXPECT_EQ(out.sent<CreaseCall>().size(), 1u);
  EXPECT_EQ(out.lastSaid(), "the line crosses no face");
}

TEST_F(GestureModelTest, ARotateDragPreviewsTheTurnThenCommitsTheAngleLastShown)
{
  load(diagonalSquare());
  model.chooseMode(GestureMode::Rotate, at(p3(0.5, 0.5)));
  EXPECT_EQ(out.lastSaid(), "rotate mode");
  out.forget();
  // From above the ring is seen edge-on: over the axis a quarter turn, half-way an eighth.
  drag(p3(0.8, 0.3), { p3(0.55, 0.55), p3(0.675, 0.425) });
  const std::vector<RotateCall> calls = out.sent<RotateCall>();
  ASSERT_EQ(calls.size(), 3u);
  EXPECT_FALSE(calls[0].commit);
  EXPECT_NEAR(std::abs(calls[0].angle), M_PI / 2, 1e-9);
  EXPECT_FALSE(calls[1].commit);
  EXPECT_NEAR(std::abs(calls[1].angle), M_PI / 4, 1e-9);
  EXPECT_TRUE(calls[2].commit);
  EXPECT_EQ(calls[2].angle, calls[1].angle);
  for (const RotateCall& c : calls)
  {
    EXPECT_EQ(c.axis_edge, calls[0].axis_edge);
    EXPECT_TRUE(c.click.isApprox(p3(0.8, 0.3)));
    EXPECT_FALSE(c.picked_layers_only);
  }
  const std::vector<Guides> guides = out.drawn<Guides>();
  ASSERT_GE(guides.size(), 3u);
  EXPECT_TRUE(guides[guides.size() - 2].ring.has_value());  // the ring while turning, then cleared
  EXPECT_FALSE(guides.back().ring.has_value());
  EXPECT_EQ(model.state(), GestureState::Idle);
}

TEST_F(GestureModelTest, ARotateDragBackToNoTurnPutsThePaperBackAndCommitsNothing)
{
  load(diagonalSquare());
  model.chooseMode(GestureMode::Rotate, at(p3(0.5, 0.5)));
  out.forget();
  drag(p3(0.8, 0.3), { p3(0.55, 0.55), p3(0.8, 0.3) });
  const std::vector<RotateCall> calls = out.sent<RotateCall>();
  ASSERT_EQ(calls.size(), 2u);
  EXPECT_NEAR(std::abs(calls[0].angle), M_PI / 2, 1e-9);
  EXPECT_EQ(calls[1].angle, 0.0);  // the preview of no turn
  EXPECT_FALSE(calls[1].commit);
}

TEST_F(GestureModelTest, AModeSwitchDuringADragCancelsIt)
{
  load(diagonalSquare());
  model.chooseMode(GestureMode::Rotate, at(p3(0.5, 0.5)));
  model.press(at(p3(0.8, 0.3)));
  model.move(dragged(p3(0.8, 0.3), p3(0.55, 0.55)));
  model.update();
  ASSERT_EQ(model.state(), GestureState::TurningFace);
  out.forget();
  model.chooseMode(GestureMode::Crease, at(p3(0.5, 0.5)));
  EXPECT_EQ(model.state(), GestureState::Idle);
  EXPECT_EQ(model.mode(), GestureMode::Crease);
  EXPECT_EQ(out.drawn<SheetShown>().size(), 1u);  // the menu's check marks and the sheet's description
  EXPECT_EQ(out.lastSaid(), "crease mode");
  model.release(dragged(p3(0.8, 0.3), p3(0.55, 0.55)));
  EXPECT_TRUE(out.requests.empty());  // nothing committed, nothing creased
}

TEST_F(GestureModelTest, ARotatePressOffEveryCreaseTurnsNothingAndSaysWhy)
{
  load(Paper::square(1.0));
  model.chooseMode(GestureMode::Rotate, at(p3(0.5, 0.5)));
  out.forget();
  model.press(at(p3(0.5, 0.4)));
  EXPECT_EQ(model.state(), GestureState::TurningNothing);
  model.move(dragged(p3(0.5, 0.4), p3(0.2, 0.2)));
  model.update();
  model.release(dragged(p3(0.5, 0.4), p3(0.2, 0.2)));
  EXPECT_TRUE(out.requests.empty());
  EXPECT_FALSE(out.lastSaid().empty());
}

TEST_F(GestureModelTest, AClickOnACreaseInRotateModeNamesItTheAxis)
{
  load(creasedSquare());
  model.chooseMode(GestureMode::Rotate, at(p3(0.5, 0.5)));
  click(p3(0.5, 0.2));  // on the midline x = .5
  EXPECT_EQ(out.lastSaid().rfind("The axis: this crease.", 0), 0u);
  const std::vector<Guides> guides = out.drawn<Guides>();
  ASSERT_TRUE(guides.back().named_axis.has_value());
  EXPECT_NEAR(guides.back().named_axis->first.x(), 0.5, 1e-12);
  EXPECT_NEAR(guides.back().named_axis->second.x(), 0.5, 1e-12);
  out.forget();
  // A turn of a face next to it is about it, not the face's automatic axis.
  drag(p3(0.7, 0.4), { p3(0.55, 0.4) });
  const std::vector<RotateCall> calls = out.sent<RotateCall>();
  ASSERT_FALSE(calls.empty());
  const Paper& paper = *model.paper();
  const Edge& axis = paper.edges[calls[0].axis_edge];
  EXPECT_NEAR(paper.vertices[axis.vertices[0]].crease_pattern.x(), 0.5, 1e-12);
  EXPECT_NEAR(paper.vertices[axis.vertices[1]].crease_pattern.x(), 0.5, 1e-12);
  out.forget();
  click(p3(0.7, 0.35));  // off every crease: the automatic axis again
  EXPECT_EQ(out.lastSaid(), "The automatic axis again.");
  EXPECT_FALSE(out.drawn<Guides>().back().named_axis.has_value());
}

TEST_F(GestureModelTest, NextLayerDownPicksTheLayerUnderTheTopOneAndTheRingTakesIt)
{
  load(stackOfLayers(1));  // the right half folded over the left: two layers over [0, .5] × [0, 1]
  model.chooseMode(GestureMode::Rotate, at(p3(0.25, 0.5)));
  const auto ringFace = [&] {
    out.forget();
    model.press(at(p3(0.25, 0.5)));
    const std::vector<Guides> guides = out.drawn<Guides>();
    model.release(dragged(p3(0.25, 0.5), p3(0.25, 0.5)));
    return guides.empty() || !guides.back().ring ? -1 : guides.back().ring->face;
  };
  const int top = ringFace();
  ASSERT_GE(top, 0);
  model.nextLayer(at(p3(0.25, 0.5)));
  EXPECT_EQ(out.lastSaid(), "Picked layer 2 of 2.");
  const GestureStatus status = model.status();
  EXPECT_EQ(status.picked_layer, 2u);
  EXPECT_EQ(status.layers, 2u);
  ASSERT_GE(status.picked_face, 0);
  EXPECT_NE(status.picked_face, top);
  EXPECT_EQ(out.drawn<Picks>().back().face, status.picked_face);
  EXPECT_EQ(ringFace(), status.picked_face);  // a press where the pick was turns the picked layer
  model.nextLayer(at(p3(0.25, 0.5)));
  EXPECT_EQ(out.lastSaid(), "No layer below this one.");
}

TEST_F(GestureModelTest, TheLayersUnderAPointAreWalkedDownToTheBottomAndUpToTheTop)
{
  load(stackOfLayers(2));  // four layers over [0, .5] × [0, .5], each a face over all of it
  model.chooseMode(GestureMode::Rotate, at(p3(0.25, 0.25)));
  const Pointer here = at(p3(0.2, 0.3));
  std::vector<int> face_of{ -1, -1 };  // the face of each layer from the top (the top not picked yet)
  for (uint32_t layer = 2; layer <= 4; ++layer)
  {
    model.nextLayer(here);
    EXPECT_EQ(out.lastSaid(), "Picked layer " + std::to_string(layer) + " of 4.");
    EXPECT_EQ(model.status().picked_layer, layer);
    face_of.push_back(model.status().picked_face);
  }
  model.nextLayer(here);
  EXPECT_EQ(out.lastSaid(), "No layer below this one.");
  EXPECT_EQ(model.status().picked_layer, 4u);
  for (uint32_t layer = 3; layer >= 1; --layer)
  {
    model.previousLayer(here);
    EXPECT_EQ(out.lastSaid(), "Picked layer " + std::to_string(layer) + " of 4.");
    EXPECT_EQ(model.status().picked_layer, layer);
    if (layer > 1)
      EXPECT_EQ(model.status().picked_face, face_of[layer]) << "layer " << layer;
  }
  face_of[1] = model.status().picked_face;
  EXPECT_EQ(std::set<int>(face_of.begin() + 1, face_of.end()).size(), 4u) << "four different faces";
  EXPECT_GE(face_of[1], 0);
  model.previousLayer(here);
  EXPECT_EQ(out.lastSaid(), "No layer above this one.");
  EXPECT_EQ(model.status().picked_layer, 1u);
  EXPECT_EQ(model.status().picked_face, face_of[1]);
  // The top layer picked is the one a press turns, as a press with nothing picked does.
  out.forget();
  model.press(here);
  const std::vector<Guides> guides = out.drawn<Guides>();
  model.release(dragged(p3(0.2, 0.3), p3(0.2, 0.3)));
  ASSERT_FALSE(guides.empty());
  ASSERT_TRUE(guides.back().ring.has_value());
  EXPECT_EQ(guides.back().ring->face, face_of[1]);
  // Elsewhere, with nothing picked there, up starts from the bottom layer.
  const Pointer elsewhere = at(p3(0.3, 0.2));
  model.previousLayer(elsewhere);
  EXPECT_EQ(out.lastSaid(), "Picked layer 4 of 4.");
  EXPECT_EQ(model.status().picked_layer, 4u);
  EXPECT_EQ(model.status().picked_face, face_of[4]);
  model.previousLayer(elsewhere);
  EXPECT_EQ(model.status().picked_face, face_of[3]);
}

TEST_F(GestureModelTest, MarkedCreasesFoldInFramesThenTheMarksGo)
{
  std::vector<int> left;
  load(creasedInHalf(left));
  model.chooseMode(GestureMode::Fold, at(p3(0.5, 0.5)));
  EXPECT_EQ(model.mode(), GestureMode::Fold);
  click(p3(0.5, 0.3));
  EXPECT_EQ(out.lastSaid(), "Crease valley.");
  click(p3(0.5, 0.3));  // again on it: the next mark
  EXPECT_EQ(out.lastSaid(), "Crease mountain (layer 1 of 1).");
  click(p3(0.5, 0.3));
  click(p3(0.5, 0.3));
  click(p3(0.5, 0.3));  // unfold, none, valley again
  EXPECT_EQ(out.lastSaid(), "Crease valley (layer 1 of 1).");
  model.foldMarks(M_PI, at(p3(0.5, 0.5)));
  EXPECT_EQ(out.lastSaid().rfind("Pick the face that stays first", 0), 0u);
  EXPECT_TRUE(out.requests.empty());
  click(p3(0.2, 0.5));
  EXPECT_EQ(out.lastSaid(), "This face stays (layer 1 of 1).");
  ASSERT_EQ(model.status().marked_edges.size(), 1u);
  EXPECT_DOUBLE_EQ(model.status().marked_angles[0], M_PI);

  model.foldMarks(M_PI, at(p3(0.5, 0.5)));
  EXPECT_EQ(model.state(), GestureState::FoldingMarks);
  for (int frame = 0; frame < 20; ++frame)
    model.tick();
  const std::vector<FlatFoldCall> frames = out.sent<FlatFoldCall>();
  ASSERT_EQ(frames.size(), 8u);  // the default 8 frames, the last one committed
  for (size_t i = 0; i < frames.size(); ++i)
  {
    EXPECT_DOUBLE_EQ(frames[i].fraction, (i + 1) / 8.0);
    EXPECT_EQ(frames[i].commit, i + 1 == frames.size());
    ASSERT_EQ(frames[i].fold.creases.size(), 1u);
    EXPECT_DOUBLE_EQ(frames[i].fold.creases[0].angle, M_PI);
    EXPECT_LT(frames[i].fold.fixed_point.x(), 0.5);  // the left half stays
  }
  EXPECT_EQ(model.state(), GestureState::Idle);
  EXPECT_TRUE(model.status().marked_edges.empty());
}

TEST_F(GestureModelTest, InFlapModeOneDragSquashesAFlapPreviewingAsFarAsThePointerWent)
{
  const Expected<std::vector<Paper>> states = craneStates();
  ASSERT_TRUE(states.ok()) << states.message();
  const Paper& triangle = (*states)[6];
  const FlapDrag flap = flapDrag(*states, 7, Vec2(1.0 / 3, 1.0 / 6));
  load(triangle);
  model.chooseMode(GestureMode::Flap, at(p3(0.5, 0.5)));
  EXPECT_STREQ(modeName(model.mode()), "flap");
  out.forget();
  model.press(at(flap.press));
  EXPECT_EQ(model.state(), GestureState::DraggingFlap);
  EXPECT_TRUE(model.dragging());
  std::vector<Vec3> way;
  for (int i = 1; i <= 4; ++i)
    way.push_back(flap.press + (flap.target - flap.press) * (i / 4.0));
  for (const Vec3& p : way)
  {
    model.move(dragged(flap.press, p));
    model.update();
  }
  const std::vector<FlatFoldCall> calls = out.sent<FlatFoldCall>();
  ASSERT_EQ(calls.size(), 4u);  // a preview per update, none committed yet
  for (size_t i = 0; i < calls.size(); ++i)
  {
    EXPECT_NEAR(calls[i].fraction, (i + 1) / 4.0, 1e-9);
    EXPECT_FALSE(calls[i].commit);
  }
  model.release(dragged(flap.press, way.back()));
  const std::vector<FlatFoldCall> after = out.sent<FlatFoldCall>();
  ASSERT_EQ(after.size(), 5u);
  EXPECT_TRUE(after.back().commit);
  EXPECT_EQ(after.back().fraction, 1.0);
  EXPECT_EQ(out.lastSaid(), "Squash fold.");
  EXPECT_EQ(model.state(), GestureState::Idle);
  // What it commits is the reference's squash (to 1e-6, the face that stays in place).
  Paper folded = triangle;
  ASSERT_TRUE(flatFold(folded, after.back().fold).ok());
  EXPECT_LE(largestOffset(folded, flap.after), 1e-6);
}

TEST_F(GestureModelTest, InFlapModeTheLayerPickedByNextLayerDownIsTheFlapDragged)
{
  const Expected<std::vector<Paper>> states = craneStates();
  ASSERT_TRUE(states.ok()) << states.message();
  const FlapDrag flap = flapDrag(*states, 8, Vec2(5.0 / 6, 2.0 / 3));
  load((*states)[7]);
  model.chooseMode(GestureMode::Flap, at(p3(0.5, 0.5)));
  model.nextLayer(at(flap.press));
  EXPECT_EQ(model.status().picked_face, flap.face);
  out.forget();
  drag(flap.press, { flap.press + 0.5 * (flap.target - flap.press), flap.target });
  const std::vector<FlatFoldCall> calls = out.sent<FlatFoldCall>();
  ASSERT_FALSE(calls.empty());
  ASSERT_TRUE(calls.back().commit);
  Paper folded = (*states)[7];
  ASSERT_TRUE(flatFold(folded, calls.back().fold).ok());
  EXPECT_LE(largestOffset(folded, flap.after), 1e-6);  // the squash underneath, as the reference's
}

TEST_F(GestureModelTest, AFlapLetGoNearWhereItWasFoldsNothingAndTheShownPreviewGoesBack)
{
  const Expected<std::vector<Paper>> states = craneStates();
  ASSERT_TRUE(states.ok()) << states.message();
  const FlapDrag flap = flapDrag(*states, 15, Vec2(0.6911, 0.0589));
  load((*states)[14]);
  model.chooseMode(GestureMode::Flap, at(p3(0.5, 0.5)));
  out.forget();
  drag(flap.press, { flap.press + 0.6 * (flap.target - flap.press), flap.press + 0.2 * (flap.target - flap.press) });
  const std::vector<FlatFoldCall> calls = out.sent<FlatFoldCall>();
  ASSERT_EQ(calls.size(), 3u);  // 60 %, 20 %, then back to none on release
  EXPECT_NEAR(calls[0].fraction, 0.6, 1e-9);
  EXPECT_NEAR(calls[1].fraction, 0.2, 1e-9);
  EXPECT_EQ(calls[2].fraction, 0.0);
  for (const FlatFoldCall& call : calls)
    EXPECT_FALSE(call.commit);
  EXPECT_EQ(out.lastSaid().rfind("Not folded", 0), 0u) << out.lastSaid();
  // A click folds nothing and says how; a press off the paper says so on release.
  out.forget();
  click(flap.press);
  EXPECT_TRUE(out.sent<FlatFoldCall>().empty());
  EXPECT_NE(out.lastSaid().find("drag the flap"), std::string::npos) << out.lastSaid();
  drag(p3(-0.5, -0.5), { p3(-0.2, -0.5) });
  EXPECT_TRUE(out.sent<FlatFoldCall>().empty());
  EXPECT_EQ(out.lastSaid().rfind("No paper here", 0), 0u) << out.lastSaid();
}

TEST_F(GestureModelTest, InFlapModeAReverseFoldGoesInsideUnlessTheOutsideOneIsChosen)
{
  const Expected<std::vector<Paper>> states = craneStates();
  ASSERT_TRUE(states.ok()) << states.message();
  const FlapDrag flap = flapDrag(*states, 15, Vec2(0.6911, 0.0589));
  load((*states)[14]);
  model.chooseMode(GestureMode::Flap, at(p3(0.5, 0.5)));
  drag(flap.press, { flap.target });
  EXPECT_EQ(out.lastSaid(), "Inside reverse fold.");
  const FlatFoldCall inside = out.sent<FlatFoldCall>().back();
  EXPECT_FALSE(model.outsideReverse());
  model.toggleOutsideReverse(at(p3(0.5, 0.5)));
  EXPECT_TRUE(model.outsideReverse());
  out.forget();
  drag(flap.press, { flap.target });
  EXPECT_EQ(out.lastSaid(), "Outside reverse fold.");
  const std::vector<FlatFoldCall> calls = out.sent<FlatFoldCall>();
  ASSERT_EQ(calls.size(), 2u);  // the preview and the commit, both of the outside fold
  // The creases on the line; the inside fold also turned the flap's spine inside out.
  for (const FlatFoldCall& call : calls)
  {
    ASSERT_EQ(call.fold.creases.size() + 1, inside.fold.creases.size());
    for (size_t k = 0; k < call.fold.creases.size(); ++k)
      EXPECT_EQ(call.fold.creases[k].start, inside.fold.creases[k].start);
  }
  // It folds the flap to the same places, wrapped round.
  Paper wrapped = (*states)[14];
  ASSERT_TRUE(flatFold(wrapped, calls.back().fold).ok());
  EXPECT_LE(largestOffset(wrapped, flap.after), 1e-6);
}

TEST_F(GestureModelTest, ANewInputFinishesTheAnimatedFoldAtOnce)
{
  std::vector<int> left;
  load(creasedInHalf(left));
  model.chooseMode(GestureMode::Fold, at(p3(0.5, 0.5)));
  click(p3(0.5, 0.3));
  click(p3(0.2, 0.5));
  model.foldMarks(M_PI / 2, at(p3(0.5, 0.5)));
  model.tick();
  model.finishFold();
  const std::vector<FlatFoldCall> frames = out.sent<FlatFoldCall>();
  ASSERT_EQ(frames.size(), 8u);
  EXPECT_TRUE(frames.back().commit);
  EXPECT_DOUBLE_EQ(frames.back().fold.creases[0].angle, M_PI / 2);
  EXPECT_EQ(model.state(), GestureState::Idle);
}

TEST_F(GestureModelTest, AVertexDragPreviewsThenCommitsWhereTheLastPreviewWent)
{
  load(Paper::square(1.0));
  model.chooseMode(GestureMode::Drag, at(p3(0.5, 0.5)));
  out.forget();
  drag(p3(1.0, 0.0), { p3(1.0, 0.1), p3(0.9, 0.2) });
  const std::vector<DragVertexCall> calls = out.sent<DragVertexCall>();
  ASSERT_EQ(calls.size(), 4u);  // the press's own, two moves, the commit
  const int corner = model.paper()->vertexAt(Vec2(1, 0));
  for (const DragVertexCall& c : calls)
    EXPECT_EQ(c.vertex, corner);
  EXPECT_TRUE(calls[0].position.isApprox(p3(1, 0)));
  EXPECT_TRUE(calls[2].position.isApprox(p3(0.9, 0.2)));
  EXPECT_FALSE(calls[2].commit);
  EXPECT_TRUE(calls[3].commit);
  EXPECT_TRUE(calls[3].position.isApprox(p3(0.9, 0.2)));
}

TEST_F(GestureModelTest, WhereRigidFacesCannotFollowTheCurvedModelBendsThePaperAndLetsGoOnRelease)
{
  load(Paper::square(1.0));
  model.chooseMode(GestureMode::Drag, at(p3(0.5, 0.5)));
  out.forget();
  out.reply = [](const PaperRequest& r) {
    const DragVertexCall& call = std::get<DragVertexCall>(r);
    const bool at_rest = call.position.isApprox(p3(1, 0));
    return PaperReply{ true, at_rest, at_rest ? "" : "the faces cannot follow", 0, !at_rest };
  };
  model.press(at(p3(1.0, 0.0)));
  model.move(dragged(p3(1.0, 0.0), p3(1.0, 0.0, 0.2)));
  model.update();
  EXPECT_EQ(model.state(), GestureState::Bending);
  EXPECT_TRUE(model.status().bending);
  std::vector<CurvedHold> holds = out.drawn<CurvedHold>();
  ASSERT_EQ(holds.size(), 1u);
  EXPECT_EQ(holds[0].vertex, model.paper()->vertexAt(Vec2(1, 0)));
  EXPECT_TRUE(holds[0].target.isApprox(p3(1, 0, 0.2)));
  now += 2.0;
  EXPECT_DOUBLE_EQ(model.timeInState(), 2.0);

  model.release(dragged(p3(1.0, 0.0), p3(1.0, 0.0, 0.2)));
  holds = out.drawn<CurvedHold>();
  ASSERT_GE(holds.size(), 2u);
  EXPECT_EQ(holds.back().vertex, -1);  // let go
  EXPECT_EQ(out.lastSaid(), "Let go: the bent paper springs back, as it was.");
  for (const DragVertexCall& c : out.sent<DragVertexCall>())
    EXPECT_FALSE(c.commit);
  EXPECT_EQ(model.state(), GestureState::Idle);
}

TEST_F(GestureModelTest, TheSliderPreviewsWhileMovingAndCommitsOnRelease)
{
  load(Paper::square(1.0));
  model.slidePress();
  EXPECT_EQ(model.state(), GestureState::Sliding);
  EXPECT_FALSE(model.dragging());  // the sheet is not dragged: its marker may be re-sent
  model.slideMove(0.41234);
  model.update();
  model.slideMove(0.41234);
  model.update();  // the same fraction again: no second preview
  model.slideRelease(0.5);
  const std::vector<FoldByAssignmentCall> calls = out.sent<FoldByAssignmentCall>();
  ASSERT_EQ(calls.size(), 2u);
  EXPECT_DOUBLE_EQ(calls[0].fraction, 0.412);  // to 0.1 %
  EXPECT_TRUE(calls[0].preview);
  EXPECT_DOUBLE_EQ(calls[1].fraction, 0.5);
  EXPECT_FALSE(calls[1].preview);
  EXPECT_DOUBLE_EQ(out.drawn<SliderMoved>().back().fraction, 0.5);
  EXPECT_EQ(model.state(), GestureState::Idle);
}

/// A fast slide's previews fall behind the handle (each one step of the solver). Held still, the
/// handle's previews go on at its fraction while they come nearer, and stop after three that come
/// no nearer; never while the handle moves, nor before it has rested `slider_catch_up_after`.
TEST_F(GestureModelTest, TheSlidersPreviewsCatchUpWithTheHandleWhileItRests)
{
  load(Paper::square(1.0));
  // paper_model's answers, in turn: how far each preview fell short of its fraction (rad).
  const std::vector<double> behind = { 1.6, 0.8, 0.9, 0.4, 0.2, 0.1, 0.05, 0.025, 0.0125, 0.01, 0.0101, 0.01, 0.01 };
  size_t answered = 0;
  out.reply = [&](const PaperRequest& r) {
    PaperReply reply{ true, true, "", 0, false };
    if (std::get<FoldByAssignmentCall>(r).preview)
      reply.angle_error = behind[std::min(answered++, behind.size() - 1)];
    return reply;
  };
  model.slidePress();
  model.slideMove(1.0);
  model.update();
  EXPECT_FALSE(model.catchUpSlider()) << "the handle has only just stopped";
  now += 0.05;
  EXPECT_FALSE(model.catchUpSlider());
  model.slideMove(0.9);
  now += 0.2;
  EXPECT_FALSE(model.catchUpSlider()) << "a move waits for the update, not for a catch-up";
  model.update();
  now += 0.2;
  int caught_up = 0;
  while (model.catchUpSlider() && caught_up < 100)
    ++caught_up;
  // The first catch-up farther (a flick's first steps), then nearer down to 0.01, then three no nearer.
  EXPECT_EQ(caught_up, 11);
  const std::vector<FoldByAssignmentCall> calls = out.sent<FoldByAssignmentCall>();
  ASSERT_EQ(calls.size(), 13u);
  for (size_t k = 1; k < calls.size(); ++k)
  {
    EXPECT_TRUE(calls[k].preview);
    EXPECT_DOUBLE_EQ(calls[k].fraction, 0.9);
  }
  EXPECT_EQ(model.updates(), 2u) << "catching up is no update of the pointer's";
  model.slideRelease(0.9);
  EXPECT_FALSE(out.sent<FoldByAssignmentCall>().back().preview);
  EXPECT_FALSE(model.catchUpSlider()) << "let go";
  // A preview that answers nothing of its distance (an older paper_model) is not followed up.
  out.forget();
  out.reply = nullptr;
  model.slidePress();
  model.slideMove(0.5);
  model.update();
  now += 1.0;
  EXPECT_FALSE(model.catchUpSlider());
  EXPECT_EQ(out.sent<FoldByAssignmentCall>().size(), 1u);
  model.slideRelease(0.5);
}

TEST_F(GestureModelTest, ReleasesKeepRefusedFoldsOnlyWhenTheMenuSaysSo)
{
  load(Paper::square(1.0));
  const auto slide = [&](double fraction) {
    model.slidePress();
    model.slideMove(fraction);
    model.update();
    model.slideRelease(fraction);
    return out.sent<FoldByAssignmentCall>().back();
  };
  const FoldByAssignmentCall refused = slide(0.5);
  EXPECT_FALSE(refused.preview);
  EXPECT_FALSE(refused.keep);
  EXPECT_FALSE(model.keepRefusedFolds());
  model.toggleKeepRefusedFolds(at(p3(0.5, 0.5)));
  EXPECT_TRUE(model.keepRefusedFolds());
  const FoldByAssignmentCall kept = slide(0.75);
  EXPECT_FALSE(kept.preview);
  EXPECT_TRUE(kept.keep);
  model.foldByAssignment(1.0, at(p3(0.5, 0.5)));  // the menu's fractions too
  EXPECT_TRUE(out.sent<FoldByAssignmentCall>().back().keep);
  for (const FoldByAssignmentCall& c : out.sent<FoldByAssignmentCall>())
    if (c.preview)
    {
      EXPECT_FALSE(c.keep) << "a preview is never refused: nothing to keep";
    }
  model.toggleKeepRefusedFolds(at(p3(0.5, 0.5)));
  EXPECT_FALSE(slide(0.25).keep);
}

TEST_F(GestureModelTest, MenuCommandsAndPinsAskPaperModelAndSayItsAnswer)
{
  load(Paper::square(1.0));
  out.reply = [](const PaperRequest&) { return PaperReply{ true, true, "done", 0, false }; };
  model.command(PaperCommand::Undo, at(p3(0.5, 0.5)));
  model.pin(at(p3(0.97, 0.02)), false);
  model.pin(at(p3(0.5, 0.5)), true);  // nothing pinned: nothing to release
  ASSERT_EQ(out.requests.size(), 2u);
  EXPECT_EQ(std::get<CommandCall>(out.requests[0]).command, PaperCommand::Undo);
  const PinCall pin = std::get<PinCall>(out.requests[1]);
  EXPECT_EQ(pin.vertex, model.paper()->vertexAt(Vec2(1, 0)));
  EXPECT_FALSE(pin.release);
  EXPECT_EQ(out.lastSaid(), "no pin near the click");
  out.reply = [](const PaperRequest&) { return PaperReply{ false, false, "undo did not answer", 0, false }; };
  model.command(PaperCommand::Undo, at(p3(0.5, 0.5)));
  EXPECT_EQ(out.lastSaid(), "undo did not answer");
}

TEST_F(GestureModelTest, APaperChangedDuringADragIsShownAfterTheRelease)
{
  load(Paper::square(1.0));
  model.press(at(p3(0.1, 0.5)));
  model.paperChanged(Paper::square(1.0), ++revision, {});
  EXPECT_TRUE(out.drawn<SheetShown>().empty());  // a marker sent now would end the drag in rviz
  model.release(dragged(p3(0.1, 0.5), p3(0.2, 0.5)));
  const std::vector<SheetReleased> released = out.drawn<SheetReleased>();
  ASSERT_EQ(released.size(), 1u);
  EXPECT_TRUE(released[0].reshow);
  model.paperChanged(Paper::square(1.0), ++revision, {});
  EXPECT_EQ(out.drawn<SheetShown>().size(), 1u);
}

namespace
{
/// rviz's camera straight above `over`, `height` up, looking down (x right, y down the picture).
ViewCamera cameraAbove(const Vec3& over, double height)
{
  ViewCamera camera;
  camera.eye = over + Vec3(0, 0, height);
  camera.axes.col(0) = Vec3::UnitX();
  camera.axes.col(2) = -Vec3::UnitZ();
  camera.axes.col(1) = camera.axes.col(2).cross(camera.axes.col(0));
  return camera;
}
}  // namespace

TEST_F(GestureModelTest, WithTheCameraKnownTheCreaseGoesThroughTheLayersTheEyeSees)
{
  load(Paper::square(1.0));
  const ViewCamera camera = cameraAbove(p3(0.5, 0.5), 2.0);
  model.press(Pointer{ p3(0.012, 0.02, 0.004), Vec3::Zero(), camera });
  // The marker moves on the plane facing the eye; the line's end is where the pointer's sight
  // line meets the pressed face's plane.
  model.release(Pointer{ std::nullopt, p3(0.985, 0.99) - p3(0.012, 0.02), camera });
  const std::vector<CreaseCall> creases = out.sent<CreaseCall>();
  ASSERT_EQ(creases.size(), 1u);
  ASSERT_TRUE(creases[0].eye.has_value());
  EXPECT_TRUE(creases[0].eye->isApprox(camera.eye));
  EXPECT_TRUE(creases[0].start.isApprox(p3(0, 0)));
  EXPECT_TRUE(creases[0].end.isApprox(p3(1, 1)));
}

TEST_F(GestureModelTest, ARingSeenEdgeOnTurnsTheViewForTheDragAndBackOnRelease)
{
  load(diagonalSquare());
  model.chooseMode(GestureMode::Rotate, at(p3(0.5, 0.5)));
  out.forget();
  const ViewCamera camera = cameraAbove(p3(0.5, 0.5), 2.0);  // from straight above: edge-on
  model.press(Pointer{ p3(0.8, 0.3, 0.004), Vec3::Zero(), camera });
  ASSERT_EQ(model.state(), GestureState::TurningFace);
  std::vector<ViewTurn> turns = out.drawn<ViewTurn>();
  ASSERT_EQ(turns.size(), 1u);
  ASSERT_TRUE(turns[0].to.has_value());
  // Turned so that the sight line to the press meets the axis (the diagonal) at |cos| ≥ 0.6.
  const Vec3 axis = Vec3(1, 1, 0).normalized();
  EXPECT_GE(std::abs(turns[0].to->rayTo(p3(0.8, 0.3)).dot(axis)), 0.6);
  model.release(Pointer{ std::nullopt, Vec3::Zero(), camera });
  turns = out.drawn<ViewTurn>();
  ASSERT_EQ(turns.size(), 2u);
  EXPECT_FALSE(turns[1].to.has_value());  // back to the view before the turn
}

TEST_F(GestureModelTest, WithoutTheViewTurnSettingTheViewStays)
{
  GestureSettings settings;
  settings.view_turn = false;
  settings.mode = GestureMode::Rotate;
  GestureModel fixed(settings, out, [this] { return now; });
  fixed.paperChanged(diagonalSquare(), 1, {});
  fixed.press(Pointer{ p3(0.8, 0.3, 0.004), Vec3::Zero(), cameraAbove(p3(0.5, 0.5), 2.0) });
  EXPECT_EQ(fixed.state(), GestureState::TurningFace);
  EXPECT_TRUE(out.drawn<ViewTurn>().empty());
}

TEST_F(GestureModelTest, NextLayerDownWalksAStacksCreasesTopFirstFromEitherSideOfTheLine)
{
  // Issue 42: beside a stacked crease of the square base, a click on one side of the line and a
  // click on the other listed its creases in different orders. Clicked 15 mm (8 px) to each side
  // in rviz's default view, then Next layer down to the last layer: the same creases in turn.
  const Expected<std::vector<Paper>> states = craneStates();
  ASSERT_TRUE(states.ok()) << states.message();
  const Paper& square_base = (*states)[8];
  // The line with the most creases on it.
  const auto onLine = [&](int line, int e) {
    const Vec3& a = square_base.vertices[square_base.edges[line].vertices[0]].folded;
    const Vec3 d = (square_base.vertices[square_base.edges[line].vertices[1]].folded - a).normalized();
    for (int v : square_base.edges[e].vertices)
    {
      const Vec3 r = square_base.vertices[v].folded - a;
      if ((r - r.dot(d) * d).norm() > 1e-9)
        return false;
    }
    return square_base.edges[e].isCrease();
  };
  int line = -1, most = 0;
  for (size_t e = 0; e < square_base.edges.size(); ++e)
  {
    int count = 0;
    for (size_t other = 0; other < square_base.edges.size(); ++other)
      count += square_base.edges[e].isCrease() && onLine(static_cast<int>(e), static_cast<int>(other));
    if (count > most)
      std::tie(line, most) = std::make_pair(static_cast<int>(e), count);
  }
  ASSERT_GE(most, 4);  // four layers fold on it
  const double yaw = 4.2, pitch = 0.75;
  ViewCamera view;
  view.eye = Vec3(0.5, 0.45, 0.1) +
             1.7 * Vec3(std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), std::sin(pitch));
  const Vec3 forward = (Vec3(0.5, 0.45, 0.1) - view.eye).normalized();
  const Vec3 right = forward.cross(Vec3::UnitZ()).normalized();
  view.axes << right, forward.cross(right), forward;
  load(square_base);
  model.chooseMode(GestureMode::Fold, at(p3(0.5, 0.5)));
  const Vec3 a = square_base.vertices[square_base.edges[line].vertices[0]].folded;
  const Vec3 b = square_base.vertices[square_base.edges[line].vertices[1]].folded;
  const Vec3 across = Vec3::UnitZ().cross(b - a).normalized();
  std::vector<int> walked[2];
  for (int side = 0; side < 2; ++side)
  {
    const Vec3 beside = 0.5 * (a + b) + (side == 0 ? -0.015 : 0.015) * across + Vec3(0, 0, model.shownLift());
    const Pointer pointer{ beside, Vec3::Zero(), view };
    model.press(pointer);
    model.release(Pointer{ std::nullopt, Vec3::Zero(), view });
    ASSERT_GE(model.status().picked_edge, 0) << out.lastSaid();
    EXPECT_EQ(model.status().picked_layer, 1u);
    EXPECT_TRUE(model.status().marked_edges.empty()) << "a click on a stack only picks";
    for (uint32_t layer = 1; layer <= model.status().layers; ++layer)
    {
      if (layer > 1)
        model.nextLayer(pointer);
      ASSERT_EQ(model.status().picked_layer, layer);
      if (onLine(line, model.status().picked_edge))
        walked[side].push_back(model.status().picked_edge);
    }
    model.nextLayer(pointer);
    EXPECT_EQ(out.lastSaid(), "No layer below this one.");
    model.clearMarks(pointer);  // lets go of the pick
  }
  EXPECT_EQ(walked[0].size(), static_cast<size_t>(most));
  EXPECT_EQ(walked[0], walked[1]);
}

TEST_F(GestureModelTest, WithKeepTheBendABentDragLetGoKeepsTheSheetBeforeTheCurvedModelLetsGo)
{
  load(Paper::square(1.0));
  model.chooseMode(GestureMode::Drag, at(p3(0.5, 0.5)));
  model.toggleKeepBend(at(p3(0.5, 0.5)));
  EXPECT_TRUE(model.keepBend());
  out.forget();
  int holds_when_kept = -1;
  bool last_held_when_kept = false;
  out.reply = [&](const PaperRequest& r) {
    if (const CommandCall* c = std::get_if<CommandCall>(&r))
    {
      EXPECT_EQ(c->command, PaperCommand::KeepBend);
      const std::vector<CurvedHold> holds = out.drawn<CurvedHold>();
      holds_when_kept = static_cast<int>(holds.size());
      last_held_when_kept = !holds.empty() && holds.back().vertex >= 0;
      return PaperReply{ true, true, "kept the bend: 1 face bent into 40 triangles", 0, false };
    }
    const DragVertexCall& call = std::get<DragVertexCall>(r);
    const bool at_rest = call.position.isApprox(p3(1, 0));
    return PaperReply{ true, at_rest, at_rest ? "" : "the faces cannot follow", 0, !at_rest };
  };
  model.press(at(p3(1.0, 0.0)));
  model.move(dragged(p3(1.0, 0.0), p3(1.0, 0.0, 0.2)));
  model.update();
  ASSERT_EQ(model.state(), GestureState::Bending);
  model.release(dragged(p3(1.0, 0.0), p3(1.0, 0.0, 0.2)));
  // Kept while the curved model still held the sheet, then let go; no drag committed.
  ASSERT_EQ(out.sent<CommandCall>().size(), 1u);
  EXPECT_GE(holds_when_kept, 1);
  EXPECT_TRUE(last_held_when_kept) << "the curved model was let go before the bend was kept";
  EXPECT_EQ(out.drawn<CurvedHold>().back().vertex, -1);
  EXPECT_EQ(out.lastSaid(), "Kept the bend: 1 face bent into 40 triangles.");
  for (const DragVertexCall& c : out.sent<DragVertexCall>())
    EXPECT_FALSE(c.commit);
  EXPECT_EQ(model.state(), GestureState::Idle);

  // Refused: said, and the paper springs back as without the entry.
  out.forget();
  out.reply = [&](const PaperRequest& r) {
    if (std::holds_alternative<CommandCall>(r))
      return PaperReply{ true, false, "the bend is not kept: nothing bent", 0, false };
    const DragVertexCall& call = std::get<DragVertexCall>(r);
    const bool at_rest = call.position.isApprox(p3(1, 0));
    return PaperReply{ true, at_rest, at_rest ? "" : "the faces cannot follow", 0, !at_rest };
  };
  model.press(at(p3(1.0, 0.0)));
  model.move(dragged(p3(1.0, 0.0), p3(1.0, 0.0, 0.2)));
  model.update();
  model.release(dragged(p3(1.0, 0.0), p3(1.0, 0.0, 0.2)));
  EXPECT_EQ(out.lastSaid(),
            "Let go: the bent paper springs back, as it was. The bend is not kept: nothing bent.");

  // Unchecked: no keeping asked.
  model.toggleKeepBend(at(p3(0.5, 0.5)));
  EXPECT_FALSE(model.keepBend());
  out.forget();
  model.press(at(p3(1.0, 0.0)));
  model.move(dragged(p3(1.0, 0.0), p3(1.0, 0.0, 0.2)));
  model.update();
  model.release(dragged(p3(1.0, 0.0), p3(1.0, 0.0, 0.2)));
  EXPECT_TRUE(out.sent<CommandCall>().empty());
  EXPECT_EQ(out.lastSaid(), "Let go: the bent paper springs back, as it was.");
}
