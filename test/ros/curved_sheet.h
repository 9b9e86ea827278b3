// The sheets curved_mesh_solver publishes on `curved_mesh`, read back as node positions.
#pragma once

#include <optional>
#include <vector>

#include <visualization_msgs/Marker.h>

#include "virtual_origami/curved/curved_mesh.h"
#include "virtual_origami/ros/conversions.h"

namespace virtual_origami::test
{
/// The node positions of a published sheet: the triangles come in the order of the mesh the
/// node made, which the same mesher makes again from the same state; nothing when they are not
/// that mesh's (a count or a shared node that does not match).
inline std::optional<core::Positions> nodePositions(const visualization_msgs::Marker& triangles,
                                                    const core::CurvedMesh& mesh)
{
  if (triangles.points.size() != 3 * mesh.triangles.size())
    return std::nullopt;
  core::Positions x = core::Positions::Zero(3, static_cast<Eigen::Index>(mesh.nodes.size()));
  std::vector<char> seen(mesh.nodes.size(), 0);
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
    {
      const int node = mesh.triangles[t].nodes[k];
      const core::Vec3 p = toVec3(triangles.points[3 * t + k]);
      if (seen[node] && (x.col(node) - p).norm() > 1e-12)
        return std::nullopt;  // not this mesh
      x.col(node) = p;
      seen[node] = 1;
    }
  return x;
}

}  // namespace virtual_origami::test
