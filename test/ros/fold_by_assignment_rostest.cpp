// rostest: folding a loaded Miura-ori by assignment, through the service and through the
// interaction node's slider driven as rviz drives it (InteractiveMarkerFeedback on the server's
// feedback topic); checked on `state`, `operations` and `markers`.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>

#include <nlohmann/json.hpp>
#include <virtual_origami/FoldByAssignment.h>
#include <virtual_origami/InteractionStatus.h>
#include <virtual_origami/Load.h>
#include <virtual_origami/Operation.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>
#include <visualization_msgs/InteractiveMarkerInit.h>
#include <visualization_msgs/MarkerArray.h>

#include "ros_test_client.h"
#include "virtual_origami/core/data_folder.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/fold_slider.h"
#include "virtual_origami/ros/mouse_feedback.h"
#include "virtual_origami/ros/operation_client.h"
#include "virtual_origami/ros/recording.h"
#include "virtual_origami/ros/replay.h"
#include "virtual_origami/ros/strain_colours.h"

using namespace virtual_origami;
using virtual_origami::test::PaperClient;
using virtual_origami::test::waitFor;
using visualization_msgs::InteractiveMarkerFeedback;

namespace
{
/// A 4 × 3 Miura-ori as a designer's FOLD file: assignments, no fold angles (so every crease is
/// driven to ±180° by its assignment), written into the model's data folder.
/// A crease pattern as a designer's FOLD file in the data folder; its name there.
std::string writePattern(const core::Paper& paper, const std::string& stem)
{
  nlohmann::json fold;
  fold["file_spec"] = 1.1;
  fold["frame_classes"] = { "creasePattern" };
  for (const core::Vertex& v : paper.vertices)
    fold["vertices_coords"].push_back({ v.crease_pattern.x(), v.crease_pattern.y() });
  for (const core::Edge& e : paper.edges)
  {
    fold["edges_vertices"].push_back({ e.vertices[0], e.vertices[1] });
    fold["edges_assignment"].push_back(std::string(1, core::assignmentLetter(e.assignment)));
  }
  for (const core::Face& f : paper.faces)
    fold["faces_vertices"].push_back(f.vertices);
  const std::string name = stem + "_" + std::to_string(::getpid()) + ".fold";
  std::ofstream(core::defaultDataFolder() + "/" + name) << fold.dump();
  return name;
}

std::string writeMiura()
{
  const core::Expected<core::Tessellation> miura = core::miuraTessellation(4, 3);
  EXPECT_TRUE(miura.ok()) << miura.message();
  return writePattern(miura->paper, "miura");
}

/// Driven creases (M or V) of a state: angle and the sign its assignment folds to.
struct Driven
{
  double angle = 0.0;
  double sign = 0.0;
};
std::vector<Driven> drivenCreases(const PaperState& s)
{
  std::vector<Driven> driven;
  for (const auto& e : s.edges)
    if (e.face_left >= 0 && e.face_right >= 0 && (e.assignment == "M" || e.assignment == "V"))
      driven.push_back({ e.fold_angle, e.assignment == "V" ? 1.0 : -1.0 });
  return driven;
}

/// The fraction f of ±π that best fits the driven creases' angles (least squares).
double fittedFraction(const PaperState& s)
{
  double fit = 0.0, norm = 0.0;
  for (const Driven& d : drivenCreases(s))
  {
    fit += d.angle * d.sign * M_PI;
    norm += M_PI * M_PI;
  }
  return norm > 0 ? fit / norm : 0.0;
}

class FoldByAssignmentTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    ops_sub_ = client_.nh().subscribe<Operation>("operations", 100, [this](const Operation::ConstPtr& op) {
      operations_.push_back(*op);
    });
    states_sub_ = client_.nh().subscribe<PaperState>("state", 100, [this](const PaperState::ConstPtr& s) {
      states_.push_back(*s);
    });
    markers_sub_ = client_.nh().subscribe<visualization_msgs::MarkerArray>(
        "markers", 100, [this](const visualization_msgs::MarkerArray::ConstPtr& array) {
          for (const auto& m : array->markers)
            if (m.ns == "front")
            {
              front_ = m;
              ++fronts_;
            }
        });
    slider_sub_ = client_.nh().subscribe<visualization_msgs::MarkerArray>(
        "fold_slider_markers", 100, [this](const visualization_msgs::MarkerArray::ConstPtr& array) {
          for (const auto& m : array->markers)
            slider_[m.ns] = m;
        });
    init_sub_ = client_.nh().subscribe<visualization_msgs::InteractiveMarkerInit>(
        "interaction/update_full", 10,
        [this](const visualization_msgs::InteractiveMarkerInit::ConstPtr& init) { init_ = *init; });
    status_sub_ = client_.nh().subscribe<InteractionStatus>(
        "interaction_status", 100, [this](const InteractionStatus::ConstPtr& s) {
          status_ = *s;
          ++statuses_;
        });
    feedback_pub_ = client_.nh().advertise<InteractiveMarkerFeedback>("interaction/feedback", 1000);
    ASSERT_TRUE(waitFor([&] { return ops_sub_.getNumPublishers() > 0 && markers_sub_.getNumPublishers() > 0; }, 30));
    ASSERT_TRUE(waitFor([&] { return feedback_pub_.getNumSubscribers() > 0; }, 30));

