// Benchmark (not a test): the user's path. The nodes as origami.launch starts them (paper_model,
// spring_solver with the newton solver, curved_mesh_solver, interaction; bench/user_path.launch),
// driven as a user drives them, on generated tessellations of about 1,000 to 10,000 vertices
// (a Miura-ori with γ = 70°, a square twist, a waterbomb; each with its own mountain/valley
// assignment) loaded from FOLD files in the data folder:
//   fold_commit          fold_by_assignment to 25, 50 and 99 % from the flat pattern (each undone)
//   turn_preview/commit  rotate, the corner face 2°, 4°, ... 10° as previews, then 10° committed
//   slider_preview       the fold slider's handle moved 1 % at a time from 0 to 40 % (and 5 % at a
//                        time to 100 %): InteractiveMarkerFeedback on interaction/feedback, as rviz
//                        sends it, each move waited for
//   slider_release_40    the handle let go at 40 % (and at 100 %): the commit from the last preview
//   drag_vertex_preview/commit  drag_vertex, the corner vertex lifted 0.4 % of the sheet at a time
//                        to 2 % from the 40 % state; drag_preview/commit: the same with the mouse in drag mode
//                        (feedback on interaction/feedback, the mode chosen from the sheet's menu)
// Every action is timed from the request (the call, or the feedback published) to its answer (the
// service's return; for the slider, the interaction node's status after the preview, or the new
// `state` after the release) and to the `markers` message that shows it. Then a breakdown of
// where the time of the path goes, measured from outside: a trivial service's round trip, the
// sizes and (de)serialisation times of the messages, one solve of spring_solver through its
// service against the same solve in this process, the face frames on tf.
// Writes <csv_prefix>.csv and <csv_prefix>_breakdown.csv (appended to: header when new).
// Run by bench/user_path.launch (make bench, scripts/run_bench.sh).
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <ros/serialization.h>
#include <std_srvs/Trigger.h>
#include <tf2_msgs/TFMessage.h>
#include <virtual_origami/DragVertex.h>
#include <virtual_origami/FoldByAssignment.h>
#include <virtual_origami/InteractionStatus.h>
#include <virtual_origami/Load.h>
#include <virtual_origami/PaperState.h>
#include <virtual_origami/Rotate.h>
#include <virtual_origami/Solve.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>
#include <visualization_msgs/InteractiveMarkerInit.h>
#include <visualization_msgs/MarkerArray.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/numerics/heap_reuse.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/fold_slider.h"
#include "virtual_origami/ros/service_call.h"
#include "virtual_origami/ros/markers.h"
#include "virtual_origami/ros/mouse_feedback.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/solvers/crease_driver_factory.h"
#include "virtual_origami/solvers/solver_factory.h"

namespace
{
using namespace virtual_origami;
using Clock = std::chrono::steady_clock;
using visualization_msgs::InteractiveMarkerFeedback;

double msSince(Clock::time_point start, Clock::time_point end = Clock::now())
{
  return std::chrono::duration<double, std::milli>(end - start).count();
}

double median(std::vector<double> v)
{
  if (v.empty())
    return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// A message fit for a CSV field: quotes replaced, at most 120 characters.
std::string excerpt(const std::string& message)
{
  std::string out;
  for (char c : message.substr(0, 120))
    out += c == '"' ? '\'' : (c == '\n' ? ' ' : c);
  return out;
}

struct Pattern
{
  std::string name;
  core::Tessellation tessellation;
};

std::optional<Pattern> makePattern(const std::string& kind, long vertices)
{
  if (kind == "miura")
  {
    // γ = 70°, as the issue measured: gridForVertexCount's count does not depend on γ.
    const core::GridSize grid = core::gridForVertexCount(core::TessellationKind::Miura, vertices);
    auto t = core::miuraTessellation(grid.columns, grid.rows, 1.0, 1.0, 70.0 * M_PI / 180.0);
    if (t)
      return Pattern{ "miura_70", std::move(*t) };
    std::fprintf(stderr, "user_path_bench: miura: %s\n", t.message().c_str());
    return std::nullopt;
  }
  const core::TessellationKind k =
      kind == "square_twist" ? core::TessellationKind::SquareTwist : core::TessellationKind::Waterbomb;
  auto t = core::tessellationWithVertices(k, vertices);
  if (t)
    return Pattern{ kind, std::move(*t) };
  std::fprintf(stderr, "user_path_bench: %s: %s\n", kind.c_str(), t.message().c_str());
  return std::nullopt;
}

/// The pattern as a designer's FOLD file (assignments, no fold angles), in the data folder.
std::string writeFold(const core::Paper& paper, const std::string& folder, const std::string& stem)
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
  std::ofstream(folder + "/" + name) << fold.dump();
  return name;
}

template <class Message>
std::pair<size_t, double> serialiseTimed(const Message& m, int repeats = 5)
{
  const uint32_t bytes = ros::serialization::serializationLength(m);
  std::vector<uint8_t> buffer(bytes);
  std::vector<double> ms;
  for (int i = 0; i < repeats; ++i)
  {
    const auto t0 = Clock::now();
    ros::serialization::OStream out(buffer.data(), bytes);
    ros::serialization::serialize(out, m);
    ms.push_back(msSince(t0));
  }
  return { bytes, median(ms) };
}

template <class Message>
double deserialiseTimed(const Message& m, int repeats = 5)
{
  const uint32_t bytes = ros::serialization::serializationLength(m);
  std::vector<uint8_t> buffer(bytes);
  ros::serialization::OStream out(buffer.data(), bytes);
  ros::serialization::serialize(out, m);
  std::vector<double> ms;
  for (int i = 0; i < repeats; ++i)
  {
    Message back;
    const auto t0 = Clock::now();
    ros::serialization::IStream in(buffer.data(), bytes);
    ros::serialization::deserialize(in, back);
    ms.push_back(msSince(t0));
  }
  return median(ms);
}

/// CPU time of the nodes of the path (user + system, all their threads, the ended ones too:
/// /proc/<pid>/stat, in clock ticks of 10 ms), their pids asked of the nodes through the master.
class NodeCpu
{
public:
  static constexpr const char* kNodes[] = { "paper_model", "spring_solver", "curved_mesh_solver", "interaction" };
  static constexpr size_t kCount = 4;
  using Sample = std::array<double, kCount>;

