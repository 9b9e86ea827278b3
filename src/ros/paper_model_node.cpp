#include "virtual_origami/ros/paper_model_node.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <malloc.h>

#include <Eigen/Geometry>
#include <geometry_msgs/TransformStamped.h>
#include <tf2/exceptions.h>
#include <visualization_msgs/MarkerArray.h>

#include "virtual_origami/core/bend_reach.h"
#include "virtual_origami/core/fold_fraction.h"
#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/model_file.h"
#include "virtual_origami/core/obj_export.h"
#include "virtual_origami/ros/remote_solver.h"
#include "virtual_origami/solvers/crease_driver_factory.h"

namespace virtual_origami
{
namespace
{
/// In the data folder, one per namespace.
std::string defaultJournalName(const ros::NodeHandle& nh)
{
  std::string ns = nh.getNamespace();
  for (char& c : ns)
    if (c == '/')
      c = '_';
  return "session" + ns + ".jsonl";
}

/// A face's frame: origin at its centroid, z along its front normal, x along its first edge.
geometry_msgs::TransformStamped faceFrame(const core::Paper& paper, int face, const std::string& parent,
                                          const std::string& child, const ros::Time& stamp)
{
  const std::vector<int>& loop = paper.faces[face].vertices;
  const core::Vec3 z = paper.faceNormal(face);
  const core::Vec3 edge = paper.vertices[loop[1]].folded - paper.vertices[loop[0]].folded;
  const core::Vec3 x = (edge - edge.dot(z) * z).normalized();
  Eigen::Matrix3d axes;
  axes << x, z.cross(x), z;
  const Eigen::Quaterniond q(axes);
  const core::Vec3 origin = paper.faceCentroid(face);
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform.translation.x = origin.x();
  t.transform.translation.y = origin.y();
  t.transform.translation.z = origin.z();
  t.transform.rotation.x = q.x();
  t.transform.rotation.y = q.y();
  t.transform.rotation.z = q.z();
  t.transform.rotation.w = q.w();
  return t;
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// What a crease driver's set-up depends on (the faces, the crease pattern, which creases are
/// driven, the held vertices), hashed (FNV-1a): a paper with another signature needs a new set-up.
uint64_t previewSetupSignature(const core::Paper& paper, const std::vector<int>& held)
{
  uint64_t hash = 1469598103934665603ull;
  const auto mix = [&hash](uint64_t value) {
    hash ^= value;
    hash *= 1099511628211ull;
  };
  const auto mixDouble = [&mix](double value) {
    uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    mix(bits);
  };
  mix(paper.vertices.size());
  for (const core::Vertex& v : paper.vertices)
  {
    mixDouble(v.crease_pattern.x());
    mixDouble(v.crease_pattern.y());
  }
  mix(paper.faces.size());
  for (const core::Face& f : paper.faces)
  {
    mix(f.vertices.size());
    for (int v : f.vertices)
      mix(static_cast<uint64_t>(v));
  }
  mix(paper.edges.size());
  for (const core::Edge& e : paper.edges)
    mix(static_cast<uint64_t>(e.assignment));
  mix(held.size());
  for (int v : held)
    mix(static_cast<uint64_t>(v));
  return hash;
}

bool hasSuffix(const std::string& s, const std::string& suffix)
{
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

PaperModelNode::PaperModelNode(ros::NodeHandle nh, ros::NodeHandle private_nh) : nh_(nh)
{
  world_frame_ = private_nh.param<std::string>("world_frame", "world");
  style_.frame_id = private_nh.param<std::string>("paper_frame", "paper");
  style_.layer_gap = private_nh.param("layer_gap", style_.layer_gap);
  size_ = private_nh.param("size", 1.0);
  pin_frame_timeout_ = private_nh.param("pin_frame_timeout", pin_frame_timeout_);
  face_frames_ = private_nh.param("face_frames", face_frames_);
  face_frame_prefix_ = private_nh.param<std::string>("face_frame_prefix", "");
  face_frames_max_ = std::max(0, private_nh.param("face_frames_max", face_frames_max_));
  solve_attempts_ = std::max(1, private_nh.param("solve_attempts", solve_attempts_));
  max_assignment_strain_ = private_nh.param("max_assignment_strain", max_assignment_strain_);
  const double pin_rate = private_nh.param("pin_rate", 30.0);

  std::string data_dir = private_nh.param<std::string>("data_dir", "");
  if (data_dir.empty())
    data_dir = core::defaultDataFolder();
  std::vector<std::string> allowed;
  private_nh.param("allowed_dirs", allowed, allowed);
  core::Expected<core::DataFolder> folder = core::DataFolder::open(data_dir, allowed);
  if (!folder)
    throw std::runtime_error(folder.message());
  folder_ = std::move(*folder);
  const core::Expected<std::string> journal =
      folder_->resolve(private_nh.param<std::string>("journal", defaultJournalName(nh_)));
  if (!journal)
    throw std::runtime_error("the journal: " + journal.message());
  std::error_code made;
  std::filesystem::create_directories(std::filesystem::path(*journal).parent_path(), made);
  // No client loads or saves over the journal or its copies (found by the round-3 probe).
  const core::Status guarded = folder_->protect(*journal);
  if (!guarded)
    throw std::runtime_error("the journal: " + guarded.message());
  journal_.setSync(private_nh.param("journal_sync", true));
  load_limits_.max_vertices = static_cast<size_t>(
      std::max(0, private_nh.param("max_load_vertices", static_cast<int>(load_limits_.max_vertices))));
  load_limits_.max_face_vertices = static_cast<size_t>(
      std::max(0, private_nh.param("max_face_vertices", static_cast<int>(load_limits_.max_face_vertices))));
  max_load_bytes_ = static_cast<size_t>(std::max(0.0, private_nh.param("max_load_mb", 64.0)) * (1 << 20));
  journal_snapshot_bytes_ =
      static_cast<uint64_t>(std::max(0.0, private_nh.param("journal_snapshot_mb", 64.0)) * (1 << 20));

  snap_ = session_.snapSettings();
  snap_.radius = private_nh.param("snap_radius", snap_.radius * size_);
  private_nh.param("edge_divisions", snap_.edge_divisions, snap_.edge_divisions);
  private_nh.param("angle_divisions", snap_.angle_divisions, snap_.angle_divisions);
  solver_ = std::make_shared<RemoteSolver>(nh_, private_nh.param<std::string>("solver_service", "solve"),
                                           private_nh.param("solver_timeout", 5.0));
  history_limit_ = static_cast<size_t>(std::max(0.0, private_nh.param("history_memory_mb", 256.0)) * 1e6);
  // A turn preview is a frame of the drag: balanced to 1e-8 it is one of Newton's steps from the
  // start the previews before it predict, where 1e-10 takes four to six (docs/SOLVERS.md).
  turn_preview_tolerance_ = private_nh.param("turn_preview_tolerance", turn_preview_tolerance_);
  if (!(turn_preview_tolerance_ >= 0) || !std::isfinite(turn_preview_tolerance_))
  {
    ROS_WARN("paper_model: turn_preview_tolerance must be a finite strain of 0 or more; 1e-8 is used");
    turn_preview_tolerance_ = 1e-8;
  }
  const std::string driver = private_nh.param<std::string>("crease_driver", "quasi_newton");
  crease_driver_ = core::makeCreaseDriver(driver);
  if (!crease_driver_)
    throw std::runtime_error("crease_driver \"" + driver + "\" is not a crease driver");
  // A clone shares what depends on the pattern alone (the factorisation's ordering): the
  // slider's release does not order a 10,000-vertex pattern again after its previews did.
  preview_driver_ = crease_driver_->clone();
  const std::string run_id = nh_.param<std::string>("/run_id", "");
  const bool resume = private_nh.param("resume", true);

  state_pub_ = nh_.advertise<PaperState>("state", 1, true);
  markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
  operations_pub_ = nh_.advertise<Operation>("operations", 100);
  curved_drag_sub_ = nh_.subscribe<VertexTarget>("curved_drag", 10, [this](const VertexTarget::ConstPtr& drag) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (faded_ == (drag->vertex >= 0))
      return;
    faded_ = drag->vertex >= 0;
    faded_revision_ = session_.revision();
    publishMarkers(session_.preview() ? *session_.preview() : session_.paper());
  });

  const core::Vec3 origin(private_nh.param("paper_x", 0.0), private_nh.param("paper_y", 0.0),
                          private_nh.param("paper_z", 0.0));
  static_tf_.sendTransform(frameTransform(world_frame_, style_.frame_id, origin, private_nh.param("paper_yaw", 0.0)));
  pin_timer_ = nh_.createTimer(ros::Duration(0.1), &PaperModelNode::broadcastFrames, this);
  // Off, the rigid faces never chase the frames: a folded model stays as folded while the
  // curved sheet (curved_mesh_solver, which looks the frames up itself) bends to them.
  if (!private_nh.param("follow_frames", true))
    ROS_INFO("paper_model: follow_frames is off: pins on frames hold the curved sheet, the model stays as it is");
  else if (pin_rate > 0)
    follow_timer_ = nh_.createTimer(ros::Duration(1.0 / pin_rate), &PaperModelNode::followPins, this);
  else
    ROS_ERROR("paper_model: pin_rate must be positive (it is %g); pins will not follow their frames", pin_rate);

  services_.push_back(nh_.advertiseService("crease", &PaperModelNode::crease, this));
  services_.push_back(nh_.advertiseService("rotate", &PaperModelNode::rotate, this));
  services_.push_back(nh_.advertiseService("squash", &PaperModelNode::squash, this));
  services_.push_back(nh_.advertiseService("undo", &PaperModelNode::undo, this));
  services_.push_back(nh_.advertiseService("redo", &PaperModelNode::redo, this));
  services_.push_back(nh_.advertiseService("reset", &PaperModelNode::reset, this));
  services_.push_back(nh_.advertiseService("pin", &PaperModelNode::pin, this));
  services_.push_back(nh_.advertiseService("pull", &PaperModelNode::pull, this));
  services_.push_back(nh_.advertiseService("fold_by_assignment", &PaperModelNode::foldByAssignment, this));
  services_.push_back(nh_.advertiseService("flat_fold", &PaperModelNode::flatFold, this));
  services_.push_back(nh_.advertiseService("drag_vertex", &PaperModelNode::dragVertex, this));
  services_.push_back(nh_.advertiseService("keep_bend", &PaperModelNode::keepBend, this));
  services_.push_back(nh_.advertiseService("load", &PaperModelNode::load, this));
  services_.push_back(nh_.advertiseService("save", &PaperModelNode::save, this));
  // Calls reconfigure() at once with the parameters (or their defaults).
  reconfigure_server_ = std::make_unique<dynamic_reconfigure::Server<PaperModelConfig>>(private_nh);
  reconfigure_server_->setCallback([this](PaperModelConfig& c, uint32_t level) { reconfigure(c, level); });
  // The services answer from now on: "resuming" until the journal is read back (a large
  // session took 2 minutes, all of them without an answer: found by the round-3 probe).
  warm_thread_ = std::thread([this] { warmUpPreviews(); });
  resume_thread_ = std::thread([this, path = *journal, run_id, resume] {
    try
    {
      restoreOrStart(path, run_id, resume);
    }
    catch (const std::exception& e)
    {
      ROS_FATAL("paper_model: %s", e.what());
      std::_Exit(1);  // as a failed start: nothing was served, nothing to save
    }
  });
}

PaperModelNode::~PaperModelNode()
{
  if (resume_thread_.joinable())
    resume_thread_.join();
  {
    std::lock_guard<std::mutex> lock(warm_mutex_);
    warm_stop_ = true;
  }
  warm_wanted_.notify_all();
  if (warm_thread_.joinable())
    warm_thread_.join();
}

void PaperModelNode::scheduleWarmUp()
{
  const std::vector<int> held = pinnedVertices();
  const uint64_t signature = previewSetupSignature(session_.paper(), held);
  if (signature == warmed_signature_)
    return;
  warmed_signature_ = signature;
  {
    std::lock_guard<std::mutex> lock(warm_mutex_);
    warm_paper_ = session_.paper();
    warm_held_ = held;
    warm_after_frames_ = preview_frames_;
  }
  warm_wanted_.notify_all();
}

void PaperModelNode::warmUpPreviews()
{
  while (true)
  {
    core::Paper paper;
    std::vector<int> held;
    uint64_t frames = 0;
    {
      std::unique_lock<std::mutex> lock(warm_mutex_);
      warm_wanted_.wait(lock, [this] { return warm_stop_ || warm_paper_; });
      if (warm_stop_)
        return;
      paper = std::move(*warm_paper_);
      warm_paper_.reset();
      held = std::move(warm_held_);
      frames = warm_after_frames_;
    }
    {
      std::lock_guard<std::mutex> drivers(drivers_mutex_);
      if (preview_frames_ != frames)
        continue;  // a preview came first and set the driver up
      // On the preview driver itself, which readies what its first frame would make (its set-up
      // and factorisations) without a frame: its frames, and so the state a release commits
      // from, stay as they were.
      core::prepareAssignmentPreviews(paper, *preview_driver_, held);
    }
    // And the rigid solver for the release's closure (spring_solver orders the pattern: at
    // 10,000 vertices the first release's closure took 0.6 s of it), outside the drivers' lock.
    if (solver_)
      core::prepareAssignmentClosure(paper, *solver_, held);
    ROS_DEBUG("paper_model: preview driver and solver prepared for %zu vertices", paper.vertices.size());
  }
}

void PaperModelNode::configureSession()
{
  // A resumed model had no solver, so every fold that needs one was refused: found by chaos.
  session_.snapSettings() = snap_;
  session_.setSolver(solver_);
  session_.setHistoryLimit(history_limit_);
  session_.setTurnPreviewTolerance(turn_preview_tolerance_);
  session_.setCreaseDrivers(crease_driver_, preview_driver_);
}

bool PaperModelNode::stillResuming()
{
  std::unique_lock<std::mutex> lock(resume_mutex_);
  // A small journal is read back in moments: a client that calls at once is served, not refused.
  return !resumed_.wait_for(lock, std::chrono::milliseconds(1000), [this] { return !resuming_; });
}

void PaperModelNode::reconfigure(PaperModelConfig& config, uint32_t)
{
  {
    std::lock_guard<std::mutex> drivers(drivers_mutex_);
    core::SolveLimits limits = preview_driver_->limits();
    limits.max_seconds = config.fold_preview_seconds;
    preview_driver_->setLimits(limits);
    preview_budget_.setAnswerSeconds(config.fold_preview_seconds);
  }
  std::lock_guard<std::mutex> lock(mutex_);
  const bool recolour =
      style_.colour_by_strain != config.colour_by_strain || style_.strain_scale != config.strain_scale;
  style_.colour_by_strain = config.colour_by_strain;
  style_.strain_scale = config.strain_scale;
  if (recolour)
    publishMarkers(session_.preview() ? *session_.preview() : session_.paper());
}

void PaperModelNode::restoreOrStart(const std::string& path, const std::string& run_id, bool resume)
{
  // Built aside and swapped in: the services refuse ("resuming") until then, and nothing else
  // touches the session or the journal meanwhile.
  core::Session restored;
  std::string notice;
  // roslaunch sets /run_id once per launch: a respawned node finds its own launch's id in the
  // journal, and `resume: false` means a new session per launch, not per process.
  if (std::filesystem::exists(path))
  {
    core::Expected<core::JournalRecovery> recovered = core::recoverJournal(path);
    const bool same_launch = recovered && !run_id.empty() && recovered->run_id == run_id;
    if (recovered && (resume || same_launch))
    {
      restored = core::Session(std::move(recovered->history));  // moved: a large history is not held twice
      ROS_INFO("paper_model: resumed revision %lu (%zu operations) from %s (%s)",
               static_cast<unsigned long>(restored.revision()), restored.log().size(), path.c_str(),
               resume ? "resume is on" : "respawned in the launch that started this session");
      if (!recovered->dropped.empty())
      {
        // The journal is written anew below: keep the damaged one as it was.
        const std::string kept = core::keepAsideName(path);
        std::error_code error;
        std::filesystem::copy_file(path, kept, error);
        notice = "the journal " + path + " was damaged: " + recovered->dropped.front() + "; revision " +
                 std::to_string(restored.revision()) + " and everything before it were recovered" +
                 (error ? "" : ", the damaged journal is kept as " + kept);
        ROS_WARN("paper_model: %s", notice.c_str());
      }
    }
    else
    {
      // Never lose a user's work: keep the old journal beside the new one.
      const std::string kept = core::keepAsideName(path);
      std::error_code error;
      std::filesystem::rename(path, kept, error);
      if (error)  // starting afresh would write over it
        throw std::runtime_error("cannot keep the journal " + path + " aside as " + kept + ": " + error.message() +
                                 "; nothing was started, so that it is not overwritten");
      if (!recovered)
        ROS_ERROR("paper_model: %s; kept it as %s and started afresh", recovered.message().c_str(), kept.c_str());
      else
        ROS_INFO("paper_model: resume is off and %s is from another launch: a new session; the last one is kept as %s",
                 path.c_str(), kept.c_str());
    }
  }
  else
    ROS_INFO("paper_model: a new session, journaled in %s", path.c_str());
  if (restored.revision() == 0 && size_ != 1.0)
    restored = core::Session(core::Paper::square(size_));
  const core::Status started = journal_.start(path, restored, run_id);
  if (!started)
    ROS_ERROR("paper_model: %s; every change is refused until the journal can be written", started.message().c_str());
  {
    std::lock_guard<std::mutex> lock(mutex_);
    session_ = std::move(restored);
    notice_ = std::move(notice);
    configureSession();
    publishState();
  }
  {
    std::lock_guard<std::mutex> lock(resume_mutex_);
    resuming_ = false;
  }
  resumed_.notify_all();
}

core::Status PaperModelNode::commit(core::Change change, const std::string& what, const ros::Time& stamp,
                                   const core::JournalEvent* event)
{
  // Checked before it is journaled: the journal must hold only what the session takes.
  const core::Status acceptable = session_.check(change);
  if (!acceptable)
    return acceptable;
  // Journaled first: an operation answered `success` survives a crash.
  const core::Status journaled =
      event ? journal_.append(session_, *event) :
              journal_.append(session_, change.operation, change.next ? &*change.next : nullptr);
  if (!journaled)
  {
    ROS_ERROR("paper_model: %s", journaled.message().c_str());
    return core::failure("not done: it could not be recorded on disk (" + journaled.message() + ")");
  }
  const size_t forgotten = session_.forgottenStates();
  const core::Status committed = session_.commit(std::move(change));
  if (!committed)
    return committed;
  // A restart reads the header and the events after it: once the events outweigh the header,
  // they become a new one (every state a large model made took 2 minutes to read back).
  if (journal_.wantsSnapshot(journal_snapshot_bytes_))
  {
    const core::Status snapped = journal_.snapshot(session_);
    if (!snapped)  // the next append starts it again (SessionJournal::append)
      ROS_WARN("paper_model: the journal's snapshot failed: %s", snapped.message().c_str());
  }
  if (session_.forgottenStates() > forgotten)
    ROS_WARN_THROTTLE(10.0, "paper_model: the oldest undo states were forgotten to keep the history within "
                      "history_memory_mb (%zu so far); the journal keeps every operation",
                      session_.forgottenStates());
  notice_.clear();
  Operation op = toMessage(session_.log().back(), &session_.paper());
  op.header.stamp = ros::Time::now();
  op.header.frame_id = style_.frame_id;
  operations_pub_.publish(op);
  publishState(stamp);
  ROS_DEBUG("paper_model: %s, revision %lu", what.c_str(), static_cast<unsigned long>(session_.revision()));
  return core::success();
}

template <class Result>
core::Expected<core::Computed<Result>> PaperModelNode::computeAndCommit(
    const std::function<core::Expected<core::Computed<Result>>(core::Workspace)>& compute, bool commit_it,
    const std::string& what, uint64_t& revision, const ros::Time& stamp, bool for_these_pins)
{
  using Answer = core::Expected<core::Computed<Result>>;
  for (int attempt = 1;; ++attempt)
  {
    // The last try computes under the lock: while others commit faster than a solve takes, an
    // optimistic try would never land (measured: 20 of 20 rotations refused against creases
    // made back to back). Then others wait for this one solve, solver_timeout at most.
    const bool last = attempt >= solve_attempts_;
    std::unique_lock<std::mutex> lock(mutex_);
    session_.setHeldVertices(pinnedVertices());
    core::Workspace workspace = session_.workspace();
    const uint64_t pins_seen = pins_changes_;
    if (!last)
      lock.unlock();
    // The state it starts from, for the journal's delta (made outside the lock too).
    const core::Paper base = commit_it && !last ? workspace.paper : core::Paper();
    Answer computed = compute(std::move(workspace));
    // The journal line of a large model takes longer to write out than to append: outside too.
    std::optional<core::JournalEvent> event;
    if (computed && commit_it && !last)
      event = core::journalEvent(computed->change.operation, &*computed->change.next, &base);
    if (!last)
      lock.lock();
    revision = session_.revision();  // answered with the revision this call made or found
    if (!computed)
      return computed;
    if (pins_changes_ != pins_seen && for_these_pins)
      return Answer::failure("the pins changed while they were followed");
    if (computed->change.base_revision != session_.revision() || pins_changes_ != pins_seen)
      continue;  // somebody else's change came first, or the pins it must hold changed: again
    if (!commit_it)
    {
      publishMarkers(*computed->change.next);  // a preview is drawn, not recorded
      session_.setPreview(std::move(computed->change));
      return computed;
    }
    const core::Status committed = commit(std::move(computed->change), what, stamp, event ? &*event : nullptr);
    revision = session_.revision();
    if (!committed)
      return Answer::failure(committed.message());
    return computed;
  }
}

void PaperModelNode::publishState(const ros::Time& stamp)
{
  PaperState state = toMessage(session_.paper(), session_.revision(), pins_);
  state.header.stamp = stamp.isZero() ? ros::Time::now() : stamp;
  state.header.frame_id = style_.frame_id;
  state.notice = notice_;
  state_pub_.publish(state);
  if (session_.revision() != faded_revision_)
    faded_ = false;  // a new paper: a bend of the old one is over (also when its let-go was lost)
  publishMarkers(session_.paper());
  // Now, not the state's stamp: a pull's older tf stamp would leave the last timer's
  // broadcast of the old pose as the latest.
  broadcastFaces(ros::Time::now());
  scheduleWarmUp();
}

void PaperModelNode::broadcastFaces(const ros::Time& stamp)
{
  const core::Paper& paper = session_.paper();
  if (!face_frames_)
    return;
  // Every listener keeps ten seconds of every frame, this node's own pin listener too: with
  // 100,000 faces at 10 Hz that was 800 MB here alone (measured with heaptrack).
  if (static_cast<int>(paper.faces.size()) > face_frames_max_)
  {
    ROS_WARN_ONCE("paper_model: the model has more faces than face_frames_max (%d): no face frames are broadcast",
                  face_frames_max_);
    return;
  }
  std::vector<geometry_msgs::TransformStamped> frames;
  for (size_t f = 0; f < paper.faces.size(); ++f)
    frames.push_back(faceFrame(paper, static_cast<int>(f), style_.frame_id,
                               face_frame_prefix_ + "face_" + std::to_string(f), stamp));
  tf_.sendTransform(frames);
}

std::vector<int> PaperModelNode::pinnedVertices() const
{
  std::vector<int> held;
  for (const auto& pinned : pins_)
    held.push_back(pinned.first);
  return held;
}

void PaperModelNode::followPins(const ros::TimerEvent&)
{
  std::vector<core::PullTarget> targets;
  std::vector<int> held;
  ros::Time stamp;
  uint64_t pins_seen = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const core::Paper& paper = session_.paper();
    const int count = static_cast<int>(paper.vertices.size());
    const double still = 1e-9 * paper.scale();
    bool moved = false;
    for (const auto& [vertex, pin] : pins_)
    {
      if (pin.frame_id.empty() || vertex >= count)
        continue;
      geometry_msgs::TransformStamped t;
      try
      {
        t = tf_buffer_.lookupTransform(style_.frame_id, pin.frame_id, ros::Time(0));
      }
      catch (const tf2::TransformException& e)
      {
        // A cycle pulls every pin or none, so the pins never pull against a stale frame.
        ROS_WARN_THROTTLE(5.0, "paper_model: vertex %d follows %s, which tf cannot place: %s; the paper stays", vertex,
                          pin.frame_id.c_str(), e.what());
        return;
      }
      const core::Vec3 target(t.transform.translation.x, t.transform.translation.y, t.transform.translation.z);
      targets.push_back({ vertex, target });
      stamp = std::max(stamp, t.header.stamp);
      const auto last = pulled_to_.find(vertex);
      if (last == pulled_to_.end() || (last->second - target).norm() > still)
        moved = true;
    }
    if (!moved)
      return;
    held = pinnedVertices();
    if (refused_ && refused_->revision == session_.revision() && refused_->targets == targets && refused_->held == held)
      return;
    pins_seen = pins_changes_;
  }
  uint64_t revision = 0;
  const auto result = computeAndCommit<core::PullResult>(
      [&](core::Workspace workspace) { return core::computePull(std::move(workspace), targets); }, true,
      "pulled to the pins' frames", revision, stamp, true);
  std::lock_guard<std::mutex> lock(mutex_);
  if (pins_changes_ != pins_seen)
    return;  // a pin was set or released meanwhile: the next cycle follows the pins as they are
  if (!result)
  {
    // Refused cycles (a frame the rigid faces cannot reach) repeat while the frame moves on:
    // one warning every few seconds, and a frame standing still is not solved again.
    ROS_WARN_THROTTLE(5.0, "paper_model: the pins cannot be followed: %s", result.message().c_str());
    refused_ = RefusedPull{ revision, targets, held };
    return;
  }
  refused_.reset();
  for (const core::PullTarget& target : targets)
    pulled_to_[target.vertex] = target.position;
  const core::PullResult& pulled = result->result;
  if (pulled.residual > 1e-6 * session_.paper().scale())
    ROS_WARN_THROTTLE(5.0, "paper_model: the rigid faces keep the pinned vertices up to %g m from their frames",
                      pulled.residual);
  ROS_DEBUG("paper_model: pulled %zu pins, residual %g m, strain %g", targets.size(), pulled.residual,
            pulled.solve.max_strain);
}

void PaperModelNode::publishMarkers(const core::Paper& paper)
{
  visualization_msgs::MarkerArray markers = paperMarkers(paper, style_, ros::Time::now());
  if (faded_)
    for (visualization_msgs::Marker& m : markers.markers)
      if (m.ns == "front" || m.ns == "back")
      {
        constexpr float kFaded = 0.3f;
        m.color.a = kFaded;
        for (std_msgs::ColorRGBA& c : m.colors)
          c.a = kFaded;
      }
  markers_pub_.publish(markers);
}

void PaperModelNode::broadcastFrames(const ros::TimerEvent&)
{
  {
    std::lock_guard<std::mutex> resume(resume_mutex_);
    if (resuming_)
      return;  // no frames of the placeholder sheet
  }
  std::lock_guard<std::mutex> lock(mutex_);
  broadcastFaces(ros::Time::now());
  std::vector<geometry_msgs::TransformStamped> frames;
  for (const auto& [vertex, pin] : pins_)
    if (vertex < static_cast<int>(session_.paper().vertices.size()))
      frames.push_back(
          frameTransform(style_.frame_id, "pin_" + std::to_string(vertex), session_.paper().vertices[vertex].folded));
  if (!frames.empty())
    tf_.sendTransform(frames);
}

bool PaperModelNode::crease(Crease::Request& req, Crease::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  core::CreaseRequest request;
  request.start = toVec3(req.start);
  request.end = toVec3(req.end);
  if (req.has_eye)
    request.eye = toVec3(req.eye);
  request.snap = req.snap;
  // Computed on a copy like a solve: the journal line of a large model is written out meanwhile.
  const auto result = computeAndCommit<core::CreaseResult>(
      [&](core::Workspace workspace) { return core::computeCrease(std::move(workspace), request); }, true, "creased",
      res.revision);
  res.success = result.ok();
  if (result)
  {
    res.new_edges.assign(result->result.new_edges.begin(), result->result.new_edges.end());
    res.message = "creased " + std::to_string(result->result.split_faces.size()) + " faces";
  }
  else
    res.message = result.message();
  return true;
}

bool PaperModelNode::rotate(Rotate::Request& req, Rotate::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  core::RotateRequest request;
  request.face = req.face;
  request.axis_edge = req.axis_edge;
  request.click = toVec3(req.click);
  request.angle = req.angle;
  request.carry_stack = !req.picked_layers_only;
  std::vector<core::Vec3> recorded;
  for (const geometry_msgs::Point& p : req.positions)
    recorded.push_back(toVec3(p));
  if (!recorded.empty() && !req.commit)
  {
    res.success = false;
    res.message = "positions are a recorded commit's result: a preview solves its turn";
    res.face = req.face;
    res.axis_edge = req.axis_edge;
    std::lock_guard<std::mutex> lock(mutex_);
    res.revision = session_.revision();
    return true;
  }
  const auto result = computeAndCommit<core::RotateResult>(
      [&](core::Workspace workspace) {
        return core::computeRotate(std::move(workspace), request, !req.commit, recorded.empty() ? nullptr : &recorded);
      },
      req.commit, "rotated", res.revision);
  res.success = result.ok();
  res.message = result ? (req.commit ? "rotated" : "preview") : result.message();
  res.face = result ? result->result.face : req.face;
  res.axis_edge = result ? result->result.axis_edge : req.axis_edge;
  return true;
}

bool PaperModelNode::answer(const core::Status& status, const std::string& done, std_srvs::Trigger::Response& res)
{
  res.success = status.ok();
  res.message = status ? done : status.message();
  return true;
}

bool PaperModelNode::squash(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  uint64_t revision = 0;
  const auto result = computeAndCommit<core::SquashResult>(
      [](core::Workspace workspace) { return core::computeSquash(std::move(workspace)); }, true, "squashed", revision);
  return answer(result ? core::success() : core::failure(result.message()),
                result && result->result.exact ? "pressed flat" : "pressed flat and restored by the solver", res);
}

bool PaperModelNode::undo(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  std::lock_guard<std::mutex> lock(mutex_);
  core::Expected<core::Change> change = session_.prepareUndo();
  return answer(change ? commit(std::move(*change), "undone") : core::failure(change.message()), "undone", res);
}

bool PaperModelNode::redo(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  std::lock_guard<std::mutex> lock(mutex_);
  core::Expected<core::Change> change = session_.prepareRedo();
  return answer(change ? commit(std::move(*change), "redone") : core::failure(change.message()), "redone", res);
}

bool PaperModelNode::reset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  std::lock_guard<std::mutex> lock(mutex_);
  core::Expected<core::Change> change = core::computeReset(session_.revision(), size_);
  const core::Status status = change ? commit(std::move(*change), "reset") : core::failure(change.message());
  if (status)
  {
    pins_.clear();  // the vertices they held are gone
    ++pins_changes_;
    pulled_to_.clear();
    publishState();
  }
  return answer(status, "reset to an unfolded square", res);
}

bool PaperModelNode::pin(PinVertex::Request& req, PinVertex::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  res.success = false;
  const auto missing = [&] {
    const int count = static_cast<int>(session_.paper().vertices.size());
    if (req.vertex >= 0 && req.vertex < count)
      return false;
    res.message =
        "vertex " + std::to_string(req.vertex) + " does not exist (the model has " + std::to_string(count) + ")";
    return true;
  };
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (missing())
      return true;
    if (req.release && !pins_.count(req.vertex))
    {
      res.message = "vertex " + std::to_string(req.vertex) + " is not pinned";
      return true;
    }
  }
  // Waiting for tf holds no lock: other clients go on meanwhile.
  if (!req.release && !req.frame_id.empty() &&
      !tf_buffer_.canTransform(style_.frame_id, req.frame_id, ros::Time(0), ros::Duration(pin_frame_timeout_),
                               &res.message))
  {
    res.message = "frame \"" + req.frame_id + "\" is not known to tf in " + style_.frame_id + " after " +
                  std::to_string(pin_frame_timeout_) + " s (" + res.message + "); vertex " +
                  std::to_string(req.vertex) + " is not pinned";
    return true;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (missing())  // the model changed while tf was asked
    return true;
  pulled_to_.erase(req.vertex);
  ++pins_changes_;
  if (req.release)
    pins_.erase(req.vertex);
  else
    pins_[req.vertex] = { req.frame_id, req.frame_id.empty() ? session_.paper().vertices[req.vertex].folded :
                                                               core::Vec3::Zero() };  // the frame's origin
  res.success = true;
  res.message = req.release ? "released" : req.frame_id.empty() ? "pinned in place" : "pinned to " + req.frame_id;
  Operation op;
  op.header.stamp = ros::Time::now();
  op.header.frame_id = style_.frame_id;
  op.revision = session_.revision();
  op.type = "pin";
  op.face = op.axis_edge = -1;
  op.vertex = req.vertex;
  op.frame_id = req.frame_id;
  op.release = req.release;
  operations_pub_.publish(op);
  publishState();
  return true;
}

bool PaperModelNode::pull(Pull::Request& req, Pull::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  res.success = false;
  if (req.vertices.size() != req.positions.size())
    res.message = "pull needs one position per vertex (" + std::to_string(req.vertices.size()) + " vertices, " +
                  std::to_string(req.positions.size()) + " positions)";
  else
  {
    std::vector<core::PullTarget> targets;
    for (size_t i = 0; i < req.vertices.size(); ++i)
      targets.push_back({ req.vertices[i], toVec3(req.positions[i]) });
    const std::string done = "pulled " + std::to_string(targets.size()) + " vertices";
    const auto result = computeAndCommit<core::PullResult>(
        [&](core::Workspace workspace) { return core::computePull(std::move(workspace), targets); }, true, done,
        res.revision);
    res.success = result.ok();
    res.message = result ? done : result.message();
    if (result)
    {
      res.residual = result->result.residual;
      res.max_strain = result->result.solve.max_strain;
    }
    return true;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  res.revision = session_.revision();
  return true;
}

bool PaperModelNode::foldByAssignment(FoldByAssignment::Request& req, FoldByAssignment::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  const bool commit_it = !req.preview;
  core::AssignmentFoldAcceptance acceptance;
  acceptance.max_strain = max_assignment_strain_;
  acceptance.keep = req.keep;
  core::AssignmentFoldResult figures;
  std::vector<core::Vec3> recorded;
  for (const geometry_msgs::Point& p : req.positions)
    recorded.push_back(toVec3(p));
  if (!recorded.empty() && !commit_it)
  {
    res.success = false;
    res.message = "positions are a recorded commit's result: a preview solves its frame";
    std::lock_guard<std::mutex> lock(mutex_);
    res.revision = session_.revision();
    return true;
  }
  // A preview's frame gets what the rest of its answer leaves of the answer's budget.
  const auto answer_start = std::chrono::steady_clock::now();
  double budget_set_at = 0.0;
  size_t vertices = 0;
  const auto result = computeAndCommit<core::AssignmentFoldResult>(
      [&](core::Workspace workspace) {
        std::lock_guard<std::mutex> drivers(drivers_mutex_);
        if (!commit_it)
        {
          ++preview_frames_;
          vertices = workspace.paper.vertices.size();
          budget_set_at = secondsSince(answer_start);
          core::SolveLimits limits = preview_driver_->limits();
          limits.max_seconds = preview_budget_.solveSeconds(budget_set_at, vertices);
          preview_driver_->setLimits(limits);
        }
        return core::computeFoldByAssignment(std::move(workspace), req.fraction, commit_it, acceptance, &figures,
                                             recorded.empty() ? nullptr : &recorded);
      },
      commit_it, "folded by assignment", res.revision);
  res.success = result.ok();
  // The figures of what was computed, refused or not: a refusal says how far from right it was.
  const core::AssignmentFoldResult& folded = result ? result->result : figures;
  res.max_strain = folded.max_strain;
  res.angle_error = folded.angle_error;
  res.rigid = folded.rigid;
  res.creases_against_target = folded.against_target;
  res.crossings = folded.crossings;
  res.ordered_pairs = folded.ordered_pairs;
  res.layer_problem = folded.layer_problem;
  res.layers_unordered = folded.layers_unordered;
  res.compliant_faces = folded.compliant_faces;
  res.largest_bend = folded.largest_bend;
  if (!result)
  {
    res.message = result.message();
    if (commit_it)
    {
      // The slider's previews are on show: the paper as it stays.
      std::lock_guard<std::mutex> lock(mutex_);
      publishMarkers(session_.paper());
    }
    return true;
  }
  char text[160];
  std::snprintf(text, sizeof text, "%s %.1f %% by assignment (strain %.2g, %s)", commit_it ? "folded" : "preview at",
                100.0 * req.fraction, folded.max_strain, folded.rigid ? "rigid" : "not rigid");
  res.message = text;
  if (!folded.layers_unordered.empty())
    res.message += "; its flat layers are left without an order, unchecked for crossing: " + folded.layers_unordered;
  if (commit_it && req.keep)
  {
    core::AssignmentFoldAcceptance strict = acceptance;
    strict.keep = false;
    const std::string problems = core::assignmentFoldProblems(folded, strict);
    if (!problems.empty())
      res.message += "; kept as asked, although " + problems;
  }
  if (!commit_it)
  {
    std::lock_guard<std::mutex> drivers(drivers_mutex_);
    preview_budget_.record(budget_set_at, folded.solve.seconds, secondsSince(answer_start), vertices);
  }
  else if (secondsSince(answer_start) > 1.0 || !folded.solve.message.empty())
    // What a slow commit cost (a release from a preview far behind its handle, or one that
    // folded from the committed paper instead), for whoever wonders why it took long.
    ROS_INFO("paper_model: fold by assignment to %.1f %% answered in %.2f s: the crease driver %d iterations, "
             "%d factorisations, %d back-substitutions in %.2f s%s%s",
             100.0 * req.fraction, secondsSince(answer_start), folded.solve.iterations, folded.solve.factorizations,
             folded.solve.back_substitutions, folded.solve.seconds, folded.solve.message.empty() ? "" : "; ",
             folded.solve.message.c_str());
  return true;
}

bool PaperModelNode::flatFold(FlatFold::Request& req, FlatFold::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  res.success = false;
  const core::Expected<core::FlatFoldRequest> request = flatFoldRequest(req.starts, req.ends, req.angles, req.fixed);
  if (!request)
  {
    res.message = request.message();
    std::lock_guard<std::mutex> lock(mutex_);
    res.revision = session_.revision();
    return true;
  }
  const bool commit_it = req.commit;
  const double fraction = req.fraction;
  const auto result = computeAndCommit<core::FlatFoldResult>(
      [&](core::Workspace workspace) {
        return commit_it ? core::computeFlatFold(std::move(workspace), *request) :
                           core::computeFlatFoldPreview(std::move(workspace), *request, fraction);
      },
      commit_it, "folded on chosen creases", res.revision);
  res.success = result.ok();
  if (!result)
  {
    res.message = result.message();
    return true;
  }
  res.changed_edges.assign(result->result.changed_edges.begin(), result->result.changed_edges.end());
  res.moved_faces.assign(result->result.moved_faces.begin(), result->result.moved_faces.end());
  char text[160];
  if (commit_it)
    std::snprintf(text, sizeof text, "folded on %zu chosen creases: %zu creases set, %zu faces moved",
                  request->creases.size(), result->result.changed_edges.size(), result->result.moved_faces.size());
  else
    std::snprintf(text, sizeof text, "preview at %.0f %% of the fold (%zu faces move)", 100.0 * fraction,
                  result->result.moved_faces.size());
  res.message = text;
  return true;
}

bool PaperModelNode::dragVertex(DragVertex::Request& req, DragVertex::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  const core::PullTarget target{ req.vertex, toVec3(req.position) };
  const bool commit_it = req.commit;
  const auto result = computeAndCommit<core::PullResult>(
      [&](core::Workspace workspace) { return core::computeDragVertex(std::move(workspace), target); }, commit_it,
      "dragged a vertex", res.revision);
  res.success = result.ok();
  if (!result)
  {
    res.message = result.message();
    std::lock_guard<std::mutex> lock(mutex_);
    res.curved_reaches = core::bendingReaches(session_.paper(), target, pinnedVertices()).ok();
    return true;
  }
  res.residual = result->result.residual;
  res.max_strain = result->result.solve.max_strain;
  res.message = (commit_it ? "dragged vertex " : "preview: vertex ") + std::to_string(req.vertex) +
                (commit_it ? "" : " dragged");
  return true;
}

bool PaperModelNode::keepBend(KeepBend::Request& req, KeepBend::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  res.success = false;
  core::Expected<core::BentSheet> sheet = bentSheet(req.points, req.triangles, req.positions);
  if (!sheet)
  {
    res.message = "the bend is not kept: " + sheet.message();
    std::lock_guard<std::mutex> lock(mutex_);
    res.revision = session_.revision();
    return true;
  }
  const auto result = computeAndCommit<core::KeptBend>(
      [&](core::Workspace workspace) { return core::computeKeepBend(std::move(workspace), *sheet); }, true,
      "kept a bend", res.revision);
  res.success = result.ok();
  if (!result)
  {
    res.message = result.message();
    return true;
  }
  const core::KeptBend& kept = result->result;
  res.bent_faces.assign(kept.bent_faces.begin(), kept.bent_faces.end());
  res.triangles_kept = kept.triangles;
  res.facets = kept.facets;
  res.largest_bend = kept.largest_bend;
  res.max_strain = kept.max_strain;
  char text[200];
  std::snprintf(text, sizeof text, "kept the bend: %zu face%s bent into %d triangles, the largest bend %.1f°",
                kept.bent_faces.size(), kept.bent_faces.size() == 1 ? "" : "s", kept.triangles,
                kept.largest_bend * 180.0 / M_PI);
  res.message = text;
  return true;
}

bool PaperModelNode::load(Load::Request& req, Load::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  // Read, sized, parsed, checked and journaled outside the lock: a large file holds up no other
  // client, and a FIFO or device is refused without waiting (DataFolder::readFile).
  const std::optional<core::ModelFormat> format = core::modelFormat(req.path);
  core::Expected<core::Paper> paper = core::Expected<core::Paper>::failure("\"" + req.path +
                                                                           "\" is a recording or a journal, not a "
                                                                           "model: load takes .fold, .cp, .opx or .svg "
                                                                           "files");
  if (format)
  {
    const core::Expected<std::string> text = folder_->readFile(req.path, max_load_bytes_);
    const core::Status sized =
        text ? core::checkModelSize(*text, *format, load_limits_) : core::failure(text.message());
    paper = sized ? core::parseModel(*text, *format, size_) : core::Expected<core::Paper>::failure(sized.message());
    const core::Status faces = paper ? core::checkFaceSizes(*paper, load_limits_) : core::success();
    if (!faces)
      paper = core::Expected<core::Paper>::failure(faces.message());
  }
  uint64_t base = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    base = session_.revision();
  }
  core::Expected<core::Change> change = paper ? core::computeLoad(base, std::move(*paper), req.path) :
                                                core::Expected<core::Change>::failure(paper.message());
  // Its journal line too, for the revision it will most likely make.
  std::optional<core::JournalEvent> event;
  if (change)
    event = core::journalEvent(change->operation, &*change->next);
  core::Status status = core::failure(change ? "" : change.message());
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (change && change->base_revision != session_.revision())  // another client came first
    {
      change = core::computeLoad(session_.revision(), std::move(*change->next), req.path);
      event.reset();
    }
    if (change)
      status = commit(std::move(*change), "loaded", ros::Time(0), event ? &*event : nullptr);
    if (status)
    {
      pins_.clear();
      ++pins_changes_;
      pulled_to_.clear();
      publishState();
    }
  }
  res.success = status.ok();
  res.message = status ? "loaded " + req.path : status.message();
  // Parsing a large file peaks at several times the model's size, on whichever thread served
  // the call; glibc keeps what was freed in that thread's arena unless asked (100,000 vertices:
  // 390 MB resident after the load without this, measured).
  malloc_trim(0);
  return true;
}

bool PaperModelNode::save(Save::Request& req, Save::Response& res)
{
  if (refuseWhileResuming(res))
    return true;
  // Control characters first: "x.jsonl\0.fold" ends in .fold only as a whole string.
  core::Status status = core::checkPathCharacters(req.path);
  const bool fold = hasSuffix(req.path, ".fold"), obj = hasSuffix(req.path, ".obj");
  if (status && !fold && !obj)
    status = core::failure("save needs a path ending in .fold or .obj, not \"" + req.path + "\"");
  if (status)
  {
    // Copied under the lock, written out of it.
    core::Paper paper;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      paper = session_.paper();
    }
    status = folder_->writeFile(req.path, fold ? core::formatFold(paper) : core::formatObj(paper));
  }
  res.success = status.ok();
  res.message = status ? "saved " + req.path + " in " + folder_->root() : status.message();
  return true;
}

}  // namespace virtual_origami