    Load::Request load;
    load.path = writeMiura();
    const Load loaded = client_.call<Load>("load", load);
    ASSERT_TRUE(loaded.response.success) << loaded.response.message;
    ASSERT_TRUE(waitFor([&] { return !operations_.empty() && operations_.back().type == "load"; }));
    base_ = operations_.back().revision;
    flat_ = client_.stateAt(base_);
    ASSERT_GT(drivenCreases(flat_).size(), 10u);
    operations_.clear();
  }

  FoldByAssignment fold(double fraction, bool preview = false, bool keep = false)
  {
    FoldByAssignment::Request request;
    request.fraction = fraction;
    request.preview = preview;
    request.keep = keep;
    return client_.call<FoldByAssignment>("fold_by_assignment", request);
  }

  /// A refused request: success false, a message, the revision and the paper as they were.
  void expectRefused(const FoldByAssignment& refused, const PaperState& before)
  {
    EXPECT_FALSE(refused.response.success);
    EXPECT_FALSE(refused.response.message.empty());
    EXPECT_EQ(refused.response.revision, before.revision);
    ros::WallDuration(0.3).sleep();
    ros::spinOnce();
    EXPECT_EQ(client_.state().revision, before.revision);
    EXPECT_EQ(client_.state().vertices_folded, before.vertices_folded);
    EXPECT_EQ(client_.state().edges, before.edges);
  }

  /// The interactive marker of that name from the server's full update, once it is at `revision`.
  std::optional<visualization_msgs::InteractiveMarker> interactiveMarker(const std::string& name)
  {
    for (const auto& m : init_.markers)
      if (m.name == name)
        return m;
    return std::nullopt;
  }

  /// The id of the menu entry whose title contains `title`.
  int menuEntry(const std::string& title)
  {
    int id = -1;
    waitFor([&] {
      const auto paper = interactiveMarker("paper");
      if (paper)
        for (const auto& entry : paper->menu_entries)
          if (entry.title.find(title) != std::string::npos)
            id = static_cast<int>(entry.id);
      return id >= 0;
    });
    return id;
  }

  void send(const InteractiveMarkerFeedback& f)
  {
    feedback_pub_.publish(f);
    ros::spinOnce();
  }

  InteractiveMarkerFeedback sliderFeedback(uint8_t type, const core::Vec3& at)
  {
    InteractiveMarkerFeedback f;
    f.header.frame_id = "paper";
    f.header.stamp = ros::Time::now();
    f.client_id = "/mouse";
    f.marker_name = "fold_slider";
    f.control_name = "slide";
    f.event_type = type;
    f.pose.position = toPoint(at);
    f.pose.orientation.w = 1.0;
    f.mouse_point = toPoint(at);
    f.mouse_point_valid = type != InteractiveMarkerFeedback::POSE_UPDATE;
    return f;
  }

  /// The node handled everything sent so far.
  void settle()
  {
    const int seen = statuses_;
    ASSERT_TRUE(waitFor([&] { return statuses_ > seen + 1 && status_.pending == 0 && !status_.dragging; }, 30));
  }

  std::vector<Operation> foldsPublished() const
  {
    std::vector<Operation> folds;
    for (const Operation& op : operations_)
      if (op.type == "fold_by_assignment")
        folds.push_back(op);
    return folds;
  }

  PaperClient client_;
  ros::Subscriber ops_sub_, states_sub_, markers_sub_, slider_sub_, init_sub_, status_sub_;
  ros::Publisher feedback_pub_;
  std::vector<Operation> operations_;
  std::vector<PaperState> states_;
  visualization_msgs::Marker front_;
  int fronts_ = 0;
  std::map<std::string, visualization_msgs::Marker> slider_;
  visualization_msgs::InteractiveMarkerInit init_;
  InteractionStatus status_;
  int statuses_ = 0;
  PaperState flat_;
  uint64_t base_ = 0;
};
}  // namespace