  /// Milliseconds of CPU each node has used so far (NaN for one not found).
  Sample now()
  {
    Sample out;
    for (size_t i = 0; i < kCount; ++i)
    {
      double ms = pids_[i] > 0 ? read(pids_[i]) : NAN;
      if (std::isnan(ms))  // not looked up yet, or respawned
      {
        pids_[i] = pidOf(std::string("/origami/") + kNodes[i]);
        ms = pids_[i] > 0 ? read(pids_[i]) : NAN;
      }
      out[i] = ms;
    }
    return out;
  }

private:
  static double read(int pid)
  {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    if (!std::getline(in, line))
      return NAN;
    // Fields after the command's closing parenthesis: state is field 3, utime 14, stime 15.
    std::istringstream fields(line.substr(line.rfind(')') + 2));
    std::string field;
    double utime = 0, stime = 0;
    for (int k = 3; k <= 15 && fields >> field; ++k)
      if (k == 14)
        utime = std::stod(field);
      else if (k == 15)
        stime = std::stod(field);
    return (utime + stime) * 1000.0 / static_cast<double>(::sysconf(_SC_CLK_TCK));
  }

  static int pidOf(const std::string& node)
  {
    XmlRpc::XmlRpcValue args, result, payload;
    args[0] = ros::this_node::getName();
    args[1] = node;
    if (!ros::master::execute("lookupNode", args, result, payload, false) ||
        payload.getType() != XmlRpc::XmlRpcValue::TypeString)
      return -1;
    std::string host;
    uint32_t port = 0;
    if (!ros::network::splitURI(static_cast<std::string>(payload), host, port))
      return -1;
    XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
    XmlRpc::XmlRpcValue pid_args, pid;
    pid_args[0] = ros::this_node::getName();
    if (!client.execute("getPid", pid_args, pid) || pid.getType() != XmlRpc::XmlRpcValue::TypeArray || pid.size() < 3 ||
        static_cast<int>(pid[0]) != 1)
      return -1;
    return static_cast<int>(pid[2]);
  }

  std::array<int, kCount> pids_{ -1, -1, -1, -1 };
};

struct Row
{
  explicit Row(std::string a = "", double s = 0) : action(std::move(a)), step(s)
  {}
  std::string action;
  double step = 0;  // fraction, degrees or lift (mm), what the action moved to
  double answer_ms = NAN, markers_ms = NAN;
  bool success = false;
  std::string message;
  NodeCpu::Sample cpu_ms{ NAN, NAN, NAN, NAN };  // each node's CPU from the request to the markers
  void cpuSince(const NodeCpu::Sample& start, const NodeCpu::Sample& end)
  {
    for (size_t i = 0; i < NodeCpu::kCount; ++i)
      cpu_ms[i] = end[i] - start[i];
  }
};

class UserPath
{
public:
  UserPath(ros::NodeHandle& nh, double timeout) : nh_(nh), timeout_(timeout)
  {
    // TCP_NODELAY as rviz's: without it Nagle's algorithm holds a message's tail for a delayed ACK.
    const ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
    markers_sub_ = nh_.subscribe<visualization_msgs::MarkerArray>(
        "markers", 10,
        [this](const visualization_msgs::MarkerArray::ConstPtr& m) {
          // The faded sheet paper_model draws while the curved model bends it (a drag no rigid
          // shape follows) shows no answer: not counted.
          for (const auto& marker : m->markers)
            if (marker.ns == "front" && marker.color.a < 0.5f)
              return;
          std::lock_guard<std::mutex> lock(mutex_);
          ++markers_seen_;
          markers_at_ = Clock::now();
          markers_ = m;
        },
        ros::VoidConstPtr(), hints);
    state_sub_ = nh_.subscribe<PaperState>(
        "state", 10,
        [this](const PaperState::ConstPtr& s) {
          std::lock_guard<std::mutex> lock(mutex_);
          state_ = s;
          state_at_ = Clock::now();
          markers_seen_at_state_ = markers_seen_;
        },
        ros::VoidConstPtr(), hints);
    status_sub_ = nh_.subscribe<InteractionStatus>(
        "interaction_status", 100,
        [this](const InteractionStatus::ConstPtr& s) {
          std::lock_guard<std::mutex> lock(mutex_);
          status_ = s;
          status_at_ = Clock::now();
        },
        ros::VoidConstPtr(), hints);
    tf_sub_ = nh_.subscribe<tf2_msgs::TFMessage>(
        "/tf", 100,
        [this](const tf2_msgs::TFMessage::ConstPtr& t) {
          std::lock_guard<std::mutex> lock(mutex_);
          if (!largest_tf_ || t->transforms.size() > largest_tf_->transforms.size())
            largest_tf_ = t;
        },
        ros::VoidConstPtr(), hints);
    init_sub_ = nh_.subscribe<visualization_msgs::InteractiveMarkerInit>(
        "interaction/update_full", 10, [this](const visualization_msgs::InteractiveMarkerInit::ConstPtr& init) {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const auto& m : init->markers)
            if (m.name == "paper")
              for (const auto& entry : m.menu_entries)
                menu_[entry.title] = entry.id;
        });
    feedback_pub_ = nh_.advertise<InteractiveMarkerFeedback>("interaction/feedback", 100);
    fold_ = nh_.serviceClient<FoldByAssignment>("fold_by_assignment", true);
    rotate_ = nh_.serviceClient<Rotate>("rotate", true);
    drag_ = nh_.serviceClient<DragVertex>("drag_vertex", true);
    undo_ = nh_.serviceClient<std_srvs::Trigger>("undo", true);
  }

