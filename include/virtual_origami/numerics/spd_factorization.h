// The sparse Cholesky factorisation behind the curved Newton solver: CHOLMOD's supernodal
// LLᵀ of A + μI (the Levenberg–Marquardt shift applied inside the factorisation, no copy of
// A). Its fill-reducing ordering and symbolic analysis depend on A's pattern alone, so they
// are computed once and reused while the pattern stays (it changes only when contact pairs
// come or go).
#pragma once

#include <memory>
#include <mutex>

#include <Eigen/Sparse>

namespace virtual_origami::numerics
{
/// The BLAS the supernodal factorisations call (Debian's serial OpenBLAS) keeps its work
/// buffers in globals without locks: two threads in it at once get each other's buffers and
/// wrong factors. Every supernodal factorisation and solve in the process holds this lock.
/// It also keeps the calling thread's OpenMP (CHOLMOD's threads) to one core, unless
/// OMP_NUM_THREADS asks for more (spd_factorization.cpp says why).
std::unique_lock<std::mutex> lockBlas();

class SpdFactorization
{
public:
  SpdFactorization();
  ~SpdFactorization();
  SpdFactorization(const SpdFactorization&) = delete;
  SpdFactorization& operator=(const SpdFactorization&) = delete;

  /// Factorises a + shift·I (a symmetric; its lower triangle is read). False when that is
  /// not positive definite; the factor is then unusable until the next success.
  bool factorize(const Eigen::SparseMatrix<double>& a, double shift);
  /// (a + shift·I)⁻¹ b with the last successful factorisation.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  bool valid() const { return valid_; }
  int rows() const { return rows_; }
  /// Symbolic analyses done so far (one per new pattern; one taken from a shared analysis
  /// does not count).
  int analyses() const { return analyses_; }
  void reset() { valid_ = false; }

  /// An analysis several factorisations of one pattern share (a driver's clones): the first to
  /// meet the pattern analyses it, the others copy its ordering and symbolic factor, which
  /// depend on the pattern alone, so every factor is the one a fresh analysis gives. Thread-safe.
  class SharedAnalysis;
  static std::shared_ptr<SharedAnalysis> makeSharedAnalysis();
  void shareAnalysis(std::shared_ptr<SharedAnalysis> shared) { shared_ = std::move(shared); }

private:
  bool finishFactorize(const Eigen::SparseMatrix<double>& a, double shift);

  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::shared_ptr<SharedAnalysis> shared_;
  bool valid_ = false;
  int rows_ = 0;
  int analyses_ = 0;
};

}  // namespace virtual_origami::numerics
