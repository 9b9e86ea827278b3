// Bubble mesh (seed 002 §2.2, after Shimada): bubbles on the paper's vertices, then the
// fewest equally spaced bubbles that cover each edge, then bubbles packed inside each face
// by a damped particle simulation; the Delaunay triangulation of their centres is the mesh.
#pragma once

#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"
#include "virtual_origami/curved/curved_mesh.h"

namespace virtual_origami::core
{
/// The inter-bubble force of seed 002 eq. (2.1): f(r) = ar³ + br² + cr + d on 0 ≤ r < r1, 0
/// beyond, positive pushing the bubbles apart. The conditions are f(r0) = 0, f(r1) = 0,
/// f′(0) = 0 and f′(r0) = −k0 — the slope at the stable distance r0, as in Shimada. The seed
/// prints f′(r1) = −k0, but that cubic is positive on (r0, r1) and negative below r0: it
/// pulls touching bubbles together and pushes separated ones apart, so r0 would be unstable.
struct BubbleForce
{
  double r0 = 1.0, r1 = 1.5, k0 = 1.0;
  double a = 0.0, b = 0.0, c = 0.0, d = 0.0;

  static BubbleForce fit(double r0, double r1, double k0);
  double operator()(double r) const { return r < r1 ? ((a * r + b) * r + c) * r + d : 0.0; }
  double slope(double r) const { return r < r1 ? (3 * a * r + 2 * b) * r + c : 0.0; }
};

struct BubbleMeshOptions
{
  /// Bubble diameter r0 (the stable distance, the target edge length), in paper units;
  /// 0: a tenth of the sheet's scale.
  double spacing = 0.0;
  double reach = 1.5;  // r1 / r0: how far the force acts
  /// The packing simulation, in units where r0 = 1, a bubble's mass is 1 and k0 = 1.
  double damping = 1.0;    // force per unit speed
  double time_step = 0.25;  // RK4 step (the stiffest mode, ~6 neighbours, has ω ≈ 3.5)
  int max_steps = 400;
  double settle_speed = 1e-4;  // stop when no bubble moves faster (r0 per time unit)
  /// Rounds of relaxing, then deleting bubbles where the packing is too dense and inserting
  /// them where it has holes.
  int adjust_rounds = 4;
  /// Per paper face: 1 fills it with bubbles so it can bend, 0 leaves it coarse (its own
  /// corners and the bubbles its curved neighbours put on shared edges). Empty: every face.
  std::vector<char> curved_faces;
  /// With a width > 0, a row of nodes that far inside each face beside every crease
  /// (bubbleMesh; see addCreaseStrips): folds whose layers are drawn apart (layered_start.h).
  double crease_strip = 0.0;
};

struct BubbleMeshReport
{
  int steps = 0;     // simulation steps over every face and round
  int inserted = 0;  // bubbles added where the density was too low
  int deleted = 0;   // and removed where it was too high
};

/// The bubble centres as mesh nodes: paper vertices first (node v is vertex v), then the
/// edges' bubbles in edge order and along each edge, then each face's interior bubbles.
std::vector<MeshNode> placeBubbles(const Paper& paper, const BubbleMeshOptions& options,
                                   BubbleMeshReport* report = nullptr);

/// placeBubbles, then the Delaunay triangulation of the centres constrained to the paper's
/// edges, each triangle assigned to the face that holds it. Re-mesh after every fold.
Expected<CurvedMesh> bubbleMesh(const Paper& paper, const BubbleMeshOptions& options = {},
                                BubbleMeshReport* report = nullptr);

/// How many bubbles cover an edge of `length` with bubbles of diameter `spacing` besides the
/// two at its ends (seed 002 §2.2.2: the fewest, equally spaced, that leave no gap).
int edgeBubbleCount(double length, double spacing);

}  // namespace virtual_origami::core
