#include "virtual_origami/ros/curved_mesh_solver_node.h"

#include <algorithm>

#include <visualization_msgs/MarkerArray.h>

#include <virtual_origami/KeepBend.h>

#include "virtual_origami/curved/bent_sheet.h"
#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/cgal_mesh.h"
#include "virtual_origami/curved/paper_material.h"
#include "virtual_origami/ros/conversions.h"

namespace virtual_origami
{
core::Expected<core::CurvedMesh> meshCurvedSheet(const core::Paper& paper, const CurvedMeshSolverConfig& config)
{
  const double spacing = config.spacing * paper.scale();
  // Layers lifted apart need strips beside the creases, which only the bubble mesher makes.
  if (config.mesher == "cgal" && !config.layers)
  {
    core::CgalMeshOptions options;
    options.spacing = spacing;
    return core::cgalMesh(paper, options);
  }
  core::BubbleMeshOptions options;
  options.spacing = spacing;
  if (config.layers)
    options.crease_strip = core::layersFor(paper, core::CurvedFollowOptions().layer_gap).stripFor(paper);
  return core::bubbleMesh(paper, options);
}

namespace
{
core::CurvedSolveOptions solveOptions(const CurvedMeshSolverConfig& config)
{
  core::CurvedSolveOptions options;
  options.method = config.method == "rk4"          ? core::CurvedMethod::Rk4 :
                   config.method == "quasi_newton" ? core::CurvedMethod::QuasiNewton :
                                                     core::CurvedMethod::Newton;
  options.tolerance = config.tolerance;
  options.max_iterations = config.max_iterations;
  options.max_seconds = config.max_seconds;
  options.check_stability = config.check_stability;
  return options;
}
}  // namespace

core::Expected<core::PaperMaterial> physicalPaper(const CurvedMeshSolverConfig& config)
{
  using Failure = core::Expected<core::PaperMaterial>;
  core::PaperMaterial paper;
  if (config.material != "custom")
  {
    core::Expected<core::PaperMaterial> preset = core::paperPreset(config.material);
    if (!preset)
      return Failure::failure("material: " + preset.message() + ", relative or custom");
    paper = *preset;
  }
  // 0 keeps the preset's value; a custom paper needs every one.
  const auto take = [](double given, double& value) {
    if (given != 0.0)
      value = given;
  };
  take(config.thickness, paper.thickness);
  take(config.youngs_modulus, paper.youngs_modulus);
  take(config.poisson_ratio, paper.poisson_ratio);
  take(config.areal_density, paper.areal_density);
  if (const core::Status checked = core::checkPaperMaterial(paper); !checked)
    return Failure::failure(checked.message() + (config.material == "custom" ? " (a custom paper needs thickness, "
                                                                               "youngs_modulus, "
                                                                               "poisson_ratio and areal_density)" :
                                                                               ""));
  return paper;
}

core::Expected<core::CurvedFollowOptions> curvedFollowOptions(const CurvedMeshSolverConfig& config)
{
  using Failure = core::Expected<core::CurvedFollowOptions>;
  core::CurvedFollowOptions options;
  if (config.material == "relative")
    options.material.bend = config.bend * options.material.stretch;
  else
  {
    const core::Expected<core::PaperMaterial> paper = physicalPaper(config);
    if (!paper)
      return Failure::failure(paper.message());
    options.material = *core::curvedMaterial(*paper);
  }
  options.material.crease = config.crease_memory;
  if (const core::Status checked = core::checkCurvedMaterial(options.material); !checked)
    return Failure::failure(checked.message());
  options.surroundings.gravity = config.gravity;
  options.surroundings.table = config.table;
  if (const core::Status checked = core::checkSurroundings(options.surroundings); !checked)
    return Failure::failure(checked.message());
  options.solve = solveOptions(config);
  if (config.layers)
  {
    // Stacked layers lifted apart, a barrier between them (docs/CURVED.md, "A barrier on that
    // start"): Newton with a fresh Hessian every step (the contacts change it), little damping,
    // and pins moved 1/100 spacing a solve, as the folded crane's pulls balance.
    options.layered = true;
    options.solve.modified_newton_rate = 0;
    options.solve.damping = 1e-4;
    options.max_pin_step = 0.01;
  }
  return options;
}

core::Expected<core::CurvedSheetFollower> curvedFollower(const CurvedMeshSolverConfig& config)
{
  core::Expected<core::CurvedFollowOptions> options = curvedFollowOptions(config);
  if (!options)
    return core::Expected<core::CurvedSheetFollower>::failure(options.message());
  return core::CurvedSheetFollower([config](const core::Paper& paper) { return meshCurvedSheet(paper, config); },
                                   *options);
}

namespace
{
// The bent sheet as markers in the state's frame: the triangles' front and back sides, and the
// mesh's edges so that the bend reads in rviz's flat shading.
visualization_msgs::MarkerArray sheetMarkers(const core::CurvedMesh& mesh, const core::Positions& positions,
                                             const std_msgs::Header& header)
{
  visualization_msgs::Marker triangles;
  triangles.header = header;
  triangles.ns = "curved_mesh";
  triangles.id = 0;
  triangles.type = visualization_msgs::Marker::TRIANGLE_LIST;
  triangles.action = visualization_msgs::Marker::ADD;
  triangles.pose.orientation.w = 1.0;
  triangles.scale.x = triangles.scale.y = triangles.scale.z = 1.0;
  // The front (crease-pattern counter-clockwise, the side the crease pattern shows) in the
  // paper markers' colours; the back side, wound the other way, just behind each triangle, so
  // that each side shows its own colour, lit from its side (the front's points stay exact).
  triangles.color.r = 0.96f;
  triangles.color.g = 0.89f;
  triangles.color.b = 0.76f;
  triangles.color.a = 1.0f;
  visualization_msgs::Marker back = triangles;
  back.ns = "curved_mesh_back";
  back.color.r = 0.55f;
  back.color.g = 0.70f;
  back.color.b = 0.86f;
  constexpr double kBehind = 0.0004;  // as the paper markers' side offset
  for (const core::MeshTriangle& t : mesh.triangles)
  {
    const core::Vec3 a = positions.col(t.nodes[0]), b = positions.col(t.nodes[1]), c = positions.col(t.nodes[2]);
    const core::Vec3 normal = (b - a).cross(c - a);
    const core::Vec3 behind = normal.norm() > 0 ? core::Vec3(-kBehind * normal.normalized()) : core::Vec3::Zero();
    for (const core::Vec3& p : { a, b, c })
      triangles.points.push_back(toPoint(p));
    for (const core::Vec3& p : { a, c, b })
      back.points.push_back(toPoint(p + behind));
  }

  visualization_msgs::Marker edges = triangles;
  edges.ns = "curved_mesh_edges";
  edges.type = visualization_msgs::Marker::LINE_LIST;
  edges.scale.x = 0.002;
  edges.color.r = edges.color.g = edges.color.b = 0.2f;
  edges.color.a = 1.0f;
  edges.points.clear();
  for (const core::MeshEdge& e : mesh.edges)
    for (int node : e.nodes)
      edges.points.push_back(toPoint(positions.col(node)));

  visualization_msgs::MarkerArray markers;
  markers.markers = { triangles, back, edges };
  return markers;
}

/// The sheet at `positions` on `curved_mesh`, in the state's frame, stamped `stamp`.
void publishSheet(ros::Publisher& publisher, const core::CurvedMesh& mesh, const core::Positions& positions,
                  std_msgs::Header header, const ros::Time& stamp)
{
  header.stamp = stamp;
  publisher.publish(sheetMarkers(mesh, positions, header));
}

/// Whether `pins` hold other vertices than `shown`, or one farther than `still` from where it was.
bool pinsMoved(const std::vector<core::PullTarget>& pins, const std::vector<core::PullTarget>& shown, double still)
{
  bool moved = pins.size() != shown.size();
  for (size_t i = 0; !moved && i < pins.size(); ++i)
    moved = pins[i].vertex != shown[i].vertex || (pins[i].position - shown[i].position).norm() > still;
  return moved;
}

/// Whether moves of the pins and the mouse on a sheet of `vertices` are shown as anytime frames:
/// the private parameter `anytime_frames` (true by default; false: every move solved to balance)
/// and the sheet at least `anytime_frames_from` vertices (700 by default: below, a move's solve to
/// balance keeps up with a 30 Hz pointer — 495 vertices, p95 46 ms — and a balance is better
/// than a frame; at 999 the solves fall behind in spells, p95 560 ms, the frames 59 ms).
bool anytimeFrames(size_t vertices)
{
  bool anytime = true;
  int from = 700;
  ros::param::getCached("~anytime_frames", anytime);
  ros::param::getCached("~anytime_frames_from", from);
  return anytime && static_cast<long>(vertices) >= from;
}
}  // namespace

CurvedMeshSolverNode::CurvedMeshSolverNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
  : reconfigure_server_(private_nh), tf_listener_(tf_buffer_)
{
  mesh_pub_ = nh.advertise<visualization_msgs::MarkerArray>("curved_mesh", 1, true);
  reconfigure_server_.setCallback([this](CurvedMeshSolverConfig& c, uint32_t level) { reconfigure(c, level); });
  // Only the newest state matters: a slow solve skips the states that came meanwhile.
  state_sub_ = nh.subscribe<PaperState>("state", 1, [this](const PaperState::ConstPtr& s) { onState(s); });
  drag_sub_ = nh.subscribe<VertexTarget>("curved_drag", 1, [this](const VertexTarget::ConstPtr& d) { onDrag(d); });
  keep_bend_client_ = nh.serviceClient<KeepBend>("keep_bend");
  keep_bend_server_ = private_nh.advertiseService("keep_bend", &CurvedMeshSolverNode::keepBend, this);
  const double pin_rate = private_nh.param("pin_rate", 30.0);
  if (pin_rate > 0)
    follow_timer_ = nh.createTimer(ros::Duration(1.0 / pin_rate), &CurvedMeshSolverNode::followFrames, this);
  else
    ROS_ERROR("curved_mesh_solver: pin_rate must be positive (it is %g); the sheet will not follow pins on frames",
              pin_rate);
}

void CurvedMeshSolverNode::reconfigure(CurvedMeshSolverConfig& config, uint32_t)
{
  // Parameters that describe no paper are refused: the sheet keeps the last good ones (and the
  // reconfigure client is shown them again).
  const auto refuse = [&](const std::string& why) {
    ROS_ERROR("curved_mesh_solver: %s; %s", why.c_str(),
              follower_ ? "the previous parameters stay" : "nothing is solved until the parameters are fixed");
    if (follower_)
      config = config_;
  };
  core::Expected<core::CurvedSheetFollower> follower = curvedFollower(config);
  if (!follower)
    return refuse(follower.message());
  // A paper thicker than the current sheet's mesh spacing (checked again on each new sheet).
  const double thickness = curvedFollowOptions(config)->material.thickness;
  if (last_state_)
    if (const core::Expected<core::Paper> paper = fromMessage(*last_state_); paper)
      if (const core::Status thin = core::checkThicknessAgainstSpacing(thickness, config.spacing * paper->scale());
          !thin)
        return refuse(thin.message());
  config_ = config;
  follower_.emplace(std::move(*follower));  // a new mesh and solver with the new parameters
  ROS_INFO("curved_mesh_solver: %s, %s mesh, spacing %g of the sheet, tolerance %g, %s paper%s%s",
           config_.method.c_str(), config_.mesher.c_str(), config_.spacing, config_.tolerance, config_.material.c_str(),
           config_.gravity > 0 || config_.table ? ", weight and table" : "", config_.enabled ? "" : " (disabled)");
  if (last_state_)
    solveAndPublish();
}

void CurvedMeshSolverNode::onState(const PaperState::ConstPtr& state)
{
  if (drag_ && last_state_ && state->revision != last_state_->revision)
    drag_.reset();  // a new paper: the drag of the old one is over (also when its let-go was lost)
  last_state_ = state;
  solveAndPublish();
}

void CurvedMeshSolverNode::onDrag(const VertexTarget::ConstPtr& drag)
{
  if (drag->vertex < 0)
  {
    // Let go, the paper springs back to the state's own sheet (solved from its rigid faces: a
    // bend undone by the solve would stop wherever the soft bending's forces fall below the
    // tolerance).
    const bool held = drag_.has_value();
    drag_.reset();
    if (held && last_state_)
      solveAndPublish(true);
    return;
  }
  const core::Vec3 position = toVec3(drag->position);
  if (!position.allFinite() ||
      (last_state_ && !drag->header.frame_id.empty() && drag->header.frame_id != last_state_->header.frame_id))
  {
    ROS_WARN_THROTTLE(5.0,
                      "curved_mesh_solver: a drag of vertex %d to a point that is not finite or not in the "
                      "paper's frame (%s) is ignored",
                      drag->vertex, drag->header.frame_id.c_str());
    return;
  }
  drag_ = core::PullTarget{ drag->vertex, position };
  drag_stamp_ = drag->header.stamp;
}

bool CurvedMeshSolverNode::currentPins(std::vector<core::PullTarget>& pins, ros::Time& stamp, std::string& error,
                                       const ros::Duration& wait)
{
  pins.clear();
  for (const Pin& pin : last_state_->pins)
  {
    if (pin.vertex < 0 || pin.vertex >= static_cast<int>(last_state_->vertices_folded.size()))
    {
      error = "pinned vertex " + std::to_string(pin.vertex) + " does not exist";
      return false;
    }
    if (pin.frame_id.empty())
    {
      pins.push_back({ pin.vertex, toVec3(last_state_->vertices_folded[pin.vertex]) });
      continue;
    }
    try
    {
      const geometry_msgs::TransformStamped t =
          tf_buffer_.lookupTransform(last_state_->header.frame_id, pin.frame_id, ros::Time(0), wait);
      pins.push_back(
          { pin.vertex, core::Vec3(t.transform.translation.x, t.transform.translation.y, t.transform.translation.z) });
      stamp = std::max(stamp, t.header.stamp);
    }
    catch (const tf2::TransformException& e)
    {
      error =
          "vertex " + std::to_string(pin.vertex) + " follows " + pin.frame_id + ", which tf cannot place: " + e.what();
      return false;
    }
  }
  // The dragged vertex, unless the state does not have it or pins it itself (a pin holds).
  if (drag_ && drag_->vertex < static_cast<int>(last_state_->vertices_folded.size()) &&
      std::none_of(pins.begin(), pins.end(), [&](const core::PullTarget& p) { return p.vertex == drag_->vertex; }))
  {
    pins.push_back(*drag_);
    stamp = std::max(stamp, drag_stamp_);
  }
  return true;
}

void CurvedMeshSolverNode::solveAndPublish(bool anew)
{
  if (!config_.enabled || !follower_)
    return;
  const unsigned long revision = last_state_->revision;
  core::Expected<core::Paper> paper = fromMessage(*last_state_);
  if (!paper)
  {
    ROS_WARN("curved_mesh_solver: state %lu cannot be read: %s", revision, paper.message().c_str());
    return;
  }
  // Stamped with the newest transform followed, else with the state's stamp.
  // A frame just pinned may not have reached this node's tf listener yet: a moment's wait.
  std::vector<core::PullTarget> pins;
  ros::Time stamp;
  std::string error;
  if (!currentPins(pins, stamp, error, ros::Duration(0.5)))
  {
    // A frame tf does not know yet: its vertex held where the model has it until it does.
    ROS_WARN_THROTTLE(5.0, "curved_mesh_solver: state %lu: %s; its vertex stays where the state has it", revision,
                      error.c_str());
    stamp = ros::Time();
    pins.clear();
    for (const Pin& pin : last_state_->pins)
      if (pin.vertex >= 0 && pin.vertex < static_cast<int>(last_state_->vertices_folded.size()))
        pins.push_back({ pin.vertex, toVec3(last_state_->vertices_folded[pin.vertex]) });
  }
  if (stamp.isZero())
    stamp = last_state_->header.stamp;
  const core::Expected<core::CurvedReport> report = follower_->solveState(*paper, pins, anew);
  if (!report)
  {
    // Never publish a diverged sheet; the last good one stays on the latched topic.
    ROS_WARN("curved_mesh_solver: state %lu: %s", revision, report.message().c_str());
    return;
  }
  publish(stamp, *report, "state");
}

void CurvedMeshSolverNode::followFrames(const ros::TimerEvent&)
{
  if (!config_.enabled || !follower_ || !follower_->hasSheet() || !last_state_)
    return;
  bool on_frames = drag_.has_value();
  for (const Pin& pin : last_state_->pins)
    on_frames = on_frames || !pin.frame_id.empty();
  if (!on_frames)
    return;
  std::vector<core::PullTarget> pins;
  ros::Time stamp;
  std::string error;
  if (!currentPins(pins, stamp, error))
  {
    ROS_WARN_THROTTLE(5.0, "curved_mesh_solver: %s; the sheet stays", error.c_str());
    return;
  }
  // A frame standing still leaves a balanced sheet as it is; a sheet its solve's budget
  // stopped short of balance is solved on from where it is, a few times, before it is shown.
  const bool moved = pinsMoved(pins, follower_->pins(), 1e-9 * follower_->paper().scale());
  constexpr int kResumes = 5;
  // Anytime frames know only the penalty contact: with `layers` every move is solved.
  if (follower_->onFrames() || (moved && !config_.layers && anytimeFrames(follower_->mesh().nodes.size())))
  {
    // Anytime frames: each move shown at once as one frame (anytime_frames.h), not balanced;
    // pins standing still for kStillSeconds after the last frame settle the sheet to the
    // tolerance, shown then (timed from the frame, not counted in cycles: after a long frame the
    // timer's next cycle may come before the drag that arrived meanwhile).
    constexpr double kStillSeconds = 0.1;
    if (moved)
    {
      resumed_ = 0;
      const core::Expected<core::FrameReport> frame = follower_->frame(pins);
      if (!frame)
      {
        ROS_WARN_THROTTLE(5.0, "curved_mesh_solver: a frame after the pins' frames%s: %s",
                          drag_ ? " and the mouse" : "", frame.message().c_str());
        return;
      }
      publishSheet(mesh_pub_, follower_->mesh(), follower_->positions(), last_state_->header, stamp);
      ROS_DEBUG("curved_mesh_solver: state %lu, frame of %zu nodes, %d corrections in %.1f ms, force %g%s",
                static_cast<unsigned long>(last_state_->revision), follower_->mesh().nodes.size(), frame->corrections,
                1e3 * frame->seconds, frame->max_force, frame->inertial ? " (inertial)" : "");
      return;
    }
    if (follower_->secondsSinceFrame() < kStillSeconds || resumed_ >= kResumes)
      return;
    ++resumed_;  // settles tried since the last frame
    const core::Expected<core::CurvedReport> settled = follower_->settle();
    if (settled)
      publish(stamp, *settled, drag_ ? "mouse, settled" : "frames, settled");
    return;
  }
  if (!moved && (follower_->balanced() || resumed_ >= kResumes))
    return;
  resumed_ = moved ? 0 : resumed_ + 1;
  const core::Expected<core::CurvedReport> report = follower_->follow(pins);
  if (!report)
  {
    ROS_WARN_THROTTLE(5.0, "curved_mesh_solver: following the pins' frames%s: %s", drag_ ? " and the mouse" : "",
                      report.message().c_str());
    return;
  }
  // Only balanced sheets are shown while frames move: an unbalanced one is solved on next cycle.
  if (!report->converged && resumed_ < kResumes)
    return;
  publish(stamp, *report, drag_ ? "mouse" : "frames");
}

bool CurvedMeshSolverNode::keepBend(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res)
{
  res.success = false;
  if (!follower_ || !follower_->hasSheet() || !last_state_)
  {
    res.message = "no bent sheet is shown: nothing to keep";
    return true;
  }
  if (follower_->onFrames())
  {
    // The frame shown is not balanced: the sheet kept is the converged one, at the pins as they
    // are now (moved since the last frame: a full solve from the frame to them).
    std::vector<core::PullTarget> pins;
    ros::Time stamp;
    std::string error;
    const bool moved =
        currentPins(pins, stamp, error) && pinsMoved(pins, follower_->pins(), 1e-9 * follower_->paper().scale());
    const core::Expected<core::CurvedReport> settled = moved ? follower_->follow(pins) : follower_->settle();
    if (settled)
      publish(drag_ ? drag_stamp_ : last_state_->header.stamp, *settled, "kept, settled");
    if (!settled || !settled->converged)
    {
      res.message = "the bent sheet did not settle to balance (" +
                    (settled ? "force " + std::to_string(settled->max_force) : settled.message()) + "): nothing kept";
      return true;
    }
  }
  const core::BentSheet sheet = core::bentSheetOf(follower_->mesh(), follower_->positions());
  KeepBend srv;
  for (const core::Vec2& p : sheet.points)
    srv.request.points.push_back(toPoint(core::Vec3(p.x(), p.y(), 0.0)));
  for (const std::array<int, 3>& t : sheet.triangles)
    srv.request.triangles.insert(srv.request.triangles.end(), t.begin(), t.end());
  for (const core::Vec3& p : sheet.positions)
    srv.request.positions.push_back(toPoint(p));
  if (!keep_bend_client_.call(srv))
  {
    res.message = "the service " + keep_bend_client_.getService() + " did not answer: nothing kept";
    return true;
  }
  res.success = srv.response.success;
  res.message = srv.response.message;
  if (res.success)
    drag_.reset();  // the model holds the bend now: nothing springs back
  return true;
}

void CurvedMeshSolverNode::publish(const ros::Time& stamp, const core::CurvedReport& report, const char* what)
{
  publishSheet(mesh_pub_, follower_->mesh(), follower_->positions(), last_state_->header, stamp);
  if (!report.converged)
    ROS_WARN_THROTTLE(5.0, "curved_mesh_solver: state %lu (%s): not balanced after %d iterations (force %g)",
                      static_cast<unsigned long>(last_state_->revision), what, report.iterations, report.max_force);
  ROS_DEBUG("curved_mesh_solver: state %lu (%s), %zu nodes, %d steps, %d iterations, residual %g",
            static_cast<unsigned long>(last_state_->revision), what, follower_->mesh().nodes.size(),
            follower_->lastSteps(), report.iterations, report.max_force);
}

}  // namespace virtual_origami
