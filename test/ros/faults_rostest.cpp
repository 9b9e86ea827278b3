// rostest: service faults (issue 10). Every field of every service gets NaN, ±inf and ±1e300;
// ids go out of range; load gets files that are not FOLD (a device, a directory, garbage);
// the solver gets malformed papers; several clients call at once; and the spring solver,
// switched to the seed's scheme, diverges mid-rotation. Whatever happens, each request is
// answered, a refusal changes nothing, and the published state stays a valid model.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <future>
#include <limits>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <thread>

#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/callback_queue.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <virtual_origami/Load.h>
#include <virtual_origami/Operation.h>
#include <virtual_origami/PinVertex.h>
#include <virtual_origami/Pull.h>
#include <virtual_origami/Save.h>
#include <virtual_origami/Solve.h>

#include "ros_test_client.h"
#include "../unit/test_models.h"
#include "virtual_origami/core/data_folder.h"
#include "virtual_origami/core/rotate.h"
#include "virtual_origami/core/tessellations.h"
#include "virtual_origami/core/validity.h"
#include "virtual_origami/solvers/newton_solver.h"
#include "virtual_origami/ros/conversions.h"

using namespace virtual_origami;
using virtual_origami::test::PaperClient;
using virtual_origami::test::waitFor;

namespace
{
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
const std::vector<double> kBadValues{ kNaN, kInf, -kInf, 1e300, -1e300 };
const std::vector<int> kBadIds{ -2, -1000, INT_MIN, INT_MAX, 1000000 };

std::string show(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}

double& field(geometry_msgs::Point& p, int axis)
{
  return axis == 0 ? p.x : axis == 1 ? p.y : p.z;
}

/// The published state is a model that satisfies the invariants.
void expectValidState(const PaperState& state, const std::string& context)
{
  const core::Expected<core::Paper> paper = fromMessage(state);
  ASSERT_TRUE(paper.ok()) << context << ": " << paper.message();
  const core::ValidityReport report = core::checkValidity(*paper);
  EXPECT_TRUE(report.ok()) << context << ": " << report.summary();
}

bool sameGeometry(const PaperState& a, const PaperState& b)
{
  return a.vertices_folded == b.vertices_folded && a.vertices_crease_pattern == b.vertices_crease_pattern &&
         a.edges == b.edges && a.faces == b.faces && a.pins == b.pins;
}

/// Sets spring_solver's parameters through dynamic_reconfigure's own service.
void configureSolver(const std::string& solver, int max_iterations)
{
  dynamic_reconfigure::Reconfigure srv;
  dynamic_reconfigure::StrParameter name;
  name.name = "solver";
  name.value = solver;
  srv.request.config.strs.push_back(name);
  dynamic_reconfigure::IntParameter iterations;
  iterations.name = "max_iterations";
  iterations.value = max_iterations;
  srv.request.config.ints.push_back(iterations);
  const std::string service = "/origami/spring_solver/set_parameters";
  ASSERT_TRUE(ros::service::waitForService(service, ros::Duration(30)));
  ASSERT_TRUE(callService(service, srv));
  bool applied = false;
  for (const auto& s : srv.response.config.strs)
    applied = applied || (s.name == "solver" && s.value == solver);
  ASSERT_TRUE(applied) << "spring_solver did not take solver " << solver;
}

class Faults : public ::testing::Test
{
protected:
  void SetUp() override
  {
    // The announcements are collected on a queue of their own, spun by its own thread, so
    // they keep coming while client threads call (the main queue is PaperClient's).
    ops_nh_.setCallbackQueue(&ops_queue_);
    ops_sub_ = ops_nh_.subscribe<Operation>("operations", 1000, [this](const Operation::ConstPtr& op) {
      std::lock_guard<std::mutex> lock(ops_mutex_);
      operations_.push_back(*op);
    });
    ops_spinner_.start();
    ASSERT_TRUE(waitFor([&] { return ops_sub_.getNumPublishers() > 0; }));
    const uint64_t latched = client_.state().revision;
    ASSERT_TRUE(client_.trigger("reset").response.success);
    revision_ = latched + 1;
    client_.stateAt(revision_);
  }

  /// A committed change happened: the next state has the next revision.
  const PaperState& advanced(uint64_t response_revision)
  {
    EXPECT_EQ(response_revision, revision_ + 1);
    ++revision_;
    return client_.stateAt(revision_);
  }

