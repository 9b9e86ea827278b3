#include "virtual_origami/ros/curved_mesh_solver_node.h"

#include <visualization_msgs/MarkerArray.h>

#include "virtual_origami/curved/bubble_mesh.h"
#include "virtual_origami/curved/cgal_mesh.h"
#include "virtual_origami/ros/conversions.h"

namespace virtual_origami
{
namespace
{
core::Expected<core::CurvedMesh> meshPaper(const core::Paper& paper, const CurvedMeshSolverConfig& config)
{
  const double spacing = config.spacing * paper.scale();
  if (config.mesher == "cgal")
  {
    core::CgalMeshOptions options;
    options.spacing = spacing;
    return core::cgalMesh(paper, options);
  }
  core::BubbleMeshOptions options;
  options.spacing = spacing;
  return core::bubbleMesh(paper, options);
}
}  // namespace

core::Expected<CurvedSheet> solveCurvedSheet(const core::Paper& paper, const std::vector<int>& held,
                                             const CurvedMeshSolverConfig& config)
{
  core::Expected<core::CurvedMesh> mesh = meshPaper(paper, config);
  if (!mesh)
    return core::Expected<CurvedSheet>::failure("cannot mesh the paper: " + mesh.message());

  CurvedSheet sheet;
  sheet.mesh = std::move(*mesh);
  sheet.positions = core::placeNodes(sheet.mesh, paper);
  std::vector<core::CurvedPin> pins;
  for (int v : held)
  {
    if (v < 0 || v >= static_cast<int>(sheet.mesh.vertex_nodes.size()))
      return core::Expected<CurvedSheet>::failure("pinned vertex " + std::to_string(v) + " does not exist");
    const int node = sheet.mesh.vertex_nodes[v];
    pins.push_back({ node, paper.vertices[v].folded });
  }

  core::CurvedMaterial material;
  material.bend = config.bend * material.stretch;
  core::CurvedSolveOptions options;
  options.method = config.method == "rk4" ? core::CurvedMethod::Rk4 : core::CurvedMethod::Newton;
  options.tolerance = config.tolerance;
  options.max_iterations = config.max_iterations;
  options.max_seconds = config.max_seconds;
  core::CurvedSolver solver(sheet.mesh, paper, material, core::ContactOptions{}, options);
  sheet.report = solver.solve(sheet.positions, pins);
  return sheet;
}

namespace
{
// The bent sheet as two markers in the state's frame: triangles, and the mesh's edges so that
// the bend reads in rviz's flat shading.
visualization_msgs::MarkerArray sheetMarkers(const CurvedSheet& sheet, const std_msgs::Header& header)
{
  visualization_msgs::Marker triangles;
  triangles.header = header;
  triangles.ns = "curved_mesh";
  triangles.id = 0;
  triangles.type = visualization_msgs::Marker::TRIANGLE_LIST;
  triangles.action = visualization_msgs::Marker::ADD;
  triangles.pose.orientation.w = 1.0;
  triangles.scale.x = triangles.scale.y = triangles.scale.z = 1.0;
  triangles.color.r = 0.55f;
  triangles.color.g = 0.75f;
  triangles.color.b = 0.95f;
  triangles.color.a = 0.85f;
  for (const core::MeshTriangle& t : sheet.mesh.triangles)
    for (int node : t.nodes)
      triangles.points.push_back(toPoint(sheet.positions.col(node)));

  visualization_msgs::Marker edges = triangles;
  edges.ns = "curved_mesh_edges";
  edges.type = visualization_msgs::Marker::LINE_LIST;
  edges.scale.x = 0.002;
  edges.color.r = edges.color.g = edges.color.b = 0.2f;
  edges.color.a = 1.0f;
  edges.points.clear();
  for (const core::MeshEdge& e : sheet.mesh.edges)
    for (int node : e.nodes)
      edges.points.push_back(toPoint(sheet.positions.col(node)));

  visualization_msgs::MarkerArray markers;
  markers.markers = { triangles, edges };
  return markers;
}
}  // namespace

CurvedMeshSolverNode::CurvedMeshSolverNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
  : reconfigure_server_(private_nh)
{
  mesh_pub_ = nh.advertise<visualization_msgs::MarkerArray>("curved_mesh", 1, true);
  reconfigure_server_.setCallback([this](CurvedMeshSolverConfig& c, uint32_t level) { reconfigure(c, level); });
  // Only the newest state matters: a slow solve skips the states that came meanwhile.
  state_sub_ = nh.subscribe<PaperState>("state", 1, [this](const PaperState::ConstPtr& s) { onState(s); });
}

void CurvedMeshSolverNode::reconfigure(CurvedMeshSolverConfig& config, uint32_t)
{
  config_ = config;
  ROS_INFO("curved_mesh_solver: %s, %s mesh, spacing %g of the sheet, tolerance %g%s", config_.method.c_str(),
           config_.mesher.c_str(), config_.spacing, config_.tolerance, config_.enabled ? "" : " (disabled)");
  if (last_state_)
    solveAndPublish();
}

void CurvedMeshSolverNode::onState(const PaperState::ConstPtr& state)
{
  last_state_ = state;
  solveAndPublish();
}

void CurvedMeshSolverNode::solveAndPublish()
{
  if (!config_.enabled)
    return;
  core::Expected<core::Paper> paper = fromMessage(*last_state_);
  if (!paper)
  {
    ROS_WARN("curved_mesh_solver: state %lu cannot be read: %s", static_cast<unsigned long>(last_state_->revision),
             paper.message().c_str());
    return;
  }
  std::vector<int> held;
  for (const Pin& pin : last_state_->pins)
    held.push_back(pin.vertex);
  core::Expected<CurvedSheet> sheet = solveCurvedSheet(*paper, held, config_);
  if (!sheet)
  {
    ROS_WARN("curved_mesh_solver: state %lu: %s", static_cast<unsigned long>(last_state_->revision),
             sheet.message().c_str());
    return;
  }
  if (sheet->report.diverged)
  {
    // Never publish a diverged sheet; the last good one stays on the latched topic.
    ROS_WARN("curved_mesh_solver: state %lu diverged: %s", static_cast<unsigned long>(last_state_->revision),
             sheet->report.message.c_str());
    return;
  }
  mesh_pub_.publish(sheetMarkers(*sheet, last_state_->header));
  ROS_DEBUG("curved_mesh_solver: state %lu, %zu nodes, %d iterations, residual %g",
            static_cast<unsigned long>(last_state_->revision), sheet->mesh.nodes.size(), sheet->report.iterations,
            sheet->report.max_force);
}

}  // namespace virtual_origami