  bool ready()
  {
    for (const char* s : { "load", "fold_by_assignment", "rotate", "drag_vertex", "undo", "solve" })
      if (!ros::service::waitForService(nh_.resolveName(s), ros::Duration(60)))
      {
        std::fprintf(stderr, "user_path_bench: no %s service\n", s);
        return false;
      }
    if (!waitFor([&] { return feedback_pub_.getNumSubscribers() > 0 && status(); }, 60))
    {
      std::fprintf(stderr, "user_path_bench: the interaction node does not listen\n");
      return false;
    }
    return true;
  }

  /// Loads the pattern; false (with the reason printed) when paper_model refuses it.
  bool load(const std::string& file, Row& row)
  {
    Load load;
    load.request.path = file;
    const uint64_t before = revision();
    takeLargestTf();  // the face frames of the pattern before are not this one's
    const int markers = markersSeen();
    const NodeCpu::Sample cpu = cpu_.now();
    const auto t0 = Clock::now();
    if (!callService(nh_.resolveName("load"), load))
      load.response.message = "the call failed";
    row = Row("load");
    row.answer_ms = msSince(t0);
    row.success = load.response.success;
    row.message = load.response.message;
    if (!row.success)
      return false;
    row.markers_ms = markersAfter(t0, markers);
    row.cpuSince(cpu, cpu_.now());
    // The interaction node has the new paper (and shows its slider) before anything else.
    waitFor([&] { return revision() > before; }, timeout_);
    const uint64_t loaded = revision();
    waitFor(
        [&] {
          auto s = status();
          return s && s->revision == loaded;
        },
        timeout_);
    ros::WallDuration(0.3).sleep();
    return true;
  }

  Row fold(double fraction, bool preview)
  {
    FoldByAssignment f;
    f.request.fraction = fraction;
    f.request.preview = preview;
    return timedCall(fold_, f, preview ? "fold_preview" : "fold_commit", fraction);
  }

  Row rotate(Rotate& r, double degrees)
  {
    return timedCall(rotate_, r, r.request.commit ? "turn_commit" : "turn_preview", degrees);
  }

  Row drag(DragVertex& d, double step)
  {
    return timedCall(drag_, d, d.request.commit ? "drag_vertex_commit" : "drag_vertex_preview", step);
  }

  bool undo()
  {
    std_srvs::Trigger t;
    const uint64_t before = revision();
    if (!undo_.call(t) || !t.response.success)
      return false;
    return waitFor([&] { return revision() > before; }, timeout_) && interactionHas(revision());
  }