  /// Either refused with a message and nothing changed, or done and the state is valid (then
  /// undone, so the next case starts from the same model). Returns whether it was done.
  template <class Response>
  bool refusedOrValid(const Response& response, const PaperState& before, const std::string& context)
  {
    if (!response.success)
    {
      EXPECT_FALSE(response.message.empty()) << context;
      ros::WallDuration(0.05).sleep();
      ros::spinOnce();
      const PaperState& now = client_.state();
      EXPECT_EQ(now.revision, before.revision) << context;
      EXPECT_TRUE(sameGeometry(now, before)) << context << ": a refused request changed the model";
      return false;
    }
    const PaperState& after = advanced(revision_ + 1);
    expectValidState(after, context);
    const std_srvs::Trigger undone = client_.trigger("undo");
    EXPECT_TRUE(undone.response.success) << context << ": " << undone.response.message;
    const PaperState& back = advanced(revision_ + 1);
    EXPECT_TRUE(sameGeometry(back, before)) << context << ": undo did not restore the model";
    return true;
  }

  /// The node still answers and folds as before.
  void expectAlive()
  {
    const Crease probe = client_.crease(0.3, -0.1, 0.3, 1.1);
    ASSERT_TRUE(probe.response.success) << probe.response.message;
    advanced(probe.response.revision);
    ASSERT_TRUE(client_.trigger("undo").response.success);
    advanced(revision_ + 1);
  }

  PaperClient client_;
  uint64_t revision_ = 0;
  ros::NodeHandle ops_nh_{ "/origami" };
  ros::CallbackQueue ops_queue_;
  ros::AsyncSpinner ops_spinner_{ 1, &ops_queue_ };
  ros::Subscriber ops_sub_;
  std::mutex ops_mutex_;
  std::vector<Operation> operations_;
};

/// A 400-vertex Miura-ori, flat, each vertex moved by up to `shake` of the sheet (seeded).
core::Paper shakenMiura(unsigned seed, double shake)
{
  core::Paper paper = core::tessellationWithVertices(core::TessellationKind::Miura, 400).value().paper;
  std::srand(seed);
  for (core::Vertex& v : paper.vertices)
    v.folded += shake * paper.scale() * core::Vec3::Random();
  return paper;
}
}  // namespace

TEST_F(Faults, CreaseFieldsNonFiniteOrHuge)
{
  ASSERT_TRUE(client_.crease(0.5, -0.1, 0.5, 1.1).response.success);
  const PaperState before = advanced(revision_ + 1);
  int done = 0, cases = 0;
  for (double bad : kBadValues)
    for (int f = 0; f < 9; ++f)  // start x y z, end x y z, eye x y z
    {
      Crease::Request r;
      r.start.x = 0.25;
      r.start.y = -0.1;
      r.end.x = 0.25;
      r.end.y = 1.1;
      r.has_eye = f >= 6;
      r.eye.x = 0.25;
      r.eye.y = 0.5;
      r.eye.z = 2.0;
      r.snap = (f % 2) == 0;
      field(f < 3 ? r.start : f < 6 ? r.end : r.eye, f % 3) = bad;
      const std::string context = "crease field " + std::to_string(f) + " = " + show(bad);
      const Crease c = client_.call<Crease>("crease", r);
      if (!std::isfinite(bad))
      {
        EXPECT_FALSE(c.response.success) << context;
      }
      done += refusedOrValid(c.response, before, context);
      ++cases;
    }
  std::printf("faults: crease, %d cases of bad values, %d went through (huge but finite) and were valid\n", cases, done);
  RecordProperty("crease_cases", cases);
  RecordProperty("crease_done", done);
  expectAlive();
}

TEST_F(Faults, RotateFieldsNonFiniteHugeOrOutOfRange)
{
  ASSERT_TRUE(client_.crease(0.5, -0.1, 0.5, 1.1).response.success);
  const PaperState before = advanced(revision_ + 1);
  for (bool commit : { false, true })
  {
    for (double bad : kBadValues)
      for (int f = 0; f < 4; ++f)  // click x y z, angle
      {
        Rotate::Request r;
        r.face = -1;
        r.axis_edge = -1;
        r.click.x = 0.8;
        r.click.y = 0.5;
        r.angle = 0.5;
        r.commit = commit;
        if (f < 3)
          field(r.click, f) = bad;
        else
          r.angle = bad;
        const std::string context = std::string(commit ? "rotate" : "preview") + " field " + std::to_string(f) +
                                    " = " + show(bad);
        const Rotate res = client_.call<Rotate>("rotate", r);
        if (!std::isfinite(bad) || f == 3)
        {
          EXPECT_FALSE(res.response.success) << context;  // ±1e300 rad is no angle either
        }
        if (!commit)
        {
          EXPECT_EQ(res.response.revision, before.revision) << context;
        }
        else
          refusedOrValid(res.response, before, context);
      }
    for (int bad : kBadIds)
      for (int which = 0; which < 2; ++which)
      {
        Rotate::Request r;
        r.face = which == 0 ? bad : -1;
        r.axis_edge = which == 1 ? bad : -1;
        r.click.x = 0.8;
        r.click.y = 0.5;
        r.angle = 0.5;
        r.commit = commit;
        const Rotate res = client_.call<Rotate>("rotate", r);
        const std::string context = std::string(which == 0 ? "face " : "axis ") + std::to_string(bad);
        EXPECT_FALSE(res.response.success) << context;
        refusedOrValid(res.response, before, context);
      }
  }
  expectAlive();
}

