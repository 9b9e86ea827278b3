#include "virtual_origami/curved/curved_metrics.h"

#include <cmath>

#include "virtual_origami/curved/contact.h"
#include "virtual_origami/curved/curved_forces.h"

namespace virtual_origami::core
{
CurvedMetrics measureCurved(const CurvedMesh& mesh, const Paper& paper, const Positions& x,
                            double penetration_tolerance)
{
  CurvedMetrics m;
  std::vector<Spring> edges;
  for (const MeshEdge& e : mesh.edges)
    edges.push_back(
        { e.nodes[0], e.nodes[1], (mesh.nodes[e.nodes[0]].crease_pattern - mesh.nodes[e.nodes[1]].crease_pattern).norm() });
  m.strain = springStrain(edges, x);

  m.crease_angles.assign(paper.edges.size(), 0.0);
  std::vector<int> hinges_on(paper.edges.size(), 0);
  for (const MeshEdge& e : mesh.edges)
  {
    if (!e.isHinge())
      continue;
    int opposite[2] = { -1, -1 };  // each triangle's node off the hinge (always found)
    for (int side = 0; side < 2; ++side)
      for (int node : mesh.triangles[e.triangles[side]].nodes)
        if (node != e.nodes[0] && node != e.nodes[1])
          opposite[side] = node;
    double angle = hingeAngle(x.col(e.nodes[0]), x.col(e.nodes[1]), x.col(opposite[0]), x.col(opposite[1]));
    const int face = mesh.triangles[e.triangles[0]].face;
    if (face != mesh.triangles[e.triangles[1]].face)
    {
      if (e.paper_edge < 0)
        continue;
      const double recorded = paper.edges[e.paper_edge].fold_angle;
      if (angle - recorded > M_PI)
        angle -= 2 * M_PI;
      else if (recorded - angle > M_PI)
        angle += 2 * M_PI;
      m.crease_angles[e.paper_edge] += angle;
      ++hinges_on[e.paper_edge];
      continue;
    }
    m.max_bend = std::max(m.max_bend, std::abs(angle));
    const double length = (mesh.nodes[e.nodes[0]].crease_pattern - mesh.nodes[e.nodes[1]].crease_pattern).norm();
    const double dual = 2 * (mesh.restArea(e.triangles[0]) + mesh.restArea(e.triangles[1])) / (3 * length);
    m.max_curvature = std::max(m.max_curvature, std::abs(angle) / dual);
    if (face < static_cast<int>(mesh.curved_faces.size()) && !mesh.curved_faces[face])
      m.flatness = std::max(m.flatness, std::abs(angle));
  }
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (hinges_on[e] > 0)
      m.crease_angles[e] /= hinges_on[e];
  m.penetrations = countTriangleCrossings(mesh, x, penetration_tolerance > 0 ? penetration_tolerance : 1e-9 * paper.scale());
  return m;
}

}  // namespace virtual_origami::core