  /// The slider pressed at 0, moved in `steps` equal moves to `target` (each preview waited
  /// for), held still `hold` seconds, released there. Rows: one per preview (`preview_action`),
  /// then the release.
  std::vector<Row> slide(double target, int steps, const std::string& release_action, double hold = 0.0,
                         const std::string& preview_action = "slider_preview")
  {
    std::vector<Row> rows;
    const SliderTrack track = sliderTrack(paper(), SliderStyle{});
    send(InteractiveMarkerFeedback::MOUSE_DOWN, sliderPoint(track, 0.0));
    ros::WallDuration(0.1).sleep();
    for (int i = 1; i <= steps && ros::ok(); ++i)
    {
      const double f = target * i / steps;
      const uint64_t applied = updatesApplied();
      const int markers = markersSeen();
      const NodeCpu::Sample cpu = cpu_.now();
      const auto t0 = Clock::now();
      send(InteractiveMarkerFeedback::POSE_UPDATE, sliderPoint(track, f));
      Row row(preview_action, f);
      // The node's status after the update it applied: the preview's answer came back.
      if (waitFor([&] { return updatesApplied() > applied; }, timeout_))
      {
        row.answer_ms = msSince(t0, statusAt());
        row.markers_ms = markersAfter(t0, markers, 2.0);
        row.success = !std::isnan(row.markers_ms);
        row.cpuSince(cpu, cpu_.now());
        row.message = row.success ? "preview drawn" : "no preview drawn: " + statusMessage();
      }
      else
        row.message = "the interaction node applied no update";
      rows.push_back(row);
    }
    if (hold > 0)
      ros::WallDuration(hold).sleep();
    const uint64_t before = revision();
    const int markers = markersSeen();
    const NodeCpu::Sample cpu = cpu_.now();
    const auto t0 = Clock::now();
    send(InteractiveMarkerFeedback::MOUSE_UP, sliderPoint(track, target));
    Row row(release_action, target);
    // No answer is seen from outside the interaction node: the new `state`, published just
    // before paper_model answers it, stands for it.
    if (waitFor([&] { return revision() > before; }, timeout_))
    {
      row.answer_ms = msSince(t0, stateAt());
      // The commit's markers come after its state (paper_model publishes them so); a preview of
      // the slider catching up with its held handle may have been drawn after t0 and before it.
      int at_state = markers;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        at_state = markers_seen_at_state_;
      }
      row.markers_ms = markersAfter(t0, at_state, 1.0);
      if (std::isnan(row.markers_ms))
        row.markers_ms = markersAfter(t0, markers);
      row.cpuSince(cpu, cpu_.now());
      row.success = true;
      row.message = "committed, revision " + std::to_string(revision());
      interactionHas(revision());
    }
    else
    {
      waitFor([&] { return false; }, 1.0);
      row.message = "nothing committed: " + statusMessage();
    }
    rows.push_back(row);
    ros::WallDuration(0.2).sleep();
    return rows;
  }

  /// A vertex dragged with the mouse in drag mode (chosen from the sheet's menu): pressed at
  /// `from`, moved in `steps` equal moves to `to` (each preview waited for), let go there. Rows:
  /// drag_preview per move, then drag_commit.
  std::vector<Row> mouseDrag(const core::Vec3& from, const core::Vec3& to, int steps)
  {
    MouseGesture gesture;
    gesture.press = from;
    if (!chooseMode("Drag mode", "drag", gesture))
    {
      Row r("drag_commit");
      r.message = "no drag mode: " + statusMessage();
      return { r };
    }
    std::vector<Row> rows;
    feedback_pub_.publish(gesture.down(ros::Time::now()));
    waitFor(
        [&] {
          auto s = status();
          return s && s->dragging;
        },
        5.0);
    for (int i = 1; i <= steps && ros::ok(); ++i)
    {
      const core::Vec3 at = from + (to - from) * (static_cast<double>(i) / steps);
      const uint64_t applied = updatesApplied();
      const int markers = markersSeen();
      const NodeCpu::Sample cpu = cpu_.now();
      const auto t0 = Clock::now();
      feedback_pub_.publish(gesture.moveTo(at, ros::Time::now()));
      Row row("drag_preview", i);
      if (waitFor([&] { return updatesApplied() > applied; }, timeout_))
      {
        row.answer_ms = msSince(t0, statusAt());
        row.markers_ms = markersAfter(t0, markers, 2.0);
        row.success = !std::isnan(row.markers_ms);
        row.message = row.success ? "preview drawn" : "no preview drawn: " + statusMessage();
        row.cpuSince(cpu, cpu_.now());
      }
      else
        row.message = "the interaction node applied no update";
      rows.push_back(row);
    }
    const uint64_t before = revision();
    const int markers = markersSeen();
    const NodeCpu::Sample cpu = cpu_.now();
    const auto t0 = Clock::now();
    feedback_pub_.publish(gesture.upAt(to, ros::Time::now()));
    Row row("drag_commit", steps);
    if (waitFor([&] { return revision() > before; }, std::min(timeout_, 10.0)))
    {
      row.answer_ms = msSince(t0, stateAt());
      row.markers_ms = markersAfter(t0, markers);
      row.cpuSince(cpu, cpu_.now());
      row.success = true;
      row.message = "committed, revision " + std::to_string(revision());
      interactionHas(revision());
    }
    else
      row.message = "nothing committed: " + statusMessage();
    rows.push_back(row);
    waitFor(
        [&] {
          auto s = status();
          return s && !s->dragging;
        },
        5.0);
    return rows;
  }

  PaperState::ConstPtr state()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return state_;
  }
  visualization_msgs::MarkerArray::ConstPtr markers()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return markers_;
  }
  tf2_msgs::TFMessage::ConstPtr takeLargestTf()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto t = largest_tf_;
    largest_tf_.reset();
    return t;
  }
  core::Paper paper()
  {
    auto p = fromMessage(*state());
    return p ? *p : core::Paper{};
  }
  uint64_t revision()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return state_ ? state_->revision : 0;
  }

  ros::NodeHandle& nh_;

