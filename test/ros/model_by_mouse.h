// A model folded by mouse through the interaction node alone, step by step against the model a
// reference script folds, as a walkthrough of docs/INTERACTION.md says (test/unit/
// crane_walkthrough.h reads it). Used by the rostests crane_by_mouse, crane_by_tool,
// flapping_bird_by_mouse and frog_base_by_mouse.
//
// How to use it:
//   class BirdByMouse : public virtual_origami::test::ModelByMouse
//   {
//   public:
//     BirdByMouse() : ModelByMouse(virtual_origami::test::MouseDriver::Markers) {}  // or ::Tool
//   };
//   TEST_F(BirdByMouse, FoldsAsTheWalkthroughSays)
//   {
//     foldAsTheWalkthroughSays(reference_json, interaction_md, "## Fold a flapping bird");
//   }
// The launch file starts paper_model (resume false), spring_solver and interaction in the
// namespace `origami`, the test node in it too (as test/ros/crane_by_mouse.test does).
//
// `foldAsTheWalkthroughSays` folds the script's steps (a test/data/*_reference.json: creases,
// half turns, flat folds) by gestures only: a crease by one drag (*Snap the line* off for a line
// off the snapping guides), a half turn by one drag in rotate mode, a flat fold by the flap drag
// the walkthrough names for its step (`**N**: press at (x, y) ... *squash fold*`) or by the marks
// it names (`**N**: ... *valley* ×3`), the face that stays and *Fold flat* / *Fold to a right
// angle*. After every step the paper equals the script's to 1e-6 after a rigid fit; each row's
// gestures are counted against the row's number (`gestures` for the markers, the `tool` column
// for the Fold tool) and the total against "**N gestures**" (the markers) or "**N gestures with
// the Fold tool**" in the text before the table. Afterwards `gestures()`, `issuedOperations()`
// (what the gestures made paper_model do), `menuChoices()` and `longestFlapUpdate()` tell more.
//
// The driver: MouseDriver::Markers sends what rviz's Interact tool sends (InteractiveMarkerFeedback
// on `interaction/feedback`: presses, drags, releases, menu selections); MouseDriver::Tool sends
// what the rviz tool virtual_origami/Fold sends (ToolEvent on `tool_events`: PRESS, MOVE, RELEASE
// looking straight down at the planned point from above, number keys for the modes, the wheel for
// the next layer down and up, Enter for *Fold flat*) and the menu by marker feedback only for what
// the tool has no key for (*Snap the line*, *Keep the face here*, *Fold to a right angle*). Each
// key press, wheel notch, click, drag and menu selection is one gesture.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>
#include <virtual_origami/Operation.h>

#include <virtual_origami/InteractionStatus.h>
#include <virtual_origami/ToolEvent.h>
#include <visualization_msgs/InteractiveMarkerInit.h>

#include "../unit/crane_walkthrough.h"
#include "../unit/rigid_fit.h"
#include "ros_test_client.h"
#include "virtual_origami/core/chosen_creases.h"
#include "virtual_origami/core/compound_fold.h"
#include "virtual_origami/core/drag.h"
#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/core/geometry.h"
#include "virtual_origami/core/kinematics.h"
#include "virtual_origami/core/layer_pick.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/mouse_feedback.h"
#include "virtual_origami/solvers/solver_factory.h"

namespace virtual_origami::test
{
/// What sends the gestures: rviz's Interact tool on the sheet marker, or the Fold tool.
enum class MouseDriver
{
  Markers,
  Tool,
};

using core::test::rigidFitDistance;

/// The crease edges lying on a crease-pattern segment (as flat_fold names them).
inline std::vector<int> creasesOn(const core::Paper& paper, const core::Vec2& start, const core::Vec2& end)
{
  std::vector<int> out;
  const auto on = [&](int v) {
    const core::Vec3 p(paper.vertices[v].crease_pattern.x(), paper.vertices[v].crease_pattern.y(), 0.0);
    return core::pointSegmentDistance(p, core::Vec3(start.x(), start.y(), 0), core::Vec3(end.x(), end.y(), 0)) < 1e-9;
  };
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease() && on(paper.edges[e].vertices[0]) && on(paper.edges[e].vertices[1]))
      out.push_back(static_cast<int>(e));
  return out;
}