TEST_F(FoldByAssignmentTest, TheSliderFoldsToHalfWithOneHistoryEntry)
{
  // The handle at 0 % beside the flat pattern, the track on `fold_slider_markers`.
  ASSERT_TRUE(waitFor([&] {
    return interactiveMarker("fold_slider").has_value() && slider_.count("fold_slider_track") &&
           slider_["fold_slider_track"].points.size() >= 2;
  })) << "no fold slider";
  const auto handle = *interactiveMarker("fold_slider");
  ASSERT_EQ(handle.controls.size(), 1u);
  EXPECT_EQ(handle.controls[0].interaction_mode, visualization_msgs::InteractiveMarkerControl::MOVE_AXIS);
  // The track runs from −100 % (the opposite assignment) to 100 %; 0 % is its middle.
  const core::Vec3 track_start = toVec3(slider_["fold_slider_track"].points[0]);
  const core::Vec3 end = toVec3(slider_["fold_slider_track"].points[1]);
  const core::Vec3 start = 0.5 * (track_start + end);
  EXPECT_NEAR((toVec3(handle.pose.position) - start).norm(), 0.0, 1e-9) << "a flat pattern is at 0 %";
  // Beside the sheet, not over it.
  double lowest_y = INFINITY;
  for (const auto& p : flat_.vertices_crease_pattern)
    lowest_y = std::min(lowest_y, p.y);
  EXPECT_LT(start.y(), lowest_y);

  const int fronts_before = fronts_;
  send(sliderFeedback(InteractiveMarkerFeedback::MOUSE_DOWN, start));
  for (int i = 1; i <= 10; ++i)
  {
    ros::WallDuration(0.03).sleep();
    send(sliderFeedback(InteractiveMarkerFeedback::POSE_UPDATE, start + (end - start) * (0.05 * i)));
  }
  // While sliding: previews drawn, the percent shown, nothing committed.
  ASSERT_TRUE(waitFor([&] { return slider_["fold_slider_percent"].text == "fold 50 %"; }, 30))
      << slider_["fold_slider_percent"].text;
  ASSERT_TRUE(waitFor([&] { return fronts_ > fronts_before; }, 30)) << "no preview drawn";
  EXPECT_TRUE(waitFor([&] {
    for (const auto& p : front_.points)
      if (std::abs(p.z) > 0.05)
        return true;
    return false;
  }, 30)) << "the previews show no fold";
  EXPECT_EQ(client_.state().revision, base_);
  EXPECT_TRUE(foldsPublished().empty());

  send(sliderFeedback(InteractiveMarkerFeedback::MOUSE_UP, start + (end - start) * 0.5));
  settle();
  const PaperState& folded = client_.stateAt(base_ + 1);
  ASSERT_TRUE(waitFor([&] { return !foldsPublished().empty(); }));
  ros::WallDuration(0.5).sleep();
  ros::spinOnce();
  const std::vector<Operation> folds = foldsPublished();
  ASSERT_EQ(folds.size(), 1u) << "one history entry for the whole slide";
  EXPECT_EQ(folds[0].fraction, 0.5);
  EXPECT_EQ(folds[0].revision, base_ + 1);
  EXPECT_EQ(client_.state().revision, base_ + 1);

  // Every driven crease went its assigned way, towards its target and not past it; together
  // they are about half way.
  for (const Driven& d : drivenCreases(folded))
  {
    EXPECT_GT(d.angle * d.sign, 0.0);
    EXPECT_LT(std::abs(d.angle), M_PI);
  }
  EXPECT_NEAR(fittedFraction(folded), 0.5, 0.1);
  // The handle stays at what was committed.
  ASSERT_TRUE(waitFor([&] {
    const auto now = interactiveMarker("fold_slider");
    return now && (toVec3(now->pose.position) - (start + 0.5 * (end - start))).norm() < 1e-9;
  }));
}