private:
  template <class Service>
  Row timedCall(ros::ServiceClient& client, Service& srv, const std::string& action, double step)
  {
    const int markers = markersSeen();
    const uint64_t before = revision();
    const NodeCpu::Sample cpu = cpu_.now();
    const auto t0 = Clock::now();
    Row row(action, step);
    if (!client.call(srv))
    {
      row.answer_ms = msSince(t0);
      row.message = "the call itself failed";
      return row;
    }
    row.answer_ms = msSince(t0);
    row.success = srv.response.success;
    row.message = srv.response.message;
    if (!row.success)
      row.cpuSince(cpu, cpu_.now());  // the user waits for a refusal as for an answer
    else
    {
      row.markers_ms = markersAfter(t0, markers);
      row.cpuSince(cpu, cpu_.now());
      // A commit: the next action waits until the others follow the new state.
      if (srv.response.revision > before && waitFor([&] { return revision() >= srv.response.revision; }, timeout_))
        interactionHas(srv.response.revision);
    }
    return row;
  }

  /// The sheet's menu entry whose title holds `title` chosen (right-click at the press point);
  /// true once the node reports `mode`.
  bool chooseMode(const std::string& title, const std::string& mode, const MouseGesture& gesture)
  {
    int id = -1;
    waitFor(
        [&] {
          std::lock_guard<std::mutex> lock(mutex_);
          for (const auto& [t, i] : menu_)
            if (t.find(title) != std::string::npos)
              id = static_cast<int>(i);
          return id >= 0;
        },
        10.0);
    if (id < 0)
      return false;
    feedback_pub_.publish(gesture.menu(static_cast<uint32_t>(id), gesture.press, ros::Time::now()));
    return waitFor(
        [&] {
          auto s = status();
          return s && s->mode == mode;
        },
        10.0);
  }

  bool interactionHas(uint64_t revision)
  {
    return waitFor(
        [&] {
          auto s = status();
          return s && s->revision >= revision;
        },
        timeout_);
  }

  /// Milliseconds from t0 to the first markers message after `seen` of them; NaN if none came.
  double markersAfter(Clock::time_point t0, int seen, double seconds = -1)
  {
    if (!waitFor([&] { return markersSeen() > seen; }, seconds < 0 ? timeout_ : seconds))
      return NAN;
    std::lock_guard<std::mutex> lock(mutex_);
    return msSince(t0, markers_at_);
  }

  void send(uint8_t type, const core::Vec3& at)
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
    feedback_pub_.publish(f);
  }

  bool waitFor(const std::function<bool()>& done, double seconds)
  {
    const auto until = Clock::now() + std::chrono::duration<double>(seconds);
    while (ros::ok() && Clock::now() < until)
    {
      if (done())
        return true;
      ros::WallDuration(0.0005).sleep();
    }
    return done();
  }

  InteractionStatus::ConstPtr status()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return status_;
  }
  uint64_t updatesApplied()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return status_ ? status_->updates_applied : 0;
  }
  std::string statusMessage()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return status_ ? status_->message : "";
  }
  Clock::time_point statusAt()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return status_at_;
  }
  Clock::time_point stateAt()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return state_at_;
  }
  int markersSeen()
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return markers_seen_;
  }

  double timeout_;
  NodeCpu cpu_;
  ros::Subscriber markers_sub_, state_sub_, status_sub_, tf_sub_, init_sub_;
  std::map<std::string, uint32_t> menu_;  // the sheet's menu entries by title
  ros::Publisher feedback_pub_;
  ros::ServiceClient fold_, rotate_, drag_, undo_;
  std::mutex mutex_;
  int markers_seen_ = 0;
  int markers_seen_at_state_ = 0;  // markers_seen_ when the last state came
  Clock::time_point markers_at_, state_at_, status_at_;
  visualization_msgs::MarkerArray::ConstPtr markers_;
  PaperState::ConstPtr state_;
  InteractionStatus::ConstPtr status_;
  tf2_msgs::TFMessage::ConstPtr largest_tf_;
};

/// The vertex nearest the crease pattern's lower left corner, and a point inside a face at it.
struct Corner
{
  int vertex = -1;
  core::Vec3 click = core::Vec3::Zero();
};

Corner cornerOf(const PaperState& s)
{
  Corner c;
  double best = INFINITY;
  for (size_t v = 0; v < s.vertices_crease_pattern.size(); ++v)
  {
    const double d = s.vertices_crease_pattern[v].x + s.vertices_crease_pattern[v].y;
    if (d < best)
    {
      best = d;
      c.vertex = static_cast<int>(v);
    }
  }
  for (const Face& f : s.faces)
    if (std::find(f.vertices.begin(), f.vertices.end(), c.vertex) != f.vertices.end())
    {
      core::Vec3 centre = core::Vec3::Zero();
      for (int v : f.vertices)
        centre += toVec3(s.vertices_crease_pattern[v]);
      c.click = centre / static_cast<double>(f.vertices.size());
      break;
    }
  return c;
}

/// Folded positions moved by a deterministic pattern of `amount`: a shape the solver must restore.
PaperState perturbed(const PaperState& s, double amount)
{
  PaperState p = s;
  for (size_t v = 0; v < p.vertices_folded.size(); ++v)
  {
    p.vertices_folded[v].x += amount * std::sin(1.7 * v);
    p.vertices_folded[v].y += amount * std::sin(2.3 * v + 1);
    p.vertices_folded[v].z += amount * std::sin(3.1 * v + 2);
  }
  return p;
}

/// spring_solver's limits (its dynamic_reconfigure parameters), for the same solve in this process.
core::SolveLimits springSolverLimits(ros::NodeHandle& nh)
{
  core::SolveLimits limits;
  ros::NodeHandle solver_nh(nh, "spring_solver");
  limits.tolerance = solver_nh.param("tolerance", limits.tolerance);
  limits.max_iterations = solver_nh.param("max_iterations", limits.max_iterations);
  limits.max_seconds = solver_nh.param("max_seconds", limits.max_seconds);
  return limits;
}

struct Breakdown
{
  std::vector<std::pair<std::string, double>> values;
  void add(const std::string& name, double value)
  {
    values.emplace_back(name, value);
  }
};

