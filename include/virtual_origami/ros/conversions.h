// Between the core's values and the package's messages. Pure functions, no node state.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <geometry_msgs/Point.h>
#include <geometry_msgs/TransformStamped.h>
#include <virtual_origami/Operation.h>
#include <virtual_origami/PaperState.h>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/core/session.h"

namespace virtual_origami
{
geometry_msgs::Point toPoint(const core::Vec3& v);
core::Vec3 toVec3(const geometry_msgs::Point& p);
/// Frame `child` at `at` in `parent`, turned by `yaw` about parent's z, stamped now.
geometry_msgs::TransformStamped frameTransform(const std::string& parent, const std::string& child,
                                               const core::Vec3& at, double yaw = 0.0);

/// A pinned vertex: held where it is (empty frame) or following a tf frame.
struct PinnedVertex
{
  std::string frame_id;
  core::Vec3 position = core::Vec3::Zero();  // in `frame_id`, or in `paper` when empty
};
using Pins = std::map<int, PinnedVertex>;

PaperState toMessage(const core::Paper& paper, uint64_t revision, const Pins& pins);
/// Fails with a message on inconsistent input (lengths, indices, assignments, topology).
core::Expected<core::Paper> fromMessage(const PaperState& state);

/// Every parameter of the operation (rotate's carry_stack as picked_layers_only = !carry_stack;
/// a flat fold's segments at z = 0). `after`, the paper the operation made, gives a fold by
/// assignment's result (`folded`), which the session's log does not keep.
Operation toMessage(const core::Operation& operation, const core::Paper* after = nullptr);
/// The operation a message names, for applying it to a session again; fails on a type that is
/// not in a session's history (pin) or unknown, and on arrays of different lengths.
core::Expected<core::Operation> fromMessage(const Operation& operation);

/// A bent sheet from its message fields (KeepBend.srv, Operation.msg): the nodes' crease-pattern
/// points, three node indices per triangle, the nodes' positions.
core::Expected<core::BentSheet> bentSheet(const std::vector<geometry_msgs::Point>& points,
                                          const std::vector<int>& triangles,
                                          const std::vector<geometry_msgs::Point>& positions);

/// A fold on chosen creases from the arrays of FlatFold.srv / Operation.msg (z ignored): fails
/// on arrays of different lengths or none.
core::Expected<core::FlatFoldRequest> flatFoldRequest(const std::vector<geometry_msgs::Point>& starts,
                                                     const std::vector<geometry_msgs::Point>& ends,
                                                     const std::vector<double>& angles,
                                                     const geometry_msgs::Point& fixed);

}  // namespace virtual_origami