TEST_F(Faults, PinLoadSaveBadInput)
{
  const PaperState before = client_.stateAt(revision_);
  for (int bad : kBadIds)
    for (bool release : { false, true })
    {
      PinVertex::Request pin;
      pin.vertex = bad == -2 ? 4 : bad;  // 4: one past the square's vertices
      pin.release = release;
      const PinVertex res = client_.call<PinVertex>("pin", pin);
      EXPECT_FALSE(res.response.success) << "pin vertex " << pin.vertex;
      refusedOrValid(res.response, before, "pin vertex " + std::to_string(pin.vertex));
    }

  // Files that are not FOLD models: each refused with a message, nothing changed.
  // In the data folder (ROS_HOME is the suite's own), so that their content is what refuses them.
  const std::string dir = core::defaultDataFolder() + "/faults_" + std::to_string(::getpid());
  ::mkdir(dir.c_str(), 0755);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
    return dir + "/" + name;
  };
  const std::vector<std::string> paths{
    "",
    "/nonexistent/x.fold",
    dir,  // a directory
    "/dev/zero",  // endless: must not be read to the end
    "/dev/null",
    write("garbage.fold", "\x01\x02 not json {{{"),
    write("huge_number.fold", R"({"vertices_coords": [[0,0],[1e999,0],[1,1]], "faces_vertices": [[0,1,2]]})"),
    write("huge.fold", R"({"vertices_coords": [[0,0],[1e300,0],[1e300,1e300],[0,1e300]],
                          "faces_vertices": [[0,1,2,3]]})"),
    write("tiny.fold", R"({"vertices_coords": [[0,0],[1e-300,0],[1e-300,1e-300],[0,1e-300]],
                          "faces_vertices": [[0,1,2,3]]})"),
    write("bad_ids.fold", R"({"vertices_coords": [[0,0],[1,0],[1,1]], "faces_vertices": [[0,1,2147483647]]})"),
    write("empty.fold", "{}"),
  };
  for (const std::string& path : paths)
  {
    Load::Request load;
    load.path = path;
    const Load res = client_.call<Load>("load", load);
    refusedOrValid(res.response, before, "load " + path);
  }
  for (const std::string& path : { std::string(""), std::string("/nonexistent/x.fold"), dir + "/x.txt",
                                   std::string("/proc/x.fold"), dir })
  {
    Save::Request save;
    save.path = path;
    const Save res = client_.call<Save>("save", save);
    EXPECT_FALSE(res.response.success) << "save " << path;
    EXPECT_FALSE(res.response.message.empty());
  }
  EXPECT_TRUE(sameGeometry(client_.state(), before));
  expectAlive();
}