/// What can be measured from outside the nodes, on the state the pattern is in now.
Breakdown measureBreakdown(UserPath& path, const std::vector<int>& held)
{
  Breakdown b;
  const PaperState::ConstPtr state = path.state();
  const auto markers = path.markers();
  b.add("faces", static_cast<double>(state->faces.size()));
  const auto [state_bytes, state_ser] = serialiseTimed(*state);
  b.add("state_bytes", static_cast<double>(state_bytes));
  b.add("state_serialise_ms", state_ser);
  b.add("state_deserialise_ms", deserialiseTimed(*state));
  if (markers)
  {
    const auto [markers_bytes, markers_ser] = serialiseTimed(*markers);
    b.add("markers_bytes", static_cast<double>(markers_bytes));
    b.add("markers_serialise_ms", markers_ser);
    b.add("markers_deserialise_ms", deserialiseTimed(*markers));
  }
  // A trivial service (this process's own, answered by its spinner over loopback TCP), called
  // as RemoteSolver calls the solver: a new connection each call (master lookup, TCP connect,
  // header exchange), and on a kept connection. (roscpp's get_loggers of paper_model is not
  // used: called while the node logs from another thread, log4cxx crashed it, twice of two.)
  {
    std::vector<double> fresh, kept;
    const std::string name = ros::this_node::getName() + "/trivial";
    ros::ServiceClient persistent = path.nh_.serviceClient<std_srvs::Trigger>(name, true);
    for (int i = 0; i < 20; ++i)
    {
      std_srvs::Trigger t;
      auto t0 = Clock::now();
      const bool fresh_ok = callService(name, t);
      fresh.push_back(fresh_ok ? msSince(t0) : NAN);
      t0 = Clock::now();
      const bool kept_ok = persistent.call(t);
      kept.push_back(kept_ok ? msSince(t0) : NAN);
    }
    b.add("trivial_call_new_connection_ms", median(fresh));
    b.add("trivial_call_persistent_ms", median(kept));
  }
  // What paper_model does to publish a change, done here on the same paper: the state message
  // built from the paper (toMessage), the markers built (paperMarkers); and what every receiver
  // of the state does first (fromMessage, spring_solver too, on every solve).
  if (auto paper = fromMessage(*state))
  {
    std::vector<double> build_state, build_markers, parse;
    for (int i = 0; i < 5; ++i)
    {
      auto t0 = Clock::now();
      const PaperState built = toMessage(*paper, state->revision, {});
      build_state.push_back(msSince(t0));
      t0 = Clock::now();
      const visualization_msgs::MarkerArray drawn = paperMarkers(*paper, MarkerStyle{}, ros::Time::now());
      build_markers.push_back(msSince(t0));
      t0 = Clock::now();
      const auto back = fromMessage(built);
      parse.push_back(msSince(t0));
    }
    b.add("state_build_ms", median(build_state));
    b.add("markers_build_ms", median(build_markers));
    b.add("state_parse_ms", median(parse));
  }
  // One solve of spring_solver through its service, as paper_model calls it (the whole paper
  // both ways, a new connection), against the same solve in this process: converged already
  // (the call's overhead alone), and from a perturbed shape (a real solve).
  const auto solveBoth = [&](const PaperState& input, const std::string& label) {
    Solve call;
    call.request.paper = input;
    call.request.fixed_vertices = held;
    auto t0 = Clock::now();
    const bool called = callService(path.nh_.resolveName("solve"), call);
    b.add("solve_service_" + label + "_ms", called ? msSince(t0) : NAN);
    b.add("solve_service_" + label + "_iterations", called ? call.response.iterations : NAN);
    const auto [request_bytes, request_ser] = serialiseTimed(call.request);
    b.add("solve_request_bytes", static_cast<double>(request_bytes));
    auto paper = fromMessage(input);
    if (!paper)
      return;
    // With spring_solver's own limits (its dynamic_reconfigure parameters).
    std::unique_ptr<core::ShapeSolver> solver = core::makeSolver("newton");
    solver->setLimits(springSolverLimits(path.nh_));
    std::vector<char> fixed(paper->vertices.size(), 0);
    for (int v : held)
      fixed[v] = 1;
    t0 = Clock::now();
    const core::SolveReport report = solver->solve(*paper, fixed);
    b.add("solve_in_process_" + label + "_ms", msSince(t0));
    b.add("solve_in_process_" + label + "_iterations", report.iterations);
  };
  solveBoth(*state, "converged");
  solveBoth(perturbed(*state, 1e-5 * path.paper().scale()), "perturbed");
  const auto tf = path.takeLargestTf();
  b.add("tf_largest_transforms", tf ? static_cast<double>(tf->transforms.size()) : 0.0);
  if (tf)
  {
    const auto [tf_bytes, tf_ser] = serialiseTimed(*tf);
    b.add("tf_largest_bytes", static_cast<double>(tf_bytes));
    b.add("tf_serialise_ms", tf_ser);
  }
  return b;
}

/// The slider's release at `fraction` done in this process as paper_model does it (a session of
/// the loaded paper, the default crease driver and its clone for previews with paper_model's
/// default frame budget, the newton rigid solver with spring_solver's limits): the slide's
/// previews 1 % apart from the flat state, then the release, timed alone: wall and CPU ms (this
/// process is single-threaded here).
Breakdown commitInProcess(const PaperState& flat, double fraction, ros::NodeHandle& nh)
{
  Breakdown b;
  auto paper = fromMessage(flat);
  if (!paper)
    return b;
  core::Session session(std::move(*paper));
  std::shared_ptr<core::ShapeSolver> rigid = core::makeSolver("newton");
  rigid->setLimits(springSolverLimits(nh));
  session.setSolver(rigid);
  std::shared_ptr<core::CreaseDriver> driver = core::makeCreaseDriver();
  std::shared_ptr<core::CreaseDriver> preview = driver->clone();
  core::SolveLimits budget = preview->limits();
  budget.max_seconds = 0.03;  // paper_model's fold_preview_seconds
  preview->setLimits(budget);
  session.setCreaseDrivers(driver, preview);
  const int steps = static_cast<int>(std::lround(100 * fraction));
  for (int k = 1; k <= steps; ++k)
    session.foldByAssignment(fraction * k / steps, false);
  const double cpu0 = static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
  const auto t0 = Clock::now();
  const auto folded = session.foldByAssignment(fraction, true);
  const double wall = msSince(t0);
  const double cpu = (static_cast<double>(std::clock()) / CLOCKS_PER_SEC - cpu0) * 1e3;
  const std::string percent = std::to_string(static_cast<int>(std::lround(100 * fraction)));
  b.add("commit_" + percent + "_in_process_ms", folded ? wall : NAN);
  b.add("commit_" + percent + "_in_process_cpu_ms", folded ? cpu : NAN);
  return b;
}

