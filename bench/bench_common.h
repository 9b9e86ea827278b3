// Helpers the benchmark programs share: a wall clock and a CPU clock, the machine's memory
// bandwidth (the floor of an explicit step) and a structured sheet mesh of any size.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <vector>

#include "virtual_origami/curved/curved_mesh.h"

namespace virtual_origami::bench
{
using namespace virtual_origami::core;

inline double now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// A Miura-ori's corner face (face 0) turns about its zigzag crease: the last of its creases not
/// parallel to x; -1 if none.
inline int cornerAxis(const Paper& paper)
{
  int axis = -1;
  for (int e : paper.faces[0].edges)
    if (paper.edges[e].isCrease() && std::abs(paper.vertices[paper.edges[e].vertices[1]].crease_pattern.y() -
                                              paper.vertices[paper.edges[e].vertices[0]].crease_pattern.y()) > 1e-9)
      axis = e;
  return axis;
}

/// This process's CPU seconds (all its threads), for times on one core of a shared machine.
inline double cpuNow()
{
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

/// Sustained memory bandwidth in bytes per second: the STREAM triad a = b + s·c, best of five,
/// bytes counted as STREAM does (24 per element: two reads, one write). `check` receives an
/// element of the result so the loop cannot be optimised away.
inline double triadBandwidth(double* check = nullptr)
{
  const size_t n = size_t(1) << 24;  // 128 MiB per array, far past the caches
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  double best = 1e30;
  for (int r = 0; r < 5; ++r)
  {
    const double start = now();
    const double s = 3.0 + r;
    for (size_t i = 0; i < n; ++i)
      a[i] = b[i] + s * c[i];
    best = std::min(best, now() - start);
  }
  if (check)
    *check = a[n / 2];
  return 24.0 * n / best;
}

/// An n × n grid of nodes over the unit square, each cell split on a diagonal: a structured
/// 10,000-node sheet without the cost of bubble-meshing it.
inline CurvedMesh gridMesh(const Paper& paper, int n)
{
  CurvedMesh mesh;
  mesh.spacing = 1.0 / (n - 1);
  mesh.curved_faces.assign(paper.faces.size(), 1);
  mesh.vertex_nodes.assign(paper.vertices.size(), -1);
  const auto edgeOf = [&](const Vec2& p, double* t) {
    for (size_t e = 0; e < paper.edges.size(); ++e)
    {
      const Vec2 a = paper.vertices[paper.edges[e].vertices[0]].crease_pattern;
      const Vec2 b = paper.vertices[paper.edges[e].vertices[1]].crease_pattern;
      const double s = (p - a).dot(b - a) / (b - a).squaredNorm();
      if (s > 0 && s < 1 && (a + s * (b - a) - p).norm() < 1e-12)
      {
        *t = s;
        return static_cast<int>(e);
      }
    }
    return -1;
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      MeshNode node;
      node.crease_pattern = Vec2(i * mesh.spacing, j * mesh.spacing);
      if ((i == 0 || i == n - 1) && (j == 0 || j == n - 1))
        for (size_t v = 0; v < paper.vertices.size(); ++v)
          if ((paper.vertices[v].crease_pattern - node.crease_pattern).norm() < 1e-12)
          {
            node.paper_vertex = static_cast<int>(v);
            mesh.vertex_nodes[v] = static_cast<int>(mesh.nodes.size());
          }
      if (node.paper_vertex < 0)
        node.paper_edge = edgeOf(node.crease_pattern, &node.edge_t);
      if (node.paper_vertex < 0 && node.paper_edge < 0)
        node.paper_face = 0;
      mesh.nodes.push_back(node);
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i)
    {
      const int a = j * n + i, b = a + 1, c = a + n + 1, d = a + n;
      mesh.triangles.push_back({ { a, b, c }, 0 });
      mesh.triangles.push_back({ { a, c, d }, 0 });
    }
  const Status linked = linkMesh(mesh, paper);
  if (!linked.ok())
  {
    std::cerr << "grid mesh: " << linked.message() << "\n";
    std::exit(1);
  }
  return mesh;
}

}  // namespace virtual_origami::bench