inline std::string readFile(const std::string& path)
{
  std::ifstream file(path);
  EXPECT_TRUE(file) << path;
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

/// The operations as a fold sequence (sequences/*.json), each with its note.
inline std::string sequenceJson(const std::vector<core::Operation>& operations, const core::FoldSequence& reference)
{
  using nlohmann::json;
  const auto xy = [](const core::Vec2& p) { return json::array({ p.x(), p.y() }); };
  const auto xyz = [](const core::Vec3& p) { return json::array({ p.x(), p.y(), p.z() }); };
  json steps = json::array();
  for (size_t i = 0; i < operations.size(); ++i)
  {
    const core::Operation& op = operations[i];
    json step;
    if (op.kind == core::Operation::Kind::Crease)
      step["crease"] = { { "start", xyz(op.crease.start) }, { "end", xyz(op.crease.end) } };
    else if (op.kind == core::Operation::Kind::Rotate)
      step["rotate"] = { { "face", op.rotate.face },
                         { "axis_edge", op.rotate.axis_edge },
                         { "click", xyz(op.rotate.click) },
                         { "angle_deg", op.rotate.angle * 180.0 / M_PI } };
    else if (op.kind == core::Operation::Kind::FlatFold)
    {
      json creases = json::array();
      for (const core::CreaseLineAngle& line : op.flat_fold.creases)
        creases.push_back(
            { { "start", xy(line.start) }, { "end", xy(line.end) }, { "angle_deg", line.angle * 180.0 / M_PI } });
      step["flat_fold"] = { { "creases", creases }, { "fixed", xy(op.flat_fold.fixed_point) } };
    }
    if (i < reference.steps.size())
      step["note"] = reference.steps[i].note;
    steps.push_back(step);
  }
  json sequence = {
    { "title", reference.title }, { "size", reference.size }, { "solver", reference.solver }, { "steps", steps }
  };
  return sequence.dump(1);
}

/// Whether a shipped sequence's steps are these operations (to 1e-9).
inline bool sameOperations(const core::FoldSequence& shipped, const std::vector<core::Operation>& operations)
{
  if (shipped.steps.size() != operations.size())
    return false;
  const auto near = [](const auto& a, const auto& b) { return (a - b).norm() < 1e-9; };
  for (size_t i = 0; i < operations.size(); ++i)
  {
    const core::Operation& a = shipped.steps[i].operation;
    const core::Operation& b = operations[i];
    if (a.kind != b.kind)
      return false;
    if (a.kind == core::Operation::Kind::Crease &&
        !(near(a.crease.start, b.crease.start) && near(a.crease.end, b.crease.end)))
      return false;
    if (a.kind == core::Operation::Kind::Rotate &&
        !(a.rotate.face == b.rotate.face && a.rotate.axis_edge == b.rotate.axis_edge &&
          near(a.rotate.click, b.rotate.click) && std::abs(a.rotate.angle - b.rotate.angle) < 1e-9))
      return false;
    if (a.kind == core::Operation::Kind::FlatFold)
    {
      if (a.flat_fold.creases.size() != b.flat_fold.creases.size() ||
          !near(a.flat_fold.fixed_point, b.flat_fold.fixed_point))
        return false;
      for (size_t k = 0; k < a.flat_fold.creases.size(); ++k)
        if (!near(a.flat_fold.creases[k].start, b.flat_fold.creases[k].start) ||
            !near(a.flat_fold.creases[k].end, b.flat_fold.creases[k].end) ||
            std::abs(a.flat_fold.creases[k].angle - b.flat_fold.creases[k].angle) > 1e-9)
          return false;
    }
  }
  return true;
}

/// The driver the test node's `~driver` parameter names: `markers`, else the Fold tool.
inline MouseDriver driverAsked()
{
  std::string driver = "tool";
  ros::param::get("~driver", driver);
  return driver == "markers" ? MouseDriver::Markers : MouseDriver::Tool;
}

class ModelByMouse : public ::testing::Test
{
public:
  explicit ModelByMouse(MouseDriver driver) : driver_(driver)
  {}

protected:
  void SetUp() override
  {
    feedback_pub_ = client_.nh().advertise<visualization_msgs::InteractiveMarkerFeedback>("interaction/feedback", 1000);
    if (driver_ == MouseDriver::Tool)
      tool_pub_ = client_.nh().advertise<ToolEvent>("tool_events", 1000);
    status_sub_ = client_.nh().subscribe<InteractionStatus>(
        "interaction_status", 100, [this](const InteractionStatus::ConstPtr& s) {
          status_ = *s;
          ++statuses_;
          if (s->mode == "flap" && s->dragging)
            longest_flap_update_ = std::max(longest_flap_update_, s->apply_seconds);
        });
    init_sub_ = client_.nh().subscribe<visualization_msgs::InteractiveMarkerInit>(
        "interaction/update_full", 10,
        [this](const visualization_msgs::InteractiveMarkerInit::ConstPtr& init) { init_ = *init; });
    operations_sub_ = client_.nh().subscribe<Operation>(
        "operations", 100, [this](const Operation::ConstPtr& op) { operations_.push_back(*op); });
    ASSERT_TRUE(waitFor([&] { return operations_sub_.getNumPublishers() > 0; }, 30));
    const ros::Time reset_at = ros::Time::now();
    ASSERT_TRUE(client_.trigger("reset").response.success);
    ASSERT_TRUE(waitFor([&] { return !operations_.empty(); }, 10));
    operations_.clear();  // the reset
    ASSERT_TRUE(waitFor([&] { return feedback_pub_.getNumSubscribers() > 0; }, 30));
    if (driver_ == MouseDriver::Tool)
    {
      ASSERT_TRUE(waitFor([&] { return tool_pub_.getNumSubscribers() > 0; }, 30));
    }
    ASSERT_TRUE(waitFor([&] { return loadMenu(); }, 30)) << "no interactive marker `paper` with a menu";
    revision_ = client_.stateSince(reset_at).revision;
    ASSERT_TRUE(waitFor([&] { return statuses_ > 0 && status_.revision == revision_; }, 10));
    received_at_start_ = status_.feedback_received;
  }

  /// Folds the script at `reference_path` by gestures as the walkthrough under `heading` of the
  /// markdown file at `walkthrough_path` says, checking every step and the gesture counts.
  void foldAsTheWalkthroughSays(const std::string& reference_path, const std::string& walkthrough_path,
                                const std::string& heading)
  {
    const Walkthrough walkthrough = parseCraneWalkthrough(readFile(walkthrough_path), heading);
    ASSERT_TRUE(walkthrough.error.empty()) << walkthrough_path << ": " << walkthrough.error;
    const bool tool = driver_ == MouseDriver::Tool;
    const auto rowOf = [&](int step) -> const WalkthroughRow* {
      for (const WalkthroughRow& row : walkthrough.rows)
        if (step >= row.first && step <= row.last)
          return &row;
      return nullptr;
    };
    int row_start = 0;
    const core::Expected<core::FoldSequence> sequence = core::parseFoldSequence(readFile(reference_path));
    ASSERT_TRUE(sequence.ok()) << sequence.message();
    reference_ = *sequence;
    core::Session reference_session;
    const core::Expected<std::vector<core::Paper>> reference =
        core::foldSequence(*sequence, reference_session, core::makeSolver(sequence->solver));
    ASSERT_TRUE(reference.ok()) << reference.message();
    ASSERT_EQ(reference->size(), sequence->steps.size() + 1);

    for (size_t i = 0; i < sequence->steps.size(); ++i)
    {
      const core::FoldStep& step = sequence->steps[i];
      const int number = static_cast<int>(i + 1);
      SCOPED_TRACE("step " + std::to_string(number) + ": " + step.note);
      const WalkthroughRow* row = rowOf(number);
      ASSERT_NE(row, nullptr) << "the walkthrough has no row for step " << number;
      if (number == row->first)
        row_start = gestures_;
      if (step.operation.kind == core::Operation::Kind::FlatFold && row->drags.count(number))
        flapFold(row->drags.at(number), (*reference)[i + 1]);
      else if (step.operation.kind == core::Operation::Kind::FlatFold)
      {
        ASSERT_TRUE(row->marks.count(number)) << "the walkthrough names no marks for step " << number;
        flatFold(step.operation.flat_fold, row->marks.at(number), (*reference)[i], (*reference)[i + 1]);
      }
      else if (step.operation.kind == core::Operation::Kind::Crease)
        crease(step.operation.crease.start, step.operation.crease.end);
      else if (step.operation.kind == core::Operation::Kind::Rotate)
      {
        ASSERT_NEAR(std::abs(step.operation.rotate.angle), M_PI, 1e-12) << "the script turns by half turns only";
        halfTurn(step.operation.rotate.click);
      }
      else
        FAIL() << "the reference has a step the test cannot make by mouse";
      if (HasFatalFailure())
        return;
      const double off = rigidFitDistance(paper(), (*reference)[i + 1]);
      ASSERT_LE(off, 1e-6) << "the mouse's paper left the script's";
      std::printf("step %zu: %d gestures so far, %.1e from the script's paper (%s)\n", i + 1, gestures_, off,
                  step.note.c_str());
      if (number == row->last)
      {
        const int said = tool ? row->tool_gestures : row->gestures;
        std::printf("walkthrough steps %d-%d: %d gestures (the text says %d)\n", row->first, row->last,
                    gestures_ - row_start, said);
        EXPECT_EQ(gestures_ - row_start, said)
            << "docs/INTERACTION.md's row for steps " << row->first << "–" << row->last << " gives another count"
            << (tool ? " in its `tool` column" : "");
      }
    }
    EXPECT_EQ(gestures_, tool ? walkthrough.total_tool_gestures : walkthrough.total_gestures)
        << "docs/INTERACTION.md's total" << (tool ? " with the Fold tool" : "");
    EXPECT_EQ(walkthrough.steps, static_cast<int>(sequence->steps.size()));
    std::printf("%s by %s: %zu steps, %d gestures\n", sequence->title.c_str(),
                tool ? "the Fold tool (keys, wheel notches, clicks, drags, menu selections)" :
                       "mouse (clicks, drags, menu selections)",
                sequence->steps.size(), gestures_);
    std::printf("the longest update of a flap drag, its preview call included: %.1f ms\n", 1e3 * longest_flap_update_);
  }

  /// foldAsTheWalkthroughSays with the test node's parameters (`~reference`, `~walkthrough`), then
  /// the shipped sequence at `~shipped` checked to be what the gestures issued.
  void foldAsTheLaunchSays(const std::string& heading)
  {
    std::string path, shipped_path, walkthrough_path;
    ASSERT_TRUE(ros::param::get("~reference", path));
    ASSERT_TRUE(ros::param::get("~shipped", shipped_path));
    ASSERT_TRUE(ros::param::get("~walkthrough", walkthrough_path));
    foldAsTheWalkthroughSays(path, walkthrough_path, heading);
    if (HasFatalFailure())
      return;
    const std::vector<core::Operation> issued = issuedOperations();
    const core::Expected<core::FoldSequence> shipped = core::parseFoldSequence(readFile(shipped_path));
    ASSERT_TRUE(shipped.ok()) << shipped.message();
    EXPECT_TRUE(sameOperations(*shipped, issued))
        << shipped_path << " is not what the gestures issued; their sequence:\n"
        << sequenceJson(issued, reference_);
    RecordProperty("gestures", gestures_);
  }

  /// The operations the gestures made paper_model carry out (the reset before them left out).
  std::vector<core::Operation> issuedOperations()
  {
    EXPECT_TRUE(waitFor([&] { return operations_.size() >= reference_.steps.size(); }, 10));
    std::vector<core::Operation> issued;
    for (const Operation& msg : operations_)
    {
      const core::Expected<core::Operation> op = fromMessage(msg);
      EXPECT_TRUE(op.ok()) << op.message();
      if (op.ok() && op->kind != core::Operation::Kind::Reset)
        issued.push_back(*op);
    }
    return issued;
  }

  int gestures() const
  {
    return gestures_;
  }
  double longestFlapUpdate() const
  {
    return longest_flap_update_;
  }
  /// How often each menu entry was chosen.
  const std::map<std::string, int>& menuChoices() const
  {
    return menu_choices_;
  }
  /// The script folded (after foldAsTheWalkthroughSays).
  const core::FoldSequence& reference() const
  {
    return reference_;
  }

  // What follows is the fixture's own: the gestures and how they are planned.

  bool loadMenu()
  {
    for (const auto& m : init_.markers)
      if (m.name == "paper")
      {
        for (const auto& entry : m.menu_entries)
          menu_[entry.title] = entry.id;
        return !menu_.empty();
      }
    return false;
  }

  core::Paper paper()
  {
    core::Expected<core::Paper> p = fromMessage(client_.state());
    EXPECT_TRUE(p.ok()) << p.message();
    return p ? *p : core::Paper::square(1.0);
  }

  /// How far above the paper rviz reports the mouse on the pickable sheet (the marker's copies
  /// of the faces lie off them by this much; every state of the crane pressed on is flat).
  double lift()
  {
    const core::Paper now = paper();
    double top = -INFINITY, mesh_top = -INFINITY;
    for (const core::Vertex& v : now.vertices)
      top = std::max(top, v.folded.z());
    for (const auto& m : init_.markers)
      if (m.name == "paper" && !m.controls.empty() && !m.controls[0].markers.empty())
        for (const auto& p : m.controls[0].markers[0].points)
          mesh_top = std::max(mesh_top, p.z);
    return mesh_top - top;
  }

  void send(const visualization_msgs::InteractiveMarkerFeedback& f)
  {
    feedback_pub_.publish(f);
    ++sent_;
    ros::spinOnce();
  }

  /// A Fold tool event with the line of sight straight down onto `at` from 2 m above it (x
  /// right, y down, z along the sight, as the tool reports rviz's camera).
  ToolEvent toolEvent(uint8_t kind, const core::Vec3& at) const
  {
    ToolEvent e;
    e.header.stamp = ros::Time::now();
    e.header.frame_id = "paper";
    e.kind = kind;
    e.eye = toPoint(at + core::Vec3(0, 0, 2.0));
    Eigen::Matrix3d axes;
    axes << core::Vec3(1, 0, 0), core::Vec3(0, -1, 0), core::Vec3(0, 0, -1);
    const Eigen::Quaterniond q(axes);
    e.camera.w = q.w();
    e.camera.x = q.x();
    e.camera.y = q.y();
    e.camera.z = q.z();
    e.ray.z = -1.0;
    return e;
  }

  void send(const ToolEvent& e)
  {
    tool_pub_.publish(e);
    ++sent_;
    ros::spinOnce();
  }

  /// The node handled everything sent so far (and any fold it animates ended): it received as
  /// much as was sent, and nothing waits in its queue.
  void settle()
  {
    ASSERT_TRUE(waitFor(
        [&] {
          return status_.feedback_received >= received_at_start_ + sent_ && status_.pending == 0 && !status_.dragging;
        },
        20));
  }

  /// The node shows the paper's latest revision (its sheet marker redrawn for it).
  void showing(uint64_t revision)
  {
    client_.stateAt(revision);
    ASSERT_TRUE(waitFor([&] { return status_.revision == revision; }, 20));
    ros::WallDuration(0.2).sleep();  // the marker's full update follows the status
    ros::spinOnce();
  }

  void press(const core::Vec3& at)
  {
    if (driver_ == MouseDriver::Tool)
      return send(toolEvent(ToolEvent::PRESS, at));
    gesture_.lift = lift();
    gesture_.press = at;
    send(gesture_.down(ros::Time::now()));
  }

  void moveTo(const core::Vec3& at)
  {
    if (driver_ == MouseDriver::Tool)
      return send(toolEvent(ToolEvent::MOVE, at));
    send(gesture_.moveTo(at, ros::Time::now()));
  }

  void releaseAt(const core::Vec3& at)
  {
    if (driver_ == MouseDriver::Tool)
      return send(toolEvent(ToolEvent::RELEASE, at));
    send(gesture_.upAt(at, ros::Time::now()));
  }

  void click(const core::Vec3& at)
  {
    press(at);
    releaseAt(at);
    ++gestures_;
    settle();
  }

  void drag(const core::Vec3& from, const core::Vec3& to, int steps = 12)
  {
    press(from);
    for (int i = 1; i <= steps; ++i)
    {
      ros::WallDuration(0.02).sleep();
      moveTo(from + (to - from) * (static_cast<double>(i) / steps));
    }
    releaseAt(to);
    ++gestures_;
    settle();
  }

  /// A key of the Fold tool, with the pointer over `at`.
  void key(const std::string& name, uint8_t modifiers = 0, const core::Vec3& at = core::Vec3(0.5, 0.5, 0))
  {
    ToolEvent e = toolEvent(ToolEvent::KEY, at);
    e.key = name;
    e.modifiers = modifiers;
    send(e);
    ++gestures_;
    settle();
  }

  /// One notch of the Fold tool's wheel over `at`: away from the user (`away`) or towards.
  void wheel(const core::Vec3& at, bool away)
  {
    ToolEvent e = toolEvent(ToolEvent::WHEEL, at);
    e.wheel_delta = away ? 120 : -120;
    send(e);
    ++gestures_;
    settle();
  }

  /// A choice of the sheet marker's menu, right-clicked at `at` (with either driver: the Fold
  /// tool has no key for what this is used for).
  void menu(const std::string& title, const core::Vec3& at = core::Vec3(0.5, 0.5, 0))
  {
    int id = -1;  // rviz shows check marks as a prefix of the title
    for (const auto& [t, i] : menu_)
      if (t.size() >= title.size() && t.compare(t.size() - title.size(), title.size(), title) == 0)
        id = i;
    ASSERT_GE(id, 0) << "no menu entry " << title;
    ++menu_choices_[title];
    gesture_.lift = lift();
    send(gesture_.menu(id, at, ros::Time::now()));
    ++gestures_;
    settle();
  }

  void mode(const std::string& name)
  {
    if (status_.mode == name)
      return;
    const std::map<std::string, std::pair<std::string, std::string>> entries{
      { "crease", { "Crease mode", "1" } },
      { "rotate", { "Rotate mode", "2" } },
      { "fold", { "Fold mode: mark creases", "3" } },
      { "flap", { "Flap mode: drag a flap", "5" } }
    };
    if (driver_ == MouseDriver::Tool)
      key(entries.at(name).second);
    else
      menu(entries.at(name).first);
    ASSERT_EQ(status_.mode, name);
  }

  /// The next layer down under `at`: *Next layer down*, or the Fold tool's wheel turned away.
  void layerDown(const core::Vec3& at)
  {
    if (driver_ == MouseDriver::Tool)
      wheel(at, true);
    else
      menu("Next layer down", at);
  }

  /// The next layer up under `at` (with nothing picked there, the bottom layer): *Next layer up*,
  /// or the Fold tool's wheel turned towards the user.
  void layerUp(const core::Vec3& at)
  {
    if (driver_ == MouseDriver::Tool)
      wheel(at, false);
    else
      menu("Next layer up", at);
  }

  /// Expects the gesture to have made one new revision.
  void committed(const std::string& what)
  {
    ASSERT_TRUE(waitFor([&] { return client_.state().revision == revision_ + 1; }, 30))
        << what << " was not committed: " << status_.message;
    ++revision_;
    showing(revision_);
  }

  /// Draws the line. Where the drag would snap an end off the line (as its guide shows), with
  /// snapping switched off for it.
  void crease(const core::Vec3& start, const core::Vec3& end)
  {
    mode("crease");
    const core::Paper now = paper();
    core::SnapSettings settings;
    settings.radius *= now.scale();
    const core::CreaseDrag drawn = core::creaseDrag(now, start, end, settings);
    const core::Vec3 d = (end - start).normalized();
    const auto offLine = [&](const core::Vec3& p) { return ((p - start) - (p - start).dot(d) * d).norm() > 1e-12; };
    const bool free = offLine(drawn.start.point) || offLine(drawn.end.point);
    if (free)
      menu("Snap the line");
    drag(start, end);
    committed("the crease");
    if (free)
      menu("Snap the line");
  }

  /// Turns the face under `click` by a half turn about its automatic axis: the pointer dragged
  /// past the press point's mirror image over the axis (seen from above, the angle follows the
  /// pointer's distance from the axis: a half turn at the mirror image, and no further).
  void halfTurn(const core::Vec3& click)
  {
    mode("rotate");
    const core::Paper now = paper();
    const core::Vec3 at = core::onSurface(now, click, kFromAbove);
    const core::Expected<core::RotationRing> ring = core::rotationRing(now, at, kFromAbove);
    ASSERT_TRUE(ring.ok()) << ring.message();
    const core::Vec3 d = (ring->axis_b - ring->axis_a).normalized();
    const core::Vec3 r = at - ring->axis_a;
    const core::Vec3 foot = ring->axis_a + r.dot(d) * d;
    drag(at, foot + 1.2 * (foot - at), 20);
    committed("the half turn");
  }

  /// The creases the node picks from under `at` (seen from above), top first.
  static std::vector<int> creasesUnderAt(const core::Paper& now, const core::Vec3& at)
  {
    return core::creasesUnder(now, core::onSurface(now, at, kFromAbove), kFromAbove, kSnapRadius * now.scale());
  }

  /// Where the crease `edge` lies in the list of layers the node walks under `at` (seen from
  /// above): 0 the top; -1 when it is not in the list.
  int layerOfCrease(const core::Paper& now, int edge, const core::Vec3& at) const
  {
    const std::vector<int> under = creasesUnderAt(now, at);
    const auto it = std::find(under.begin(), under.end(), edge);
    return it == under.end() ? -1 : static_cast<int>(it - under.begin());
  }

  /// Where a click lands on nothing and lets go of the pick: on the table beside the paper (with
  /// the Fold tool on the sheet's margin, where a press still reaches the node; off it the tool
  /// sends nothing, as rviz sends the sheet marker nothing).
  core::Vec3 besideThePaper(const core::Paper& now) const
  {
    if (driver_ == MouseDriver::Markers)
      return core::Vec3(-0.3, -0.3, 0.0);
    core::Vec3 lo = now.vertices[0].folded;
    for (const core::Vertex& v : now.vertices)
      lo = lo.cwiseMin(v.folded);
    return lo - core::Vec3(0.05, 0.05, 0.0) * now.scale();
  }

  /// Clicks the crease until it is picked and carries `angle`'s mark.
  void mark(int edge, double angle)
  {
    const core::Paper now = paper();
    core::Vec3 at =
        0.5 * (now.vertices[now.edges[edge].vertices[0]].folded + now.vertices[now.edges[edge].vertices[1]].folded);
    // With the Fold tool the mouse stays where the last crease was picked when this one lies
    // under it too: the wheel walks there.
    if (driver_ == MouseDriver::Tool && status_.picked_edge >= 0 && last_pick_.allFinite() &&
        layerOfCrease(now, edge, last_pick_) >= 0)
      at = last_pick_;
    const double wanted = angle > 0 ? M_PI : angle < 0 ? -M_PI : 0.0;
    const auto marked = [&]() -> std::optional<double> {
      for (size_t i = 0; i < status_.marked_edges.size(); ++i)
        if (status_.marked_edges[i] == edge)
          return status_.marked_angles[i];
      return std::nullopt;
    };
    if (marked() == wanted)
      return;
    // Where the last pick was made, a click would mark the crease picked there: first down
    // through the layers (with the Fold tool up or down, the way the crease lies), and from the
    // top again (a click on nothing lets go of the pick).
    bool here = status_.picked_edge >= 0 && (at - last_pick_).norm() < 1e-9;
    const auto walking = [&](int step) { return status_.picked_edge != edge && step < 32 && !HasFatalFailure(); };
    if (here && driver_ == MouseDriver::Tool)
    {
      // The wheel walks either way: as many notches as the crease lies from the pick, unless
      // picking afresh (a click beside, a click here, down from the top) takes fewer.
      const int target = layerOfCrease(now, edge, at), picked = static_cast<int>(status_.picked_layer) - 1;
      if (target >= 0 && std::abs(target - picked) > 2 + target)
        here = false, click(besideThePaper(now));
      else if (target >= 0 && target < picked)
        for (int up = 0; walking(up) && status_.picked_layer > 1; ++up)
          layerUp(at);
    }
    if (here)
      for (int down = 0; walking(down) && status_.picked_layer < status_.layers; ++down)
        layerDown(at);
    if (status_.picked_edge != edge && !HasFatalFailure())
    {
      if (here)
        click(besideThePaper(now));
      // Picked afresh: a click picks the top layer, and down from it; with the Fold tool the
      // wheel turned towards the user picks the bottom one, and up from it, where that is shorter
      // (and no pick nearby would be walked instead).
      const std::vector<int> under = creasesUnderAt(now, at);
      const auto it = std::find(under.begin(), under.end(), edge);
      const int target = it == under.end() ? -1 : static_cast<int>(it - under.begin());
      const bool pick_near = !here && (at - last_pick_).norm() <= kSnapRadius * now.scale();
      if (driver_ == MouseDriver::Tool && target >= 0 && !pick_near &&
          static_cast<int>(under.size()) - target < 1 + target)
      {
        for (int up = 0; walking(up) && (up == 0 || status_.picked_layer > 1); ++up)
          layerUp(at);
      }
      else
      {
        click(at);
        for (int down = 0; walking(down); ++down)
          layerDown(at);
      }
      last_pick_ = at;
    }
    ASSERT_EQ(status_.picked_edge, edge) << "the crease was never picked under " << at.transpose();
    for (int i = 0; marked() != wanted && i < 4 && !HasFatalFailure(); ++i)
      click(at);
    ASSERT_EQ(marked(), wanted);
  }

  /// The face to keep in place: the script's, or, where that one stands edge-on to the view
  /// from above, a face seen from there that the script's fold leaves in place too (`before`
  /// and `after`: the script's paper around the fold) — the same fold.
  static int faceThatStays(const core::Paper& now, const core::FlatFoldRequest& request, const core::Paper& before,
                           const core::Paper& after)
  {
    const auto stays = [&](int f) {
      for (int v : now.faces[f].vertices)
        for (size_t r = 0; r < before.vertices.size(); ++r)
          if ((before.vertices[r].crease_pattern - now.vertices[v].crease_pattern).norm() < 1e-9 &&
              (before.vertices[r].folded - after.vertices[r].folded).norm() > 1e-9)
            return false;
      return true;
    };
    const auto seen = [&](int f) { return std::abs(now.faceNormal(f).z()) > 0.5; };
    const int scripts = core::faceContaining(now, request.fixed_point);
    if (scripts >= 0 && seen(scripts))
      return scripts;
    for (size_t f = 0; f < now.faces.size(); ++f)
      if (seen(static_cast<int>(f)) && stays(static_cast<int>(f)))
        return static_cast<int>(f);
    return -1;
  }

  /// Picks `face` to stay: *Keep the face here* at its centroid and down to its layer. With the
  /// Fold tool, where it takes fewer gestures, at a point of the face with no crease near (the
  /// centroid, or towards a corner): a click there and down, or the wheel turned towards the user
  /// there (from the bottom layer up).
  void keepFace(const core::Paper& now, int face)
  {
    const double radius = kSnapRadius * now.scale();
    core::Vec3 at = now.faceCentroid(face);
    enum class Way
    {
      Menu,
      Click,
      Wheel,
    } way = Way::Menu;
    if (driver_ == MouseDriver::Tool)
    {
      int fewest = 1 + 32;  // the menu, and down as far as it may take
      std::vector<core::Vec3> places{ at };
      for (int v : now.faces[face].vertices)
        for (double t : { 0.3, 0.6 })
          places.push_back(at + t * (now.vertices[v].folded - at));
      for (const core::Vec3& place : places)
      {
        const core::Vec3 on = core::onSurface(now, place, kFromAbove);
        const std::vector<int> under = core::facesUnder(now, on, kFromAbove);
        const auto it = std::find(under.begin(), under.end(), face);
        // A pick alive nearby would be walked on; a crease near is picked before the faces.
        if (it == under.end() || !core::creasesUnder(now, on, kFromAbove, radius).empty() ||
            (place - last_pick_).norm() <= radius)
          continue;
        const int target = static_cast<int>(it - under.begin()), n = static_cast<int>(under.size());
        if (1 + target < fewest)
          fewest = 1 + target, at = place, way = Way::Click;
        if (n - target < fewest)
          fewest = n - target, at = place, way = Way::Wheel;
      }
    }
    if (way == Way::Wheel)
      for (int up = 0; (up == 0 || status_.picked_face != face) && up < 32 && !HasFatalFailure(); ++up)
        layerUp(at);
    else if (way == Way::Click)
      click(at);
    else
      menu("Keep the face here", at);
    for (int down = 0; status_.picked_face != face && down < 32 && !HasFatalFailure(); ++down)
      layerDown(at);
    ASSERT_EQ(status_.picked_face, face);
  }

  /// Marks the flat fold's creases as the walkthrough's text says (`marks`: +1 valley, −1
  /// mountain, 0 unfold, in the order of the script's creases), picks the face that stays, and
  /// folds.
  void flatFold(const core::FlatFoldRequest& request, const std::vector<int>& marks, const core::Paper& before,
                const core::Paper& after)
  {
    mode("fold");
    ASSERT_EQ(marks.size(), request.creases.size()) << "the text names a mark for each crease of the fold";
    bool right_angle = false;
    for (size_t k = 0; k < request.creases.size(); ++k)
    {
      const core::CreaseLineAngle& line = request.creases[k];
      const std::vector<int> edges = creasesOn(paper(), line.start, line.end);
      ASSERT_FALSE(edges.empty());
      right_angle = std::abs(std::abs(line.angle) - M_PI / 2) < 1e-9;
      for (int e : edges)
      {
        mark(e, marks[k]);
        if (HasFatalFailure())
          return;
      }
    }
    const core::Paper now = paper();
    const int face = faceThatStays(now, request, before, after);
    ASSERT_GE(face, 0);
    keepFace(now, face);
    if (HasFatalFailure())
      return;
    if (right_angle)
      menu("Fold to a right angle");
    else if (driver_ == MouseDriver::Tool)
      key("Return", 0, now.faceCentroid(face));
    else
      menu("Fold flat");
    committed("the fold on the marked creases");
  }

  /// Where the reference's paper after the fold (`after`) puts the crease-pattern point `cp`,
  /// moved rigidly so that `fixed` (a face of `now`) lies where it lies now.
  static core::Vec3 whereTheReferencePuts(const core::Paper& after, const core::Paper& now, int fixed,
                                          const core::Vec2& cp)
  {
    const std::vector<int>& corners = now.faces[fixed].vertices;
    Eigen::Matrix3Xd from(3, corners.size()), to(3, corners.size());
    for (size_t i = 0; i < corners.size(); ++i)
    {
      const int v = after.vertexAt(now.vertices[corners[i]].crease_pattern, 1e-9);
      EXPECT_GE(v, 0);
      from.col(static_cast<Eigen::Index>(i)) = after.vertices[std::max(v, 0)].folded;
      to.col(static_cast<Eigen::Index>(i)) = now.vertices[corners[i]].folded;
    }
    Eigen::Isometry3d motion;
    motion.matrix() = Eigen::umeyama(from, to, false);
    const int face = core::faceContaining(after, cp);
    return motion * (core::facePose(after, face) * core::Vec3(cp.x(), cp.y(), 0.0));
  }

  /// A fold by one drag, as the walkthrough's text says: the flap pressed at `named`'s point (the
  /// layer there picked, when it is not on top, by the next layer down from the top or the next
  /// layer up from the bottom, whichever takes fewer) and dragged to where the reference puts
  /// that point.
  void flapFold(const FlapDragNamed& named, const core::Paper& after)
  {
    mode("flap");
    const core::Paper now = paper();
    const core::Vec2 cp(named.x, named.y);
    const int face = core::faceContaining(now, cp);
    ASSERT_GE(face, 0) << "no face at (" << named.x << ", " << named.y << ")";
    const core::Vec3 at = core::facePose(now, face) * core::Vec3(cp.x(), cp.y(), 0.0);
    const std::vector<int> under = core::facesUnder(now, at, kFromAbove);
    if (under.empty() || under[0] != face)
    {
      const auto layer = std::find(under.begin(), under.end(), face);
      ASSERT_NE(layer, under.end()) << "the flap's face is not under its point";
      const long downs = layer - under.begin(), ups = under.end() - layer;
      for (int notch = 0; status_.picked_face != face && notch < 16 && !HasFatalFailure(); ++notch)
        ups < downs ? layerUp(at) : layerDown(at);
      ASSERT_EQ(status_.picked_face, face) << "the flap's layer was never picked";
    }
    // The face the interaction keeps in place is the one compound_fold keeps.
    const core::Expected<core::CompoundFolds> folds = core::CompoundFolds::at(now, face, at);
    ASSERT_TRUE(folds.ok()) << folds.message();
    drag(at, whereTheReferencePuts(after, now, folds->fixedFace(), cp));
    committed("the " + named.kind);
    EXPECT_EQ(status_.message,
              std::string(1, static_cast<char>(std::toupper(named.kind[0]))) + named.kind.substr(1) + ".");
  }

  static inline const core::Vec3 kFromAbove = core::Vec3(0, 0, -1);
  // The interaction's snap_radius (also how near a crease a click names it), of the paper's scale.
  static inline const double kSnapRadius = core::SnapSettings{}.radius;

  MouseDriver driver_;
  PaperClient client_;
  ros::Publisher feedback_pub_, tool_pub_;
  ros::Subscriber status_sub_, init_sub_, operations_sub_;
  std::vector<Operation> operations_;
  visualization_msgs::InteractiveMarkerInit init_;
  InteractionStatus status_;
  int statuses_ = 0;
  double longest_flap_update_ = 0.0;  // the longest update of a flap drag, its preview included (s)
  std::map<std::string, int> menu_;
  std::map<std::string, int> menu_choices_;
  MouseGesture gesture_;
  core::FoldSequence reference_;
  uint64_t revision_ = 0;
  int gestures_ = 0;
  uint64_t sent_ = 0, received_at_start_ = 0;
  core::Vec3 last_pick_ = core::Vec3::Constant(NAN);
};

}  // namespace virtual_origami::test