// The slider's previews go on one kept connection to paper_model: when paper_model dies and
// comes back (the launch respawns it), the next slide is previewed all the same.
TEST_F(FoldByAssignmentTest, TheSliderPreviewsAgainAfterPaperModelCameBack)
{
  ASSERT_TRUE(waitFor([&] {
    return interactiveMarker("fold_slider").has_value() && slider_.count("fold_slider_track") &&
           slider_["fold_slider_track"].points.size() >= 2;
  })) << "no fold slider";
  const core::Vec3 end = toVec3(slider_["fold_slider_track"].points[1]);
  const core::Vec3 start = 0.5 * (toVec3(slider_["fold_slider_track"].points[0]) + end);
  const auto at = [&](double fraction) { return core::Vec3(start + (end - start) * fraction); };
  const auto highest = [&] {
    double z = 0.0;
    for (const auto& p : front_.points)
      z = std::max(z, std::abs(p.z));
    return z;
  };
  // A slide to 10 %, previewed on the kept connection, released.
  int fronts_before = fronts_;
  send(sliderFeedback(InteractiveMarkerFeedback::MOUSE_DOWN, at(0.0)));
  send(sliderFeedback(InteractiveMarkerFeedback::POSE_UPDATE, at(0.1)));
  ASSERT_TRUE(waitFor([&] { return fronts_ > fronts_before; }, 30)) << "no preview drawn";
  send(sliderFeedback(InteractiveMarkerFeedback::MOUSE_UP, at(0.1)));
  settle();
  ASSERT_TRUE(waitFor([&] { return client_.state().revision == base_ + 1; }, 30));

  test::crash("paper_model");
  // Back with the session as it was, drawn again.
  ASSERT_TRUE(waitFor([&] { return fronts_ > fronts_before + 2 && client_.state().revision == base_ + 1; }, 60));
  ros::WallDuration(1.0).sleep();
  ros::spinOnce();
  const double committed = highest();
  ASSERT_GT(committed, 0.0);

  // The next slide, from 10 % to 30 %: previewed, higher than the committed 10 %.
  fronts_before = fronts_;
  send(sliderFeedback(InteractiveMarkerFeedback::MOUSE_DOWN, at(0.1)));
  send(sliderFeedback(InteractiveMarkerFeedback::POSE_UPDATE, at(0.3)));
  EXPECT_TRUE(waitFor([&] { return fronts_ > fronts_before && highest() > 1.5 * committed; }, 30))
      << "no preview after paper_model came back: " << status_.message;
  EXPECT_EQ(client_.state().revision, base_ + 1) << "a preview commits nothing";
  send(sliderFeedback(InteractiveMarkerFeedback::MOUSE_UP, at(0.3)));
  settle();
  EXPECT_TRUE(waitFor([&] { return client_.state().revision == base_ + 2; }, 60)) << "the release committed nothing";
}

