// FOLD read: every frame resolved (inheritance, a crease pattern for folded forms by unfolding)
// into a Paper. Malformed input is refused by naming the field, never by quoting the file.
#include "virtual_origami/core/fold_io.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "fold_fields.h"
#include "fold_format.h"
#include "format_error.h"
#include "virtual_origami/core/convex_partition.h"
#include "virtual_origami/core/kinematics.h"
#include "virtual_origami/core/planar_geometry.h"
#include "virtual_origami/core/planar_graph.h"
#include "virtual_origami/core/traced_paper.h"

namespace virtual_origami::core
{
namespace
{
/// The faces around a vertex must unfold it to one place within this (relative to the sheet
/// scale): other tools round their coordinates to about 6 digits.
constexpr double kDevelopableTolerance = 1e-4;
/// 3D coordinates within this of one plane (relative to their extent) are a flat sheet.
constexpr double kCoplanarTolerance = 1e-6;
/// Smallest allowed turn at a face corner, as a sine: a little slack for rounded files.
constexpr double kConvexityTolerance = 1e-6;
/// Larger files are refused unread: no paper this tool folds needs one.
constexpr size_t kMaxFoldFileBytes = size_t{ 64 } << 20;
/// A measured fold angle this close to ±180° takes its sign from the assignment.
constexpr double kFlatFoldTolerance = 1e-4;

std::string formatNumber(double x)
{
  std::ostringstream out;
  out << x;
  return out.str();
}

// ---------------------------------------------------------------------------------------------
// Crease-pattern geometry

/// The coordinates in their own plane when they lie in one, else nothing.
std::optional<std::vector<Vec2>> planarCoordinates(const std::vector<Vec3>& coords)
{
  Vec3 low = coords.front(), high = coords.front(), centroid = Vec3::Zero();
  for (const Vec3& p : coords)
  {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
    centroid += p;
  }
  centroid /= static_cast<double>(coords.size());
  const double tolerance = kCoplanarTolerance * (high - low).norm();
  std::vector<Vec2> flat;
  if (high.z() - low.z() <= tolerance)  // the usual z = const sheet: keep x and y as they are
  {
    for (const Vec3& p : coords)
      flat.emplace_back(p.x(), p.y());
    return flat;
  }
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Vec3& p : coords)
    scatter += (p - centroid) * (p - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  const Vec3 normal = solver.eigenvectors().col(0);  // smallest eigenvalue first
  for (const Vec3& p : coords)
    if (std::abs((p - centroid).dot(normal)) > tolerance)
      return std::nullopt;
  // Which side the plane is seen from does not matter: clockwise faces are mirrored later.
  const Vec3 seed = std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = (seed - normal * normal.dot(seed)).normalized();
  const Vec3 w = normal.cross(u);
  for (const Vec3& p : coords)
    flat.emplace_back((p - centroid).dot(u), (p - centroid).dot(w));
  return flat;
}

std::vector<std::array<int, 2>> edgesOfFaces(const std::vector<std::vector<int>>& faces)
{
  std::vector<std::array<int, 2>> edges;
  std::map<std::pair<int, int>, int> seen;
  for (const std::vector<int>& face : faces)
    for (size_t i = 0; i < face.size(); ++i)
    {
      const int a = face[i], b = face[(i + 1) % face.size()];
      if (seen.emplace(std::minmax(a, b), static_cast<int>(edges.size())).second)
        edges.push_back({ a, b });
    }
  return edges;
}

std::vector<Vec2> creasePatternOf(const Paper& paper)
{
  std::vector<Vec2> points;
  for (const Vertex& v : paper.vertices)
    points.push_back(v.crease_pattern);
  return points;
}

std::vector<Vec2> facePolygon(const Paper& paper, int face)
{
  std::vector<Vec2> polygon;
  for (int v : paper.faces[face].vertices)
    polygon.push_back(paper.vertices[v].crease_pattern);
  return polygon;
}

// ---------------------------------------------------------------------------------------------
// Unfolding a folded form

/// A folded face in its own plane seen from its front (Newell normal towards the viewer), so
/// its cycle is counter-clockwise. A face lying in z = const with normal +z keeps its x and y.
std::vector<Vec2> faceInOwnPlane(const Paper& paper, int face)
{
  const Vec3 normal = paper.faceNormal(face);
  const Vec3 seed = std::abs(normal.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = (seed - normal * normal.dot(seed)).normalized();
  const Vec3 w = normal.cross(u);
  std::vector<Vec2> local;
  for (int v : paper.faces[face].vertices)
    local.emplace_back(paper.vertices[v].folded.dot(u), paper.vertices[v].folded.dot(w));
  return local;
}

/// Moves a polygon rigidly (no reflection) so its corners i and j match `a` and `b`: same
/// direction, same midpoint, which splits any rounding error in the edge length evenly.
std::vector<Vec2> matchEdge(const std::vector<Vec2>& polygon, size_t i, size_t j, const Vec2& a, const Vec2& b)
{
  const Vec2 from = polygon[j] - polygon[i], to = b - a;
  const double turn = std::atan2(to.y(), to.x()) - std::atan2(from.y(), from.x());
  const Eigen::Rotation2Dd rotation(turn);
  const Vec2 shift = 0.5 * (a + b) - rotation * (0.5 * (polygon[i] + polygon[j]));
  std::vector<Vec2> moved;
  for (const Vec2& p : polygon)
    moved.push_back(rotation * p + shift);
  return moved;
}

size_t cornerOf(const Face& face, int vertex)
{
  return std::find(face.vertices.begin(), face.vertices.end(), vertex) - face.vertices.begin();
}

/// Each face laid in the plane: face 0 as seen from its front, then breadth first across
/// shared edges, each face turned to meet its neighbour along their edge. A folded form in
/// several pieces (nothing says where one lies from another once unfolded) has each further
/// piece laid the same way from its first face, beside the pieces before it in +x.
std::vector<std::vector<Vec2>> layOutFaces(const Paper& paper)
{
  const size_t face_count = paper.faces.size();
  std::vector<std::vector<Vec2>> placed(face_count);
  double right = -std::numeric_limits<double>::infinity(), gap = 0.0;
  for (size_t root = 0; root < face_count; ++root)
  {
    if (!placed[root].empty())
      continue;
    placed[root] = faceInOwnPlane(paper, static_cast<int>(root));
    std::vector<int> piece{ static_cast<int>(root) };
    std::deque<int> queue{ static_cast<int>(root) };
    while (!queue.empty())
    {
      const int f = queue.front();
      queue.pop_front();
      const Face& face = paper.faces[f];
      for (size_t i = 0; i < face.edges.size(); ++i)
      {
        const Edge& edge = paper.edges[face.edges[i]];
        if (!edge.isCrease() || !placed[edge.otherFace(f)].empty())
          continue;
        const int g = edge.otherFace(f);
        const int a = face.vertices[i], b = face.vertices[(i + 1) % face.vertices.size()];
        const Face& other = paper.faces[g];
        placed[g] = matchEdge(faceInOwnPlane(paper, g), cornerOf(other, a), cornerOf(other, b), placed[f][i],
                              placed[f][(i + 1) % face.vertices.size()]);
        queue.push_back(g);
        piece.push_back(g);
      }
    }
    Vec2 low = Vec2::Constant(std::numeric_limits<double>::infinity()), high = -low;
    for (int f : piece)
      for (const Vec2& p : placed[f])
      {
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
      }
    if (root > 0)  // beside the pieces before, a tenth of the first one's size apart
      for (int f : piece)
        for (Vec2& p : placed[f])
          p.x() += right + gap - low.x();
    if (root == 0)
      gap = 0.1 * (high - low).maxCoeff();
    right = root == 0 ? high.x() : right + gap + (high.x() - low.x());
  }
  return placed;
}

/// The crease pattern of a folded form: its faces laid out in the plane, each vertex at the
/// mean of the places its faces give it, which must agree (the form must be developable).
std::vector<Vec2> unfold(const Paper& paper)
{
  const std::vector<std::vector<Vec2>> placed = layOutFaces(paper);
  double area = 0;
  for (const std::vector<Vec2>& polygon : placed)
    area += std::abs(signedArea(polygon));
  const double tolerance = kDevelopableTolerance * std::sqrt(area);
  const size_t vertex_count = paper.vertices.size();
  std::vector<Vec2> sum(vertex_count, Vec2::Zero()), first(vertex_count, Vec2::Zero());
  std::vector<int> count(vertex_count, 0);
  for (size_t f = 0; f < placed.size(); ++f)
    for (size_t i = 0; i < placed[f].size(); ++i)
    {
      const int v = paper.faces[f].vertices[i];
      const Vec2& p = placed[f][i];
      if (count[v] == 0)
        first[v] = p;
      else if ((p - first[v]).norm() > tolerance)
        fail("folded form is not developable at vertex " + std::to_string(v) + ": its faces unfold it " +
             formatNumber((p - first[v]).norm()) + " apart");
      sum[v] += p;
      ++count[v];
    }
  for (size_t v = 0; v < vertex_count; ++v)
    sum[v] /= static_cast<double>(count[v]);  // every vertex has a face: checked before
  return sum;
}

// ---------------------------------------------------------------------------------------------
// Building a paper

/// FOLD faces are counter-clockwise seen from the paper's front, and the model's faces are
/// counter-clockwise in the crease pattern. A file whose faces are all clockwise shows its
/// crease pattern from the back. Reversing the cycles would turn the front over: every face
/// normal in 3D would flip, and with it the sign of every fold angle and every M/V letter and
/// face order. Mirroring the crease pattern (x → −x) instead shows it from the front: cycles,
/// 3D positions, normals, angles and assignments all stay as the file has them.
void orientCounterClockwise(Paper& paper)
{
  const double min_area = 1e-12 * std::pow(boundingDiagonal(creasePatternOf(paper)), 2);
  int ccw = -1, cw = -1;
  for (size_t f = 0; f < paper.faces.size(); ++f)
  {
    const double area = paper.faceArea(static_cast<int>(f));
    if (std::abs(area) <= min_area)
      fail(indexed("faces_vertices", f) + " has no area in the crease pattern");
    (area > 0 ? ccw : cw) = static_cast<int>(f);
  }
  if (ccw >= 0 && cw >= 0)
    fail(indexed("faces_vertices", cw) + " is clockwise but " + indexed("faces_vertices", ccw) +
         " is counter-clockwise in the crease pattern");
  if (cw >= 0)
    for (Vertex& v : paper.vertices)
      v.crease_pattern.x() = -v.crease_pattern.x();
}

/// Every face must be a simple polygon, counter-clockwise in the crease pattern; a concave one
/// is split into convex pieces (SPEC: faces are convex) joined by new flat edges marked
/// `split`, which formatFold leaves out again. The first piece keeps the face's number and
/// starts at its first vertex; the others come after the file's faces. Returns, for each of
/// the file's faces, the faces it became.
std::vector<std::vector<int>> splitConcaveFaces(Paper& paper)
{
  const double diagonal = boundingDiagonal(creasePatternOf(paper));
  const double touching = 1e-9 * diagonal;  // sides this close meet
  const double slack = 1e-13 * diagonal * diagonal;
  const size_t file_faces = paper.faces.size();
  std::vector<std::vector<int>> pieces_of(file_faces);
  for (size_t f = 0; f < file_faces; ++f)
  {
    pieces_of[f] = { static_cast<int>(f) };
    const std::string name = indexed("faces_vertices", f);
    const std::vector<int> cycle = paper.faces[f].vertices;
    const std::vector<Vec2> polygon = facePolygon(paper, static_cast<int>(f));
    const size_t n = polygon.size();
    double total_turn = 0;
    bool convex = true;
    for (size_t i = 0; i < n; ++i)
    {
      const Vec2 in = polygon[(i + 1) % n] - polygon[i];
      const Vec2 out = polygon[(i + 2) % n] - polygon[(i + 1) % n];
      const double turn = std::atan2(cross2(in, out), in.dot(out));
      const double sine = cross2(in, out) / (in.norm() * out.norm());
      const std::string corner = " (at vertex " + std::to_string(cycle[(i + 1) % n]) + ")";
      if (!std::isfinite(sine))
        fail(name + " has two corners at one point in the crease pattern" + corner);
      // A corner that doubles back (turn near ±π) has a tiny sine too: reject it by angle.
      if (std::abs(turn) > M_PI - kConvexityTolerance)
        fail(name + " doubles back on itself in the crease pattern" + corner);
      convex = convex && sine >= -kConvexityTolerance;
      total_turn += turn;
    }
    if (total_turn > 3 * M_PI)  // all left turns, but winding twice: a star
      fail(name + " winds around twice in the crease pattern (a star, not a polygon)");
    if (convex)
      continue;
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i + 2; j < n; ++j)
      {
        if (i == 0 && j == n - 1)
          continue;  // neighbours round the end
        if (segmentDistance(polygon[i], polygon[(i + 1) % n], polygon[j], polygon[(j + 1) % n]) <= touching)
          fail(name + " crosses or touches itself in the crease pattern (its sides " + std::to_string(cycle[i]) + "-" +
               std::to_string(cycle[(i + 1) % n]) + " and " + std::to_string(cycle[j]) + "-" +
               std::to_string(cycle[(j + 1) % n]) + " meet)");
      }
    const ConvexPieces split = convexPieces(polygon, slack);
    if (split.pieces.empty())
      fail(name + " is concave and could not be split into convex pieces");
    // The piece with the face's first side keeps the face's number and first vertex.
    std::vector<std::vector<int>> pieces;
    for (const std::vector<int>& piece : split.pieces)
    {
      std::vector<int> vertices;
      for (int i : piece)
        vertices.push_back(cycle[i]);
      pieces.push_back(vertices);
    }
    const auto first = std::find_if(pieces.begin(), pieces.end(), [&](const std::vector<int>& piece) {
      const auto at = std::find(piece.begin(), piece.end(), cycle[0]);
      return at != piece.end() && piece[(at - piece.begin() + 1) % piece.size()] == cycle[1];
    });
    if (first == pieces.end())
      fail(name + " is concave and could not be split into convex pieces");
    std::iter_swap(pieces.begin(), first);
    paper.faces[f].vertices = startingAt(pieces[0], cycle[0]);
    for (size_t k = 1; k < pieces.size(); ++k)
    {
      pieces_of[f].push_back(static_cast<int>(paper.faces.size()));
      paper.faces.push_back({ pieces[k], {} });
    }
    for (const auto& [u, v] : split.diagonals)
    {
      Edge edge;
      edge.vertices = { cycle[u], cycle[v] };
      edge.assignment = Assignment::Flat;
      edge.split = true;
      paper.edges.push_back(edge);
    }
  }
  const Status linked = linkTopology(paper);
  if (!linked)
    fail(linked.message());
  return pieces_of;
}

void checkEveryVertexUsed(const std::vector<std::vector<int>>& faces, size_t vertex_count)
{
  std::vector<char> used(vertex_count, 0);
  for (const std::vector<int>& face : faces)
    for (int v : face)
      used[v] = 1;
  for (size_t v = 0; v < vertex_count; ++v)
    if (!used[v])
      fail("vertex " + std::to_string(v) + " (" + indexed("vertices_coords", v) + ") is used by no face");
}

/// The file's face orders, each between every piece of its two faces (splitConcaveFaces).
std::vector<FaceOrder> faceOrdersOf(const std::vector<std::array<int, 3>>& orders,
                                    const std::vector<std::vector<int>>& pieces_of)
{
  const size_t face_count = pieces_of.size();
  std::vector<FaceOrder> result;
  for (size_t i = 0; i < orders.size(); ++i)
  {
    const auto& [f, g, s] = orders[i];
    for (int face : { f, g })
      if (static_cast<size_t>(face) >= face_count)
        fail(indexed("faceOrders", i) + " names face " + std::to_string(face) + " but there are " +
             std::to_string(face_count) + " faces");
    // FOLD [f, g, +1]: f lies on the side g's normal points to, i.e. FaceOrder{g, f, +1}.
    for (int g_piece : pieces_of[g])
      for (int f_piece : pieces_of[f])
        result.push_back({ g_piece, f_piece, s });
  }
  return result;
}

/// Edges with one face are the boundary; the model has no boundary edge between two faces,
/// so such a "B" (a file's slip) becomes an unassigned crease.
void markBoundaries(Paper& paper)
{
  for (Edge& edge : paper.edges)
  {
    if (!edge.isCrease())
    {
      edge.assignment = Assignment::Boundary;
      edge.fold_angle = 0.0;
    }
    else if (edge.assignment == Assignment::Boundary)
      edge.assignment = Assignment::Unassigned;
  }
}

/// A crease pattern lies flat at z = 0, or folded by the file's fold angles when they close
/// (each piece from its first face, which stays where the crease pattern has it).
void foldCreasePattern(Paper& paper, const std::optional<std::vector<std::optional<double>>>& fold_angles)
{
  for (Vertex& v : paper.vertices)
    v.folded = Vec3(v.crease_pattern.x(), v.crease_pattern.y(), 0.0);
  if (!fold_angles)
    return;
  std::vector<double> angles(paper.edges.size(), 0.0);
  bool folded = false;
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
    {
      angles[e] = (*fold_angles)[e].value_or(0.0);  // no value: as drawn, flat
      folded = folded || angles[e] != 0.0;
    }
  if (!folded)
    return;
  // Each piece folded on its own, its first face where the crease pattern has it.
  std::vector<Vec3> placed(paper.vertices.size());
  std::vector<char> reached(paper.faces.size(), 0), vertex_placed(paper.vertices.size(), 0);
  for (size_t start = 0; start < paper.faces.size(); ++start)
  {
    if (reached[start])
      continue;
    const std::vector<char> piece = walkFaces(paper, static_cast<int>(start));
    Paper alone = paper;
    alone.faces.clear();
    alone.edges.clear();
    std::vector<int> faces_of_piece;
    for (size_t f = 0; f < paper.faces.size(); ++f)
      if (piece[f])
      {
        reached[f] = 1;
        faces_of_piece.push_back(static_cast<int>(f));
        alone.faces.push_back(paper.faces[f]);
      }
    std::vector<double> angles_alone;
    for (size_t e = 0; e < paper.edges.size(); ++e)
    {
      const auto [left, right] = paper.edges[e].faces;
      if ((left >= 0 && piece[left]) || (right >= 0 && piece[right]))
      {
        alone.edges.push_back(paper.edges[e]);
        angles_alone.push_back(angles[e]);
      }
    }
    const Expected<std::vector<Vec3>> positions =
        linkTopology(alone) ?
            foldedPositionsFromAngles(alone, angles_alone, 0, Eigen::Isometry3d::Identity(), 1e-6 * paper.scale()) :
            Expected<std::vector<Vec3>>::failure("");
    // Angles that do not close (a non-rigid target, or rounded in the file) cannot place the
    // faces; the crease pattern itself is still good, so it loads flat instead of failing.
    if (!positions)
      return;
    for (int f : faces_of_piece)
      for (int v : paper.faces[f].vertices)
      {
        // Pieces touching at a vertex must agree on it.
        if (vertex_placed[v] && !((placed[v] - (*positions)[v]).norm() <= 1e-6 * paper.scale()))
          return;
        placed[v] = (*positions)[v];
        vertex_placed[v] = 1;
      }
  }
  for (size_t v = 0; v < paper.vertices.size(); ++v)
    paper.vertices[v].folded = placed[v];
  for (size_t e = 0; e < paper.edges.size(); ++e)
    paper.edges[e].fold_angle = angles[e];
}

/// A fold angle measured in 3D; ±180° cannot tell mountain from valley, the assignment can.
double measuredFoldAngle(const Paper& paper, int e)
{
  const double angle = measureFoldAngle(paper, e);
  if (M_PI - std::abs(angle) > kFlatFoldTolerance)
    return angle;
  switch (paper.edges[e].assignment)
  {
    case Assignment::Mountain:
      return -std::abs(angle);
    case Assignment::Valley:
      return std::abs(angle);
    default:
      return angle;
  }
}

void setFoldedFormAngles(Paper& paper, const std::optional<std::vector<std::optional<double>>>& fold_angles)
{
  for (size_t e = 0; e < paper.edges.size(); ++e)
    if (paper.edges[e].isCrease())
    {
      const std::optional<double> given = fold_angles ? (*fold_angles)[e] : std::nullopt;
      paper.edges[e].fold_angle = given ? *given : measuredFoldAngle(paper, static_cast<int>(e));
    }
}

bool hasClass(const FrameData& data, const std::string& name)
{
  return std::find(data.classes.begin(), data.classes.end(), name) != data.classes.end();
}

/// A resolved frame, and whether the file gave it as a crease pattern.
struct BuiltFrame
{
  Paper paper;
  bool crease_pattern = false;
};

/// The crease pattern a frame gives or inherits, before any unfolding.
std::optional<std::vector<Vec2>> givenCreasePattern(const FrameData& data, bool folded_form,
                                                    const std::optional<std::vector<Vec2>>& flat,
                                                    const BuiltFrame* parent)
{
  if (!folded_form)
    return flat;
  if (data.crease_pattern)
    return data.crease_pattern;
  if (parent && parent->crease_pattern && parent->paper.vertices.size() == data.coords.size())
    return creasePatternOf(parent->paper);
  return std::nullopt;
}

/// A frame given by its edges alone, its paper traced from them in the crease pattern
/// (tracePaper: holes, cuts opened, pieces): its fields carried over to the vertices and edges
/// the tracing made, its faces among them.
struct TracedFrame
{
  FrameData data;
  std::vector<Vec2> crease_pattern;
};

TracedFrame traceFrame(const FrameData& data, const std::vector<Vec2>& crease_pattern)
{
  // readFrame made sure there are edges.
  const std::vector<std::array<int, 2>>& edges = *data.edges;
  std::vector<Assignment> assignments =
      data.assignments ? *data.assignments : std::vector<Assignment>(edges.size(), Assignment::Unassigned);
  DrawingNames names;
  names.point = [](int v) { return indexed("vertices_coords", v); };
  names.edge = [](int e) { return indexed("edges_vertices", e); };
  const Expected<TracedPaper> traced =
      tracePaper(crease_pattern, edges, assignments, 1e-12 * std::pow(boundingDiagonal(crease_pattern), 2), names);
  if (!traced)
    fail("edges_vertices: tracing the faces: " + traced.message());
  TracedFrame frame;
  frame.data = data;
  frame.crease_pattern = traced->points;
  FrameData& out = frame.data;
  out.coords.clear();
  for (const VertexSource& source : traced->sources)
    out.coords.push_back((1 - source.t) * data.coords[source.a] + source.t * data.coords[source.b]);
  out.edges = traced->edges;
  out.assignments.emplace();
  if (data.fold_angles)
    out.fold_angles.emplace();
  if (data.target_angles)
    out.target_angles.emplace();
  if (data.facets)
    out.facets.emplace();
  for (const int source : traced->edge_sources)
  {
    // A joint (no source) lies flat and has no target.
    out.assignments->push_back(source >= 0 ? assignments[source] : Assignment::Flat);
    if (out.fold_angles)
      out.fold_angles->push_back(source >= 0 ? (*data.fold_angles)[source] : std::optional<double>(0.0));
    if (out.target_angles)
      out.target_angles->push_back(source >= 0 ? (*data.target_angles)[source] : std::nullopt);
    if (out.facets)
      out.facets->push_back(source >= 0 ? (*data.facets)[source] : 0);
  }
  out.faces = traced->faces;
  out.crease_pattern.reset();
  return frame;
}

/// A file's faces on both sides of a cut (C) edge: the cut opens as tracePaper opens one. Each
/// vertex gets a copy for every group of its faces that meet across edges other than cuts; the
/// faces take their group's copy, and a cut edge one edge for each side.
void openCutsBetweenFaces(FrameData& data, std::optional<std::vector<Vec2>>& crease_pattern)
{
  if (!data.edges || !data.assignments ||
      std::find(data.assignments->begin(), data.assignments->end(), Assignment::Cut) == data.assignments->end())
    return;
  std::vector<std::vector<int>>& faces = *data.faces;
  std::map<std::pair<int, int>, int> edge_of;
  for (size_t e = 0; e < data.edges->size(); ++e)
    edge_of[std::minmax((*data.edges)[e][0], (*data.edges)[e][1])] = static_cast<int>(e);
  const auto isCut = [&](int a, int b) {
    const auto it = edge_of.find(std::minmax(a, b));
    return it != edge_of.end() && (*data.assignments)[it->second] == Assignment::Cut;
  };
  // At each vertex, its faces joined across the sides round it that are not cuts.
  std::vector<std::vector<std::pair<int, size_t>>> corners(data.coords.size());  // (face, index)
  for (size_t f = 0; f < faces.size(); ++f)
    for (size_t i = 0; i < faces[f].size(); ++i)
      corners[faces[f][i]].emplace_back(static_cast<int>(f), i);
  const std::vector<std::vector<int>> original = faces;
  std::vector<int> origin(data.coords.size());  // the file's vertex each vertex copies
  for (size_t v = 0; v < origin.size(); ++v)
    origin[v] = static_cast<int>(v);
  for (size_t v = 0; v < corners.size(); ++v)
  {
    const auto& around = corners[v];
    std::vector<int> group(around.size());
    for (size_t k = 0; k < around.size(); ++k)
      group[k] = static_cast<int>(k);
    const auto root = [&](int k) {
      while (group[k] != k)
        k = group[k];
      return k;
    };
    const auto neighbours = [&](size_t k) {
      const std::vector<int>& face = original[around[k].first];
      const size_t n = face.size(), i = around[k].second;
      return std::array<int, 2>{ face[(i + n - 1) % n], face[(i + 1) % n] };
    };
    for (size_t k = 0; k < around.size(); ++k)
      for (size_t j = k + 1; j < around.size(); ++j)
        for (int w : neighbours(k))
          for (int x : neighbours(j))
            if (w == x && !isCut(static_cast<int>(v), w))
              group[root(static_cast<int>(k))] = root(static_cast<int>(j));
    std::map<int, int> copy;
    for (size_t k = 0; k < around.size(); ++k)
    {
      const auto [it, added] = copy.emplace(root(static_cast<int>(k)),
                                            copy.empty() ? static_cast<int>(v) : static_cast<int>(data.coords.size()));
      if (added && it->second != static_cast<int>(v))
      {
        origin.push_back(static_cast<int>(v));
        data.coords.push_back(data.coords[v]);
        if (crease_pattern)
          crease_pattern->push_back((*crease_pattern)[v]);
        if (data.crease_pattern)
          data.crease_pattern->push_back((*data.crease_pattern)[v]);
      }
      faces[around[k].first][around[k].second] = it->second;
    }
  }
  if (origin.size() == corners.size())
    return;  // no cut between two faces
  // Each edge as the faces now meet it: a cut between two faces becomes two edges.
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> sides;  // file edge ends → ends now
  for (size_t f = 0; f < faces.size(); ++f)
    for (size_t i = 0; i < faces[f].size(); ++i)
    {
      const size_t n = faces[f].size();
      const std::pair<int, int> key = std::minmax(original[f][i], original[f][(i + 1) % n]);
      const std::pair<int, int> now = std::minmax(faces[f][i], faces[f][(i + 1) % n]);
      std::vector<std::pair<int, int>>& seen = sides[key];
      if (std::find(seen.begin(), seen.end(), now) == seen.end())
        seen.push_back(now);
    }
  const size_t file_edges = data.edges->size();
  for (size_t e = 0; e < file_edges; ++e)
  {
    const auto it = sides.find(std::minmax((*data.edges)[e][0], (*data.edges)[e][1]));
    if (it == sides.end())
      continue;
    const int first = (*data.edges)[e][0];
    for (size_t k = 0; k < it->second.size(); ++k)
    {
      // As the file has it: from the copy of its first vertex.
      std::array<int, 2> ends{ it->second[k].first, it->second[k].second };
      if (origin[ends[0]] != first)
        std::swap(ends[0], ends[1]);
      if (k == 0)
      {
        (*data.edges)[e] = ends;
        continue;
      }
      data.edges->push_back(ends);
      data.assignments->push_back((*data.assignments)[e]);
      if (data.fold_angles)
        data.fold_angles->push_back((*data.fold_angles)[e]);
      if (data.target_angles)
        data.target_angles->push_back((*data.target_angles)[e]);
      if (data.facets)
        data.facets->push_back((*data.facets)[e]);
    }
  }
}

/// Vertices (crease pattern when known, folded = the file's coordinates), edges and faces,
/// linked. Assignments default to unassigned; markBoundaries settles the boundary.
Paper linkedPaper(const FrameData& data, const std::vector<std::vector<int>>& faces,
                  const std::optional<std::vector<Vec2>>& crease_pattern)
{
  Paper paper;
  for (size_t v = 0; v < data.coords.size(); ++v)
    paper.vertices.push_back({ crease_pattern ? (*crease_pattern)[v] : Vec2::Zero(), data.coords[v] });
  const std::vector<std::array<int, 2>> edges = data.edges ? *data.edges : edgesOfFaces(faces);
  for (size_t e = 0; e < edges.size(); ++e)
  {
    const Assignment assignment = data.assignments ? (*data.assignments)[e] : Assignment::Unassigned;
    paper.edges.push_back({ edges[e], assignment, 0.0, { -1, -1 }, false, {} });
  }
  for (const std::vector<int>& cycle : faces)
    paper.faces.push_back({ cycle, {} });
  const Status linked = linkTopology(paper);
  if (!linked)
    fail(linked.message());
  return paper;
}

BuiltFrame buildFrame(const json& frame, const BuiltFrame* parent)
{
  FrameData data = readFrame(frame);
  const std::optional<std::vector<Vec2>> flat = planarCoordinates(data.coords);
  BuiltFrame built;
  built.crease_pattern = flat && !hasClass(data, "foldedForm");
  std::optional<std::vector<Vec2>> crease_pattern = givenCreasePattern(data, !built.crease_pattern, flat, parent);
  if (!data.faces)
  {
    if (!crease_pattern)
      fail("faces_vertices is missing: a folded form needs faces_vertices to be unfolded");
    TracedFrame traced = traceFrame(data, *crease_pattern);
    data = std::move(traced.data);
    crease_pattern = std::move(traced.crease_pattern);
  }
  else
    openCutsBetweenFaces(data, crease_pattern);
  const std::vector<std::vector<int>>& faces = *data.faces;
  checkEveryVertexUsed(faces, data.coords.size());

  Paper& paper = built.paper;
  paper = linkedPaper(data, faces, crease_pattern);
  if (!crease_pattern)
  {
    const std::vector<Vec2> unfolded = unfold(paper);
    for (size_t v = 0; v < paper.vertices.size(); ++v)
      paper.vertices[v].crease_pattern = unfolded[v];
  }
  orientCounterClockwise(paper);
  const std::vector<std::vector<int>> pieces_of = splitConcaveFaces(paper);
  paper.face_orders = faceOrdersOf(data.face_orders, pieces_of);
  paper.sheet_area = 0.0;
  for (size_t f = 0; f < paper.faces.size(); ++f)
    paper.sheet_area += paper.faceArea(static_cast<int>(f));
  markBoundaries(paper);
  // The edges splitConcaveFaces added lie flat.
  std::optional<std::vector<std::optional<double>>> fold_angles = data.fold_angles;
  if (fold_angles)
    fold_angles->resize(paper.edges.size(), 0.0);
  // A crease pattern's fold angles say where its creases are meant to go (what folding by
  // assignment drives them to); a folded form's say where they are.
  const size_t file_edges = data.edges ? data.edges->size() : 0;
  for (size_t e = 0; e < paper.edges.size() && e < file_edges; ++e)
  {
    Edge& edge = paper.edges[e];
    if (!edge.isCrease())
      continue;
    if (data.target_angles)
      edge.target_angle = (*data.target_angles)[e];
    else if (built.crease_pattern && fold_angles && (*fold_angles)[e] &&
             (*(*fold_angles)[e] != 0.0 || edge.assignment == Assignment::Flat))
      edge.target_angle = (*fold_angles)[e];
    // A facet bends inside a face of the paper: with its target, it is one again (isFacet).
    if (data.facets && (*data.facets)[e] && edge.target_angle)
      edge.split = true;
  }
  if (built.crease_pattern)
    foldCreasePattern(paper, fold_angles);
  else
    setFoldedFormAngles(paper, fold_angles);
  return built;
}

// ---------------------------------------------------------------------------------------------
// Frames

/// Re-throws a frame's error with the frame named, unless it is the key frame.
template <class F>
auto inFrame(size_t frame, F&& body)
{
  try
  {
    return body();
  }
  catch (const FormatError& e)
  {
    if (frame == 0)
      throw;
    throw FormatError(indexed("file_frames", frame - 1) + ": " + e.what());
  }
}

/// The frames' own dictionaries: frame 0 is the top level (without file metadata, which
/// frames must not inherit), frame i + 1 is file_frames[i].
std::vector<json> ownFrames(const json& root)
{
  std::vector<json> frames(1);
  for (const auto& [key, value] : root.items())
    if (key.rfind("file_", 0) != 0)
      frames[0][key] = value;
  const json* file_frames = findField(root, "file_frames");
  if (!file_frames)
    return frames;
  requireArray(*file_frames, "file_frames");
  for (size_t i = 0; i < file_frames->size(); ++i)
  {
    if (!(*file_frames)[i].is_object())
      fail(indexed("file_frames", i) + " is " + kindOf((*file_frames)[i]) + ", not an object");
    frames.push_back((*file_frames)[i]);
  }
  return frames;
}

/// The frame a frame inherits from, or -1. The key frame inherits from nothing.
int inheritedParent(const json& frame, size_t index, size_t frame_count)
{
  const json* inherit = findField(frame, "frame_inherit");
  if (index == 0 || !inherit)
    return -1;
  if (!inherit->is_boolean())
    fail("frame_inherit is " + kindOf(*inherit) + ", not true or false");
  if (!inherit->get<bool>())
    return -1;
  const json* parent = findField(frame, "frame_parent");
  if (!parent)
    fail("frame_inherit is true but frame_parent is missing");
  const int p = readIndex(*parent, "frame_parent");
  if (static_cast<size_t>(p) >= frame_count)
    fail("frame_parent is " + std::to_string(p) + " but there are " + std::to_string(frame_count) + " frames");
  if (static_cast<size_t>(p) == index)
    fail("frame_parent names the frame itself");
  return p;
}

/// The parent's fields, overridden by the child's own.
json inheritFields(const json& parent, const json& own)
{
  json merged = parent;
  merged.erase("frame_inherit");
  merged.erase("frame_parent");
  for (const auto& [key, value] : own.items())
    merged[key] = value;
  return merged;
}

std::vector<Paper> readFrames(const json& root)
{
  const std::vector<json> own = ownFrames(root);
  const size_t count = own.size();
  std::vector<int> parents(count);
  for (size_t i = 0; i < count; ++i)
    parents[i] = inFrame(i, [&] { return inheritedParent(own[i], i, count); });

  std::vector<json> resolved(count);
  std::vector<std::optional<BuiltFrame>> built(count);
  for (size_t i = 0; i < count; ++i)
  {
    // Build the frame's unbuilt ancestors first, oldest first (a parent may come later in the file).
    std::vector<int> chain;
    for (int f = static_cast<int>(i); f >= 0 && !built[f]; f = parents[f])
    {
      if (chain.size() == count)
        inFrame(i, [] { fail("frame_parent leads round in a loop"); });
      chain.push_back(f);
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it)
    {
      const int f = *it, p = parents[f];
      resolved[f] = p >= 0 ? inheritFields(resolved[p], own[f]) : own[f];
      built[f] = inFrame(f, [&] { return buildFrame(resolved[f], p >= 0 ? &*built[p] : nullptr); });
    }
  }
  std::vector<Paper> papers;
  for (std::optional<BuiltFrame>& frame : built)
    papers.push_back(std::move(frame->paper));
  return papers;
}

FoldDocument readDocument(const json& root)
{
  FoldDocument document;
  const std::optional<std::string> title = readOptionalString(root, "file_title");
  const std::optional<std::string> frame_title = readOptionalString(root, "frame_title");
  document.title = title ? *title : frame_title.value_or("");
  document.creator = readOptionalString(root, "file_creator").value_or("");
  document.frames = readFrames(root);
  return document;
}

/// "line L, column C (byte B)" for the 1-based byte offset nlohmann's parse errors give.
std::string placeIn(const std::string& text, size_t byte)
{
  const size_t end = std::min(byte > 0 ? byte - 1 : 0, text.size());
  const size_t line = 1 + static_cast<size_t>(std::count(text.begin(), text.begin() + static_cast<long>(end), '\n'));
  const size_t line_start = text.rfind('\n', end > 0 ? end - 1 : 0);
  const size_t column = line_start == std::string::npos || end == 0 ? end + 1 : end - line_start;
  return "syntax error at line " + std::to_string(line) + ", column " + std::to_string(column) + " (byte " +
         std::to_string(byte) + ")";
}

}  // namespace

Expected<FoldDocument> parseFold(const std::string& text)
{
  json root;
  try
  {
    root = json::parse(text);
  }
  // nlohmann's messages quote what it last read ("last read: '...'"): say where instead.
  catch (const json::parse_error& e)
  {
    return Expected<FoldDocument>::failure("invalid JSON: " + placeIn(text, e.byte));
  }
  catch (const json::exception&)  // out_of_range, for numbers like 1e999
  {
    return Expected<FoldDocument>::failure("invalid JSON: a number too large for a double");
  }
  if (!root.is_object())
    return Expected<FoldDocument>::failure("invalid FOLD: the top level is " + kindOf(root) + ", not a JSON object");
  try
  {
    return readDocument(root);
  }
  catch (const FormatError& e)
  {
    return Expected<FoldDocument>::failure(e.what());
  }
}

Expected<FoldDocument> readFoldFile(const std::string& path)
{
  // A device, FIFO or directory would block or never end (load of /dev/zero filled memory).
  std::error_code error;
  if (std::filesystem::exists(path, error) && !std::filesystem::is_regular_file(path, error))
    return Expected<FoldDocument>::failure("cannot load " + path + ": not a regular file");
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file)
    return Expected<FoldDocument>::failure("cannot open " + path + ": " + std::strerror(errno));
  std::string text;
  char buffer[1 << 16];
  size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, file)) > 0 && text.size() <= kMaxFoldFileBytes)
    text.append(buffer, got);
  if (text.size() > kMaxFoldFileBytes)
  {
    std::fclose(file);
    return Expected<FoldDocument>::failure("cannot load " + path + ": larger than " +
                                           std::to_string(kMaxFoldFileBytes >> 20) + " MiB");
  }
  const bool read_error = std::ferror(file) != 0;
  const std::string reason = read_error ? std::strerror(errno) : "";
  std::fclose(file);
  if (read_error)
    return Expected<FoldDocument>::failure("cannot read " + path + ": " + reason);
  return parseFold(text);
}

Expected<Paper> loadPaper(const std::string& path)
{
  Expected<FoldDocument> document = readFoldFile(path);
  if (!document)
    return Expected<Paper>::failure(document.message());
  return std::move(document->frames.back());
}

}  // namespace virtual_origami::core