std::vector<std::string> split(const std::string& list)
{
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty())
      out.push_back(item);
  return out;
}
}  // namespace

int main(int argc, char** argv)
{
  // As the nodes it measures beside its in-process commit (heap_reuse.h).
  numerics::keepFreedMemory(numerics::ThreadHeaps::Shared);
  ros::init(argc, argv, "user_path_bench");
  ros::NodeHandle pnh("~");
  const std::string prefix = pnh.param<std::string>("csv_prefix", "docs/bench/user_path");
  const std::string data_dir = pnh.param<std::string>("data_dir", "");
  const std::string configuration = pnh.param<std::string>("configuration", "journal_sync");
  const std::vector<std::string> patterns = split(pnh.param<std::string>("patterns", "miura,square_twist,waterbomb"));
  // The Miura-ori at every size; the square twist and the waterbomb, whose commits take half a
  // minute at 1,000 vertices (they fold only through strained faces), at their own sizes.
  const std::vector<std::string> sizes = split(pnh.param<std::string>("sizes", "1000,2500,5000,10000"));
  const std::vector<std::string> other_sizes = split(pnh.param<std::string>("other_sizes", "1000"));
  const int steps_40 = pnh.param("slide_steps_40", 40);    // 1 % a move
  const int steps_100 = pnh.param("slide_steps_100", 20);  // 5 % a move
  // A mouse drags a face 10° in about half a second: at paper_model's pace, previews 0.5° apart.
  const int turn_steps = std::max(1, pnh.param("turn_steps", 20));
  const double timeout = pnh.param("timeout", 180.0);      // for any answer; longer is recorded as none
  // "all"; "slider": the slides and their releases alone (no fold commits, turns, drags or
  // breakdown), for measuring the slider's previews in a minute; "turn": the turn alone.
  const std::string actions = pnh.param<std::string>("actions", "all");
  const bool turns_only = actions == "turn";
  const bool everything = actions != "slider" && !turns_only;
  if (data_dir.empty())
  {
    std::fprintf(stderr, "user_path_bench: ~data_dir (paper_model's data folder) is needed\n");
    return 1;
  }
  ros::NodeHandle nh("/origami");
  ros::AsyncSpinner spinner(2);
  spinner.start();
  UserPath path(nh, timeout);
  ros::NodeHandle own("~");
  const ros::ServiceServer trivial = own.advertiseService<std_srvs::Trigger::Request, std_srvs::Trigger::Response>(
      "trivial", boost::function<bool(std_srvs::Trigger::Request&, std_srvs::Trigger::Response&)>(
                     [](std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
                       res.success = true;
                       return true;
                     }));
  if (!path.ready())
    return 1;

  const bool new_csv = !std::filesystem::exists(prefix + ".csv");
  std::ofstream csv(prefix + ".csv", std::ios::app);
  if (new_csv)
    csv << "configuration,pattern,vertices,action,step,answer_ms,markers_ms,success,paper_model_cpu_ms,"
           "spring_solver_cpu_ms,curved_mesh_solver_cpu_ms,interaction_cpu_ms,message\n";
  const bool new_breakdown = !std::filesystem::exists(prefix + "_breakdown.csv");
  std::ofstream breakdown(prefix + "_breakdown.csv", std::ios::app);
  if (new_breakdown)
    breakdown << "configuration,pattern,vertices,quantity,value\n";

  std::vector<std::pair<std::string, std::string>> runs;  // pattern kind, size
  for (const std::string& size : sizes)
    for (const std::string& kind : patterns)
      if (kind == "miura")
        runs.emplace_back(kind, size);
  for (const std::string& size : other_sizes)
    for (const std::string& kind : patterns)
      if (kind != "miura")
        runs.emplace_back(kind, size);
  for (const auto& [kind, size] : runs)
  {
    const std::optional<Pattern> pattern = makePattern(kind, std::stol(size));
    if (!pattern)
      continue;
    const size_t vertices = pattern->tessellation.paper.vertices.size();
    const auto write = [&](const Row& r) {
      csv << configuration << ',' << pattern->name << ',' << vertices << ',' << r.action << ',' << r.step << ','
          << r.answer_ms << ',' << r.markers_ms << ',' << (r.success ? 1 : 0);
      for (double ms : r.cpu_ms)
        csv << ',' << ms;
      csv << ",\"" << excerpt(r.message) << "\"\n";
      csv.flush();
      std::printf("  %-12s %6zu %-18s %5.3g  answer %8.1f ms  markers %8.1f ms  cpu: model %6.0f solver %6.0f "
                  "curved %6.0f interaction %4.0f ms %s\n",
                  pattern->name.c_str(), vertices, r.action.c_str(), r.step, r.answer_ms, r.markers_ms, r.cpu_ms[0],
                  r.cpu_ms[1], r.cpu_ms[2], r.cpu_ms[3], r.success ? "" : excerpt(r.message).c_str());
      std::fflush(stdout);
    };
    const std::string file = writeFold(pattern->tessellation.paper, data_dir, pattern->name);
    Row loaded;
    const bool ok = path.load(file, loaded);
    std::filesystem::remove(data_dir + "/" + file);
    write(loaded);
    if (!ok)
      continue;
    const PaperState flat = *path.state();
    const Corner corner = cornerOf(flat);
    // The slider alone: a user's moment to find it, in which the nodes take in the new pattern
    // (curved_mesh_solver meshes its sheet, paper_model readies the preview driver), as the
    // actions before the slide give them in a whole run.
    if (!everything)
      ros::WallDuration(3.0).sleep();
    // The release at 40 % in this process, the same computation without the nodes around it
    // (the Miura-ori only: the others' commits take half a minute at 1,000 vertices).
    if (kind == "miura" && everything)
      for (const auto& [name, value] : commitInProcess(flat, 0.4, nh).values)
        breakdown << configuration << ',' << pattern->name << ',' << vertices << ',' << name << ',' << value << '\n';

    // fold_by_assignment commits from the flat pattern, each undone.
    for (double fraction : { 0.25, 0.5, 0.99 })
    {
      if (!everything)
        break;
      const Row r = path.fold(fraction, false);
      write(r);
      if (r.success)
        path.undo();
    }
    // The corner face turned to 10° in `turn_steps` previews, then 10° committed, undone.
    if (everything || turns_only)
    {
      Rotate r;
      r.request.face = -1;
      r.request.axis_edge = -1;
      r.request.click = toPoint(corner.click);
      r.request.commit = false;
      for (int i = 1; i <= turn_steps; ++i)
      {
        const double degrees = 10.0 * i / turn_steps;
        r.request.angle = degrees * M_PI / 180.0;
        const Row row = path.rotate(r, degrees);
        write(row);
        if (row.success && r.request.face < 0)
        {
          r.request.face = r.response.face;  // picked once, as a drag does
          r.request.axis_edge = r.response.axis_edge;
        }
      }
      r.request.commit = true;
      const Row row = path.rotate(r, 10);
      write(row);
      if (row.success)
        path.undo();
    }
    if (turns_only)
      continue;
    // The slider to 40 %, released (kept); the corner vertex dragged up from there.
    bool at_40 = false;
    for (const Row& r : path.slide(0.4, steps_40, "slider_release_40"))
    {
      write(r);
      at_40 = r.action == "slider_release_40" && r.success;
    }
    if (at_40 && !everything)
      path.undo();  // back to the flat pattern
    if (at_40 && everything)
    {
      const PaperState folded = *path.state();
      // 0.4 % of the sheet a step, 2 % in all: a mouse drag shorter than 1 % is a click.
      const double span = 0.004 * path.paper().scale();
      DragVertex d;
      d.request.vertex = corner.vertex;
      d.request.commit = false;
      for (int step = 1; step <= 5; ++step)
      {
        d.request.position = folded.vertices_folded[corner.vertex];
        d.request.position.z += step * span;
        write(path.drag(d, step));
      }
      d.request.commit = true;
      const Row row = path.drag(d, 5);
      write(row);
      if (row.success)
        path.undo();
      // The same lift with the mouse, through the interaction node.
      const core::Vec3 from = toVec3(folded.vertices_folded[corner.vertex]);
      bool dragged = false;
      for (const Row& r : path.mouseDrag(from, from + core::Vec3(0, 0, 5 * span), 5))
      {
        write(r);
        dragged = r.action == "drag_commit" && r.success;
      }
      if (dragged)
        path.undo();
      // The breakdown on the 40 % state, the face at the corner held as a turn holds it.
      std::vector<int> held;
      for (const Face& f : folded.faces)
        if (std::find(f.vertices.begin(), f.vertices.end(), corner.vertex) != f.vertices.end())
        {
          held.assign(f.vertices.begin(), f.vertices.end());
          break;
        }
      const Breakdown b = measureBreakdown(path, held);
      for (const auto& [name, value] : b.values)
        breakdown << configuration << ',' << pattern->name << ',' << vertices << ',' << name << ',' << value << '\n';
      breakdown.flush();
      path.undo();  // back to the flat pattern
    }
    // The slider from 0 to 100 %, released.
    bool released = false;
    for (const Row& r : path.slide(1.0, steps_100, "slider_release_100"))
    {
      write(r);
      released = r.action == "slider_release_100" && r.success;
    }
    // Flicked from 0 to 100 % in one move (faster than a frame: one preview, far behind the
    // handle), let go at once, and let go after half a second held still (its previews catch up).
    for (const auto& [hold, release] : { std::pair<double, const char*>{ 0.0, "slider_flick_release" },
                                         std::pair<double, const char*>{ 0.5, "slider_flick_held_release" } })
    {
      // From the flat pattern: the last release undone (where it was refused, nothing to undo).
      if (!released || !path.undo())
        break;
      released = false;
      for (const Row& r : path.slide(1.0, 1, release, hold, "slider_flick_preview"))
      {
        write(r);
        released = r.action == release && r.success;
      }
    }
  }
  std::printf("wrote %s.csv and %s_breakdown.csv\n", prefix.c_str(), prefix.c_str());
  return 0;
}