TEST_F(FoldByAssignmentTest, TheServiceRefusesBadInputAndChangesNothing)
{
  for (double fraction : { std::numeric_limits<double>::quiet_NaN(), -1.5, 1.5 })
    for (bool preview : { false, true })
    {
      const FoldByAssignment refused = fold(fraction, preview);
      expectRefused(refused, flat_);
      EXPECT_NE(refused.response.message.find("fraction"), std::string::npos) << refused.response.message;
    }
  // An unfolded square has no crease to drive.
  ASSERT_TRUE(client_.trigger("reset").response.success);
  const PaperState square = client_.stateAt(base_ + 1);
  expectRefused(fold(0.5), square);
  expectRefused(fold(0.5, true), square);
  ros::spinOnce();
  EXPECT_TRUE(foldsPublished().empty());
}

TEST_F(FoldByAssignmentTest, AStrainedFoldIsRefusedWithItsFiguresAndKeptOnRequest)
{
  // A square twist cannot fold half way with rigid faces (strain ≈ 2e-3, over the 1e-3 bound).
  Load::Request load;
  load.path = writePattern(core::squareTwistTessellation(2, 2).value().paper, "square_twist");
  const Load loaded = client_.call<Load>("load", load);
  ASSERT_TRUE(loaded.response.success) << loaded.response.message;
  const PaperState flat = client_.stateAt(base_ + 1);
  const FoldByAssignment refused = fold(0.5);
  expectRefused(refused, flat);
  EXPECT_GT(refused.response.max_strain, 1e-3);
  EXPECT_FALSE(refused.response.rigid);
  EXPECT_NE(refused.response.message.find("the faces would stretch"), std::string::npos) << refused.response.message;
  const FoldByAssignment kept = fold(0.5, false, true);
  ASSERT_TRUE(kept.response.success) << kept.response.message;
  EXPECT_EQ(kept.response.revision, flat.revision + 1);
  EXPECT_NEAR(kept.response.max_strain, refused.response.max_strain, 1e-6);
  EXPECT_NE(kept.response.message.find("kept as asked"), std::string::npos) << kept.response.message;
  EXPECT_EQ(kept.response.crossings, 0);
}

TEST_F(FoldByAssignmentTest, ANegativeFractionFoldsEveryCreaseTheOtherWay)
{
  const FoldByAssignment folded = fold(-0.4);
  ASSERT_TRUE(folded.response.success) << folded.response.message;
  EXPECT_EQ(folded.response.creases_against_target, 0);
  const PaperState state = client_.stateAt(folded.response.revision);
  int opposite = 0;
  for (const Driven& d : drivenCreases(state))
  {
    EXPECT_LT(d.angle * d.sign, 0.0) << "every driven crease folds against its assignment's sign";
    opposite += d.angle * d.sign < -0.1 ? 1 : 0;
  }
  EXPECT_GT(opposite, 10);
  // The assignments are the file's still, and the fold reads as the opposite assignment's.
  EXPECT_EQ(drivenCreases(state).size(), drivenCreases(flat_).size());
  EXPECT_LT(fittedFraction(state), -0.1);
}

TEST_F(FoldByAssignmentTest, ASlideReleasedCommitsBalancedAndItsReplayIsBitForBit)
{
  // The slider's path: previews 5 % apart to 60 %, then the release commits from the last.
  for (int percent = 5; percent <= 60; percent += 5)
  {
    const FoldByAssignment preview = fold(0.01 * percent, true);
    ASSERT_TRUE(preview.response.success) << preview.response.message;
    EXPECT_EQ(preview.response.revision, base_);
  }
  const FoldByAssignment committed = fold(0.6);
  ASSERT_TRUE(committed.response.success) << committed.response.message;
  EXPECT_EQ(committed.response.revision, base_ + 1);
  // A Miura-ori is a mechanism: the commit closes its faces exactly (spring_solver's newton).
  EXPECT_TRUE(committed.response.rigid) << committed.response.message;
  EXPECT_LE(committed.response.max_strain, 1e-9);
  EXPECT_GE(committed.response.angle_error, 0.0);
  const PaperState first = client_.stateAt(base_ + 1);
  ASSERT_TRUE(waitFor([&] { return foldsPublished().size() == 1; }));
  const Operation recorded = foldsPublished()[0];
  EXPECT_EQ(recorded.fraction, 0.6);
  // The recording carries where the commit ended.
  EXPECT_EQ(recorded.folded, first.vertices_folded);

  // Undo, then the recorded operation applied again as a replay does: it takes the result.
  ASSERT_TRUE(client_.trigger("undo").response.success);
  client_.stateAt(base_ + 2);
  OperationClient replay("/origami");
  const core::Status applied = replay.apply(recorded);
  ASSERT_TRUE(applied.ok()) << applied.message();
  const PaperState again = client_.stateAt(base_ + 3);
  EXPECT_EQ(again.vertices_folded, first.vertices_folded);

  // A recorded result of another paper, or as a preview, is refused and changes nothing.
  FoldByAssignment::Request wrong;
  wrong.fraction = 0.6;
  wrong.positions = recorded.folded;
  wrong.positions.pop_back();
  expectRefused(client_.call<FoldByAssignment>("fold_by_assignment", wrong), again);
  wrong.positions = recorded.folded;
  wrong.preview = true;
  expectRefused(client_.call<FoldByAssignment>("fold_by_assignment", wrong), again);
}