// Found by the round-3 probe: a load of a FIFO named *.cp or *.opx never answered, and while
// 4 + 2 such loads waited, crease and undo from other clients got no answer for 15 s.
TEST_F(Faults, AFifoIsRefusedAtOnceAndHoldsUpNoOne)
{
  const std::string dir = core::defaultDataFolder() + "/faults_fifo_" + std::to_string(::getpid());
  ::mkdir(dir.c_str(), 0755);
  std::vector<std::string> fifos;
  for (const char* name : { "pipe.cp", "pipe.opx", "pipe.fold" })
  {
    fifos.push_back(dir + "/" + name);
    ASSERT_EQ(::mkfifo(fifos.back().c_str(), 0600), 0) << fifos.back();
  }
  // More loads than the node has threads (4 by default). (A FIFO's refusal comes at once: with
  // ros::service::call, roscpp lost one of them in CI; callService says why.)
  std::vector<std::future<std::pair<bool, Load::Response>>> loads;
  for (int i = 0; i < 6; ++i)
    loads.push_back(std::async(std::launch::async, [path = fifos[i % fifos.size()]] {
      Load srv;
      srv.request.path = path;
      const bool called = callService("/origami/load", srv);
      return std::make_pair(called, srv.response);
    }));
  auto crease = std::async(std::launch::async, [] {
    Crease srv;
    srv.request.start.x = srv.request.end.x = 0.4;
    srv.request.start.y = -0.1;
    srv.request.end.y = 1.1;
    const bool called = callService("/origami/crease", srv);
    return std::make_pair(called, srv.response);
  });
  // Whatever the test finds, no call is left waiting on a FIFO: each gets a writer that closes
  // at once (before the futures above, which wait for their calls, go).
  struct Unblock
  {
    const std::vector<std::string>& fifos;
    std::vector<std::future<std::pair<bool, Load::Response>>>& loads;
    ~Unblock()
    {
      const auto answered = [&] {
        for (auto& load : loads)
          if (load.valid() && load.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
            return false;
        return true;
      };
      for (int round = 0; round < 300 && !answered(); ++round)
      {
        for (const std::string& fifo : fifos)
        {
          const int fd = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
          if (fd >= 0)
            ::close(fd);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
    }
  } unblock{ fifos, loads };
  ASSERT_EQ(crease.wait_for(std::chrono::seconds(10)), std::future_status::ready);
  const auto [creased, crease_response] = crease.get();
  ASSERT_TRUE(creased);
  ASSERT_TRUE(crease_response.success) << crease_response.message;
  advanced(crease_response.revision);
  for (auto& load : loads)
  {
    ASSERT_EQ(load.wait_for(std::chrono::seconds(10)), std::future_status::ready);
    const auto [called, response] = load.get();
    EXPECT_TRUE(called);
    EXPECT_FALSE(response.success);
    EXPECT_NE(response.message.find("not a regular file"), std::string::npos) << response.message;
  }
  ASSERT_TRUE(client_.trigger("undo").response.success);
  advanced(revision_ + 1);
  for (const std::string& fifo : fifos)
    std::remove(fifo.c_str());
  ::rmdir(dir.c_str());
}

// Found by the round-3 probe: a 30,000-line parallel-crease .cp answered "loaded ..." with the
// revision and the paper unchanged. A load makes a new revision with the file's paper, or is
// refused with nothing changed; a load of the paper as it is is refused.
TEST_F(Faults, ALoadChangesThePaperOrIsRefused)
{
  const std::string name = "parallel_" + std::to_string(::getpid()) + ".cp";
  const std::string path = core::defaultDataFolder() + "/" + name;
  {
    std::ofstream cp(path);
    cp << "1 0 0 1 0\n1 1 0 1 1\n1 1 1 0 1\n1 0 1 0 0\n";
    constexpr int kLines = 30000;
    for (int i = 1; i <= kLines; ++i)
    {
      const double x = static_cast<double>(i) / (kLines + 1);
      cp << (i % 2 ? 2 : 3) << " " << x << " 0 " << x << " 1\n";
    }
  }
  const PaperState before = client_.stateAt(revision_);
  Load::Request load;
  load.path = name;
  const Load first = client_.call<Load>("load", load);
  if (first.response.success)
  {
    const PaperState& loaded = client_.stateAt(revision_ + 1);
    ++revision_;
    EXPECT_EQ(loaded.faces.size(), 30001u);
    // The same file again: the paper as it is, so nothing loaded and no revision.
    const Load again = client_.call<Load>("load", load);
    EXPECT_FALSE(again.response.success);
    EXPECT_NE(again.response.message.find("nothing loaded"), std::string::npos) << again.response.message;
    ros::WallDuration(0.3).sleep();
    ros::spinOnce();
    EXPECT_EQ(client_.state().revision, revision_);
  }
  else
  {
    EXPECT_FALSE(first.response.message.empty());
    ros::WallDuration(0.3).sleep();
    ros::spinOnce();
    EXPECT_EQ(client_.state().revision, before.revision);
    EXPECT_TRUE(sameGeometry(client_.state(), before)) << first.response.message;
  }
  std::remove(path.c_str());
  // The sheet saved and loaded back: the paper as it is.
  ASSERT_TRUE(client_.trigger("reset").response.success);
  advanced(revision_ + 1);
  Save::Request save;
  save.path = "faults_sheet.fold";
  ASSERT_TRUE(client_.call<Save>("save", save).response.success);
  load.path = save.path;
  const Load same = client_.call<Load>("load", load);
  EXPECT_FALSE(same.response.success);
  EXPECT_NE(same.response.message.find("nothing loaded"), std::string::npos) << same.response.message;
  std::remove((core::defaultDataFolder() + "/faults_sheet.fold").c_str());
  expectAlive();
}

TEST_F(Faults, SolverGetsMalformedPapers)
{
  ASSERT_TRUE(client_.crease(0.5, -0.1, 0.5, 1.1).response.success);
  const PaperState good = advanced(revision_ + 1);
  std::vector<Solve::Request> requests;
  for (double bad : kBadValues)
  {
    Solve::Request r;
    r.paper = good;
    field(r.paper.vertices_folded[1], 0) = bad;
    requests.push_back(r);
    r.paper = good;
    field(r.paper.vertices_crease_pattern[2], 1) = bad;
    requests.push_back(r);
  }
  for (int bad : kBadIds)
  {
    Solve::Request r;
    r.paper = good;
    r.paper.faces[0].vertices[0] = bad;  // a face naming a vertex that does not exist
    requests.push_back(r);
    r.paper = good;
    r.paper.edges[0].v1 = bad;
    requests.push_back(r);
    r.paper = good;
    r.fixed_vertices = { 0, bad };
    requests.push_back(r);
  }
  Solve::Request r;
  r.paper = good;
  r.paper.vertices_folded.pop_back();  // lengths differ
  requests.push_back(r);
  r.paper = good;
  r.paper.edges[0].assignment = "Q";
  requests.push_back(r);
  r.paper = PaperState();  // empty
  requests.push_back(r);
  r.paper = good;
  r.paper.faces[1].vertices.assign(100000, 0);  // large and degenerate
  requests.push_back(r);
  for (size_t i = 0; i < requests.size(); ++i)
  {
    Solve srv;
    srv.request = requests[i];
    ASSERT_TRUE(ros::service::waitForService("/origami/solve", ros::Duration(30)));
    ASSERT_TRUE(callService("/origami/solve", srv)) << "request " << i << ": the solver died";
    if (srv.response.success)
      for (const auto& p : srv.response.positions)
        EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << "request " << i;
    else
      EXPECT_FALSE(srv.response.message.empty()) << "request " << i;
  }
  // A looser tolerance that is not a strain of 0 or more is refused.
  for (double bad : { -1e-8, double(NAN), double(INFINITY) })
  {
    Solve loose;
    loose.request.paper = good;
    loose.request.looser_tolerance = bad;
    ASSERT_TRUE(callService("/origami/solve", loose));
    EXPECT_FALSE(loose.response.success) << bad;
    EXPECT_NE(loose.response.message.find("looser tolerance"), std::string::npos) << loose.response.message;
  }
  // The solver still serves paper_model.
  Solve fine;
  fine.request.paper = good;
  ASSERT_TRUE(callService("/origami/solve", fine));
  EXPECT_TRUE(fine.response.success) << fine.response.message;
}

namespace
{
/// Records the paper and held vertices a solve is asked for, solving nothing.
struct SolveRecorder : core::ShapeSolver
{
  core::Paper paper;
  std::vector<char> fixed;
  std::string name() const override { return "recorder"; }
  core::SolveReport solve(core::Paper& asked, const std::vector<char>& held) override
  {
    paper = asked;
    fixed = held;
    return core::SolveReport{};
  }
};
}  // namespace

/// A drag's frame balanced to the solver's own tolerance reaches the solver as one (Solve's
/// `frame` at looser_tolerance 0; a turn's first preview asks it so, core/rotate.cpp): at the
/// frames' lower damping floor. The start a 1,100-vertex Miura-ori's corner face turned 0.5° off
/// the flat sheet gives the solver: as a frame it is balanced to the tolerance in fewer than half
/// the iterations the same request takes as a commit, whose steps creep there (24 against 61 in
/// process).
TEST_F(Faults, SolverBalancesAFrameAtItsOwnToleranceAsAFrame)
{
  const core::Paper flat = core::tessellationWithVertices(core::TessellationKind::Miura, 1100).value().paper;
  core::RotateRequest turn;
  turn.face = 0;
  turn.axis_edge = core::test::slantedCreaseOf(flat, 0);
  ASSERT_GE(turn.axis_edge, 0);
  turn.angle = 0.5 * M_PI / 180;
  SolveRecorder recorder;
  core::Paper turned = flat;
  ASSERT_FALSE(core::rotate(turned, turn, &recorder, {}, core::TurnGuide{}, core::TurnStart{}, 1e-8));
  ASSERT_EQ(recorder.paper.vertices.size(), flat.vertices.size());
  Solve frame;
  frame.request.paper = toMessage(recorder.paper, 0, {});
  for (size_t v = 0; v < recorder.fixed.size(); ++v)
    if (recorder.fixed[v])
      frame.request.fixed_vertices.push_back(static_cast<int>(v));
  ASSERT_FALSE(frame.request.fixed_vertices.empty());
  frame.request.frame = true;
  Solve commit;
  commit.request = frame.request;
  commit.request.frame = false;
  ASSERT_TRUE(callService("/origami/solve", frame));
  ASSERT_TRUE(callService("/origami/solve", commit));
  EXPECT_TRUE(frame.response.success) << frame.response.message;
  EXPECT_LE(frame.response.max_strain, 1e-10);  // spring_solver's tolerance, not a looser one
  EXPECT_LT(2 * frame.response.iterations, commit.response.iterations) << commit.response.message;
}

/// A closure's stall window reaches the solver through the service (fold by assignment's closures
/// run in spring_solver): with two faces of a shaken Miura-ori held, no rigid state exists, and
/// the solve stops once its energy stops falling instead of running to its limits. A negative
/// window is refused.
TEST_F(Faults, SolverStopsAStalledSolveWhenAsked)
{
  const core::Paper paper = shakenMiura(7, 0.03);
  Solve stalled, to_limit;
  stalled.request.paper = toMessage(paper, 0, {});
  for (int v : paper.faces.front().vertices)
    stalled.request.fixed_vertices.push_back(v);
  for (int v : paper.faces.back().vertices)
    stalled.request.fixed_vertices.push_back(v);
  to_limit.request = stalled.request;
  stalled.request.stall_window = 30;
  ASSERT_TRUE(callService("/origami/solve", stalled));
  ASSERT_TRUE(callService("/origami/solve", to_limit));
  EXPECT_FALSE(stalled.response.success);
  EXPECT_NE(stalled.response.message.find("stalled"), std::string::npos) << stalled.response.message;
  EXPECT_LE(stalled.response.iterations, 60);
  EXPECT_FALSE(to_limit.response.success);
  EXPECT_GT(to_limit.response.iterations, 2 * stalled.response.iterations) << to_limit.response.message;
  Solve negative;
  negative.request = stalled.request;
  negative.request.stall_window = -1;
  ASSERT_TRUE(callService("/origami/solve", negative));
  EXPECT_FALSE(negative.response.success);
  EXPECT_NE(negative.response.message.find("stall window"), std::string::npos) << negative.response.message;
}

// A prepare asks the solver to ready itself for a pattern (paper_model does it for a pattern just
// loaded): it answers success with the positions as given, and the solve after it is the one a
// solve alone gives.
TEST_F(Faults, SolverPreparedForAPatternMovesNothingAndSolvesAsBefore)
{
  const core::Paper paper = shakenMiura(11, 0.001);
  Solve prepare, solve;
  prepare.request.paper = toMessage(paper, 0, {});
  prepare.request.prepare = true;
  ASSERT_TRUE(callService("/origami/solve", prepare));
  EXPECT_TRUE(prepare.response.success) << prepare.response.message;
  ASSERT_EQ(prepare.response.positions.size(), paper.vertices.size());
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    EXPECT_EQ(toVec3(prepare.response.positions[v]), paper.vertices[v].folded) << "vertex " << v;
  EXPECT_EQ(prepare.response.iterations, 0);

  solve.request.paper = prepare.request.paper;
  ASSERT_TRUE(callService("/origami/solve", solve));
  EXPECT_TRUE(solve.response.success) << solve.response.message;
  core::Paper alone = paper;
  core::NewtonSolver solver;
  core::SolveLimits limits = solver.limits();
  limits.tolerance = 1e-10;  // spring_solver's
  limits.max_iterations = 1000;
  solver.setLimits(limits);
  const core::SolveReport report = solver.solve(alone, {});
  ASSERT_TRUE(report.converged) << report.message;
  ASSERT_EQ(solve.response.positions.size(), alone.vertices.size());
  double largest = 0.0;
  for (size_t v = 0; v < alone.vertices.size(); ++v)
    largest = std::max(largest, (toVec3(solve.response.positions[v]) - alone.vertices[v].folded).norm());
  EXPECT_LE(largest, 1e-9 * paper.scale());
}

TEST_F(Faults, SolverRefusesPapersThatAreNotOne)
{
  ASSERT_TRUE(client_.crease(0.5, -0.1, 0.5, 1.1).response.success);
  const PaperState good = advanced(revision_ + 1);
  std::vector<Solve::Request> requests(3);
  requests[0].paper = PaperState();  // empty: nothing to solve
  requests[1].paper = good;
  requests[1].paper.edges[0].face_left = 1000000000;  // a face that does not exist
  requests[2].paper = good;
  requests[2].paper.edges[0].face_right = requests[2].paper.edges[0].face_left;  // not the edge's faces
  for (size_t i = 0; i < requests.size(); ++i)
  {
    Solve srv;
    srv.request = requests[i];
    ASSERT_TRUE(callService("/origami/solve", srv)) << "request " << i << ": the solver died";
    EXPECT_FALSE(srv.response.success) << "request " << i;
    EXPECT_FALSE(srv.response.message.empty()) << "request " << i;
  }
}

TEST_F(Faults, APullOfNothingMakesNoRevision)
{
  const PaperState before = client_.state();
  Pull::Request nothing;
  const Pull pulled = client_.call<Pull>("pull", nothing);
  EXPECT_FALSE(pulled.response.success);
  EXPECT_FALSE(pulled.response.message.empty());
  EXPECT_EQ(pulled.response.revision, before.revision);
  ros::WallDuration(0.3).sleep();
  ros::spinOnce();
  EXPECT_EQ(client_.state().revision, before.revision);
}

TEST_F(Faults, ConcurrentClients)
{
  ASSERT_TRUE(client_.crease(0.5, -0.1, 0.5, 1.1).response.success);
  advanced(revision_ + 1);
  const uint64_t start = revision_;
  constexpr int kClients = 4, kCalls = 30;
  std::mutex mutex;
  std::vector<uint64_t> committed;  // revisions of the successful committing calls
  std::atomic<int> transport_failures{ 0 };
  std::vector<std::thread> threads;
  for (int c = 0; c < kClients; ++c)
    threads.emplace_back([&, c] {
      // Each client its own handle and persistent connections, as a robot's node holds them: a
      // connection and a master lookup per call made the machine's load, not paper_model,
      // the thing measured (a call was lost to it once, in a ctest run on a loaded machine).
      ros::NodeHandle nh("/origami");
      ros::ServiceClient crease = nh.serviceClient<Crease>("crease", true);
      ros::ServiceClient rotate = nh.serviceClient<Rotate>("rotate", true);
      ros::ServiceClient undo = nh.serviceClient<std_srvs::Trigger>("undo", true);
      ros::ServiceClient redo = nh.serviceClient<std_srvs::Trigger>("redo", true);
      std::mt19937 rng(1000 + c);
      std::uniform_real_distribution<double> u(0.05, 0.95);
      for (int i = 0; i < kCalls; ++i)
      {
        bool ok = false, success = false, commits = true;
        uint64_t revision = 0;
        switch (rng() % 5)
        {
          case 0:
          {
            Crease srv;
            const double x = u(rng);
            srv.request.start.x = x;
            srv.request.start.y = -0.1;
            srv.request.end.x = x;
            srv.request.end.y = 1.1;
            ok = crease.call(srv);
            success = srv.response.success;
            revision = srv.response.revision;
            break;
          }
          case 1:
          case 2:
          {
            Rotate srv;
            srv.request.face = -1;
            srv.request.axis_edge = -1;
            srv.request.click.x = u(rng);
            srv.request.click.y = u(rng);
            srv.request.angle = (u(rng) - 0.5) * 0.5;
            srv.request.commit = rng() % 2;
            commits = srv.request.commit;
            ok = rotate.call(srv);
            success = srv.response.success;
            revision = srv.response.revision;
            break;
          }
          default:
          {
            std_srvs::Trigger srv;
            ok = (rng() % 2 ? undo : redo).call(srv);
            success = srv.response.success;
            commits = false;  // Trigger answers carry no revision; counted from the topic below
            if (success)
            {
              std::lock_guard<std::mutex> lock(mutex);
              committed.push_back(0);
            }
            break;
          }
        }
        if (!ok)
          ++transport_failures;
        if (ok && success && commits)
        {
          std::lock_guard<std::mutex> lock(mutex);
          committed.push_back(revision);
        }
      }
    });
  for (auto& t : threads)
    t.join();
  EXPECT_EQ(transport_failures.load(), 0);
  // Every committed change made its own revision: no two answers share one.
  std::set<uint64_t> revisions;
  for (uint64_t r : committed)
    if (r != 0)
    {
      EXPECT_TRUE(revisions.insert(r).second) << "two changes answered revision " << r;
    }
  const uint64_t end = start + committed.size();
  const PaperState& last = client_.stateAt(end);
  EXPECT_EQ(last.revision, end);
  expectValidState(last, "after concurrent clients");
  // Every change was announced once, in order.
  const auto announced = [&] {
    std::lock_guard<std::mutex> lock(ops_mutex_);
    std::vector<uint64_t> revisions;
    for (const Operation& op : operations_)
      if (op.revision > start)
        revisions.push_back(op.revision);
    return revisions;
  };
  ASSERT_TRUE(waitFor([&] { return announced().size() >= committed.size(); }));
  const std::vector<uint64_t> ops = announced();
  ASSERT_EQ(ops.size(), committed.size());
  for (size_t i = 0; i < ops.size(); ++i)
    EXPECT_EQ(ops[i], start + 1 + i);
  std::printf("faults: %d clients x %d calls at once, %zu changes committed, each its own revision\n", kClients, kCalls,
              committed.size());
  RecordProperty("concurrent_calls", kClients * kCalls);
  RecordProperty("concurrent_commits", static_cast<int>(committed.size()));
  revision_ = end;
}

TEST_F(Faults, DivergingSolverIsRolledBack)
{
  // A degree-4 vertex at the centre; turning the top-right face about its half crease moves
  // every other face through the solver. Horizontal creases on the right add nine vertices to
  // the left-bottom face's side on x = 0.5: with that free face of 13 vertices the largest
  // spring stiffness eigenvalue is about 16, past the seed scheme's stability limit of 10
  // (seed_spring_solver.h); without them it is about 9 and the scheme only crawls.
  ASSERT_TRUE(client_.crease(0.5, -0.1, 0.5, 1.1).response.success);
  const Crease half = client_.crease(0.5, 0.5, 1.0, 0.8);
  ASSERT_TRUE(half.response.success);
  ASSERT_EQ(half.response.new_edges.size(), 1u);
  const int axis = half.response.new_edges[0];  // named: the automatic axis would be x = 0.5
  ASSERT_TRUE(client_.crease(0.5, 0.5, 0.0, 0.9).response.success);
  for (int k = 1; k <= 9; ++k)
  {
    const double y = 0.045 * k;
    const Crease c = client_.crease(0.45, y, 1.1, y);
    ASSERT_TRUE(c.response.success) << "y = " << y << ": " << c.response.message;
  }
  revision_ += 12;
  const PaperState before = client_.stateAt(revision_);

  // The drag starts with the default solver: the previews work.
  const Rotate first = client_.rotate(-1, axis, 0.9, 0.9, 0.1, false);
  ASSERT_TRUE(first.response.success) << first.response.message;
  // Mid-drag the solver becomes the seed's scheme with a small budget: it diverges.
  configureSolver("seed_spring", 2000);
  for (double angle : { 0.2, 0.3 })
  {
    const Rotate diverged = client_.rotate(first.response.face, first.response.axis_edge, 0.9, 0.9, angle, false);
    EXPECT_FALSE(diverged.response.success);
    EXPECT_NE(diverged.response.message.find("diverged"), std::string::npos) << diverged.response.message;
    EXPECT_EQ(diverged.response.revision, before.revision);
  }
  // The release commits: refused, reported, and the model stays at its last good state.
  const Rotate release = client_.rotate(first.response.face, first.response.axis_edge, 0.9, 0.9, 0.3, true);
  EXPECT_FALSE(release.response.success);
  EXPECT_NE(release.response.message.find("rolled back"), std::string::npos) << release.response.message;
  EXPECT_NE(release.response.message.find("stability limit"), std::string::npos) << release.response.message;
  EXPECT_EQ(release.response.revision, before.revision);
  ros::WallDuration(0.3).sleep();
  ros::spinOnce();
  EXPECT_EQ(client_.state().revision, before.revision);
  EXPECT_TRUE(sameGeometry(client_.state(), before));
  {
    std::lock_guard<std::mutex> lock(ops_mutex_);
    for (const Operation& op : operations_)
      EXPECT_LE(op.revision, before.revision) << "a refused " << op.type << " was announced";
  }

  // Back to an exact solver: the same fold goes through.
  configureSolver("newton", 1000);
  const Rotate again = client_.rotate(first.response.face, first.response.axis_edge, 0.9, 0.9, 0.3, true);
  ASSERT_TRUE(again.response.success) << again.response.message;
  expectValidState(advanced(again.response.revision), "after the fold with newton");
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "faults_rostest");
  ros::NodeHandle keep_alive;
  return RUN_ALL_TESTS();
}
