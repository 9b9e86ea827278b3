// What a QuasiNewtonDriver keeps between its calls (private to src/solvers): the energy and the
// factorised matrices while the pattern stays, the last frames for the prediction, and where
// the Gauss–Newton matrix's entries land (shared with the driver's clones).
#pragma once

#include <cmath>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include <Eigen/CholmodSupport>

#include "virtual_origami/core/face_springs.h"
#include "virtual_origami/numerics/spd_factorization.h"
#include "virtual_origami/solvers/driven_faces.h"
#include "virtual_origami/solvers/quasi_newton_driver.h"

namespace virtual_origami::core
{
/// A crease the targets drive (the others are NaN: free to follow).
inline bool driven(double target)
{
  return std::isfinite(target);
}

struct QuasiNewtonDriver::AssemblyPlan
{
  std::mutex mutex;
  std::vector<std::pair<int, int>> entries;  // the (row, column) of each entry it was made for
  std::vector<int> slots;
  Eigen::SparseMatrix<double> pattern;  // compressed

  bool matches(const std::vector<Eigen::Triplet<double>>& triplets) const;
  /// Plans the compressed pattern of `triplets` and where each lands in it.
  void plan(const std::vector<Eigen::Triplet<double>>& triplets, int rows);
};

/// What stays while the pattern, the held vertices and the set of driven creases stay: the
/// energy's faces and hinges, and the factorised constant matrix. Also the last frames, for
/// the prediction.
struct QuasiNewtonDriver::Setup
{
  // CHOLMOD's supernodal factor (its own choice of ordering): against Eigen's simplicial one with
  // AMD, half the set-up and less than half the back-substitution on a 10,000-vertex pattern.
  using Factor = Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>;

  std::vector<std::vector<int>> face_vertices;
  std::vector<Vec2> crease_pattern;
  std::vector<char> fixed;
  std::vector<char> driven_edges;
  std::vector<Spring> springs;  // the faces' vertex pairs, for the strain reported
  DrivenFaces energy;
  std::vector<int> free_index, free_vertices;
  Eigen::SparseMatrix<double> constant_matrix;  // until it is factorised
  Factor factor;                                // the constant matrix
  bool constant_tried = false, factored = false;
  int free_count = 0;
  numerics::SpdFactorization gauss_newton;  // the lagged or exact matrix, 3 rows per free vertex
  // Each face's fitted frame where gauss_newton was factorised (Lagged: how far they turned since).
  std::vector<Eigen::Matrix<double, 3, 2>> factor_frames;
  Eigen::SparseMatrix<double> gauss_newton_matrix;
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<int> slots;         // where each of the triplets lands among the matrix's values
  double factor_seconds = 0.0;    // wall time the last factorisation took
  double restore_seconds = 0.0;   // wall time the last restoring step took
  double evaluate_seconds = 0.0;  // wall time the last energy pass of a line search took
  // The step length the subspace frames' line searches start at (remember_frame_step), and how
  // many frames in a row took their first trial at it.
  double frame_step = 1.0;
  int frame_first_trials = 0;
  // The last two frames this driver returned (as in the paper) and their targets, and where
  // the last one started.
  Positions last, before_last, last_start;
  std::vector<double> last_target, before_last_target;
  bool last_balanced = true;      // whether the last frame reached balance within its budget
  bool last_continued = false;    // the last frame went on from the one before it
  double last_face_energy = 0.0;  // the face term of the energy at the last frame
  // Where QuasiNewtonDriver::prepare factorised the Gauss–Newton matrix before any frame: the
  // first frame from there takes that factor as its own (empty: not prepared).
  Positions prepared_start;

  Setup(const Paper& paper, const std::vector<char>& held, const std::vector<double>& target, double stiffness,
        std::shared_ptr<numerics::SpdFactorization::SharedAnalysis> analysis);

  /// The constant matrix factorised at its first use: a commit or a turn whose steps are all
  /// taken whole needs none (its analysis and factorisation are 30 ms on 10,000 vertices).
  bool factorConstant();
  /// The constant matrix's solve; zero where it is not definite (no step from it).
  Eigen::MatrixX3d solveConstant(const Eigen::MatrixX3d& rhs);
  bool matches(const Paper& paper, const std::vector<char>& held, const std::vector<double>& target) const;

  static std::vector<Vec2> creasePattern(const Paper& paper);
  static std::vector<char> drivenEdges(const Paper& paper, const std::vector<double>& target);
};

}  // namespace virtual_origami::core