TEST_F(FoldByAssignmentTest, AnAnimatedReplayOfTheRecordedFoldsEndsInTheRecordedState)
{
  ASSERT_TRUE(fold(0.4).response.success);
  ASSERT_TRUE(fold(0.8).response.success);
  ASSERT_TRUE(client_.trigger("undo").response.success);
  const PaperState expected = client_.stateAt(base_ + 3);
  ASSERT_TRUE(waitFor([&] { return operations_.size() == 3u; }));

  // As the recorder keeps it: the operations since the load, and the states around them.
  Recording recording;
  recording.operations = operations_;
  recording.states = states_;
  for (const PaperState& s : states_)
    if (s.revision == base_)
      recording.initial_state = s;
  ASSERT_TRUE(recording.initial_state.has_value());
  const int fronts_before = fronts_;
  OperationClient client("/origami");
  ReplayOptions options;
  options.speed = 20.0;  // animated, quickly
  options.animation_steps = 4;
  const core::Status replayed = replay(recording, client, options);
  ASSERT_TRUE(replayed.ok()) << replayed.message();
  // Load, two folds each shown through three previews and their commit, undo: 10 drawings.
  EXPECT_TRUE(waitFor([&] { return fronts_ - fronts_before >= 10; })) << fronts_ - fronts_before;
  ASSERT_TRUE(waitFor([&] { return client_.state().revision == base_ + 7; }));
  const PaperState& got = client_.state();
  ASSERT_EQ(got.vertices_folded.size(), expected.vertices_folded.size());
  for (size_t v = 0; v < got.vertices_folded.size(); ++v)
  {
    EXPECT_NEAR(got.vertices_folded[v].x, expected.vertices_folded[v].x, 1e-9);
    EXPECT_NEAR(got.vertices_folded[v].y, expected.vertices_folded[v].y, 1e-9);
    EXPECT_NEAR(got.vertices_folded[v].z, expected.vertices_folded[v].z, 1e-9);
  }
}

TEST_F(FoldByAssignmentTest, TheMenuFoldsAllTheWayAndColoursByStrain)
{
  const int full = menuEntry("100 %");
  ASSERT_GE(full, 0) << "no menu entry Fold by assignment > 100 %";
  MouseGesture gesture;
  send(gesture.menu(static_cast<uint32_t>(full), core::Vec3(1, 1, 0), ros::Time::now()));
  settle();
  client_.stateAt(base_ + 1);
  ASSERT_TRUE(waitFor([&] { return foldsPublished().size() == 1; }, 30));
  EXPECT_EQ(foldsPublished()[0].fraction, 1.0);

  // Strain colours: one colour per point of the faces when on, none when off again.
  const int strain = menuEntry("Colour by strain");
  ASSERT_GE(strain, 0);
  send(gesture.menu(static_cast<uint32_t>(strain), core::Vec3(1, 1, 0), ros::Time::now()));
  settle();
  EXPECT_TRUE(waitFor([&] { return !front_.points.empty() && front_.colors.size() == front_.points.size(); }, 10))
      << front_.colors.size() << " colours for " << front_.points.size() << " points";
  send(gesture.menu(static_cast<uint32_t>(strain), core::Vec3(1, 1, 0), ros::Time::now()));
  settle();
  EXPECT_TRUE(waitFor([&] { return !front_.points.empty() && front_.colors.empty(); }, 10));
}

TEST(StrainColours, BlueWithoutStrainRedAtTheScaleAndBeyond)
{
  const auto expectColour = [](const std_msgs::ColorRGBA& c, float r, float g, float b) {
    EXPECT_FLOAT_EQ(c.r, r);
    EXPECT_FLOAT_EQ(c.g, g);
    EXPECT_FLOAT_EQ(c.b, b);
    EXPECT_FLOAT_EQ(c.a, 1.0f);
  };
  expectColour(strainColour(0.0, 1e-2), 0, 0, 1);
  expectColour(strainColour(0.25e-2, 1e-2), 0, 1, 1);  // a quarter: cyan
  expectColour(strainColour(0.5e-2, 1e-2), 0, 1, 0);   // half: green
  expectColour(strainColour(0.75e-2, 1e-2), 1, 1, 0);  // three quarters: yellow
  expectColour(strainColour(1e-2, 1e-2), 1, 0, 0);
  expectColour(strainColour(5.0, 1e-2), 1, 0, 0);
  expectColour(strainColour(INFINITY, 1e-2), 1, 0, 0);
  expectColour(strainColour(NAN, 1e-2), 1, 0, 1);  // magenta: nothing else is
  // From blue to red the red part never falls and the blue part never rises.
  std_msgs::ColorRGBA last = strainColour(0.0, 1.0);
  for (int i = 1; i <= 100; ++i)
  {
    const std_msgs::ColorRGBA c = strainColour(i / 100.0, 1.0);
    EXPECT_GE(c.r, last.r);
    EXPECT_LE(c.b, last.b);
    last = c;
  }
}

TEST(FoldSlider, TheTrackLiesBesideTheCreasePatternAndMapsOntoMinusOneToOne)
{
  const core::Expected<core::Tessellation> miura = core::miuraTessellation(4, 3);
  ASSERT_TRUE(miura.ok()) << miura.message();
  const core::Paper& paper = miura->paper;
  const SliderTrack track = sliderTrack(paper, SliderStyle{});
  double lo_x = INFINITY, hi_x = -INFINITY, lo_y = INFINITY;
  for (const core::Vertex& v : paper.vertices)
  {
    lo_x = std::min(lo_x, v.crease_pattern.x());
    hi_x = std::max(hi_x, v.crease_pattern.x());
    lo_y = std::min(lo_y, v.crease_pattern.y());
  }
  EXPECT_NEAR(track.start.x(), lo_x, 1e-12);
  EXPECT_NEAR(track.end.x(), hi_x, 1e-12);
  EXPECT_NEAR(track.start.y(), lo_y - 0.15 * paper.scale(), 1e-12);
  EXPECT_EQ(sliderFraction(track, track.start), -1.0);  // the opposite assignment
  EXPECT_EQ(sliderFraction(track, 0.5 * (track.start + track.end)), 0.0);
  EXPECT_EQ(sliderFraction(track, track.end), 1.0);
  EXPECT_NEAR(sliderFraction(track, sliderPoint(track, 0.37) + core::Vec3(0, 0.2, 0.3)), 0.37, 1e-12);
  EXPECT_NEAR(sliderFraction(track, sliderPoint(track, -0.6) + core::Vec3(0, 0.2, 0.3)), -0.6, 1e-12);
  EXPECT_EQ(sliderFraction(track, track.start - (track.end - track.start)), -1.0);  // clamped
  EXPECT_EQ(sliderFraction(track, track.end + (track.end - track.start)), 1.0);
  EXPECT_EQ(sliderFraction(track, core::Vec3(NAN, 0, 0)), 0.0);

}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "fold_by_assignment_rostest");
  ros::NodeHandle keep_alive;
  return RUN_ALL_TESTS();
}
