// A sparse Cholesky factor that one thread makes and another uses: CHOLMOD's supernodal LLᵀ of
// A + shift·I, made under the process's BLAS lock, then copied, and back-substituted supernode
// by supernode with Eigen's dense kernels, not the BLAS. A frame's correction can then use the
// last factor while a background thread makes the next one (numerics::SpdFactorization's
// solves take the BLAS lock, and would wait behind a whole factorisation).
#pragma once

#include <memory>

#include <Eigen/Sparse>

namespace virtual_origami::core
{
class KeptFactor
{
public:
  KeptFactor();
  ~KeptFactor();
  KeptFactor(const KeptFactor&) = delete;
  KeptFactor& operator=(const KeptFactor&) = delete;

  /// Factorises a + shift·I (a symmetric, its lower triangle read; the ordering and symbolic
  /// analysis made once per pattern). False when that is not positive definite; the last good
  /// factor is then kept. `tag` names what the factor was made for (the caller's state), and
  /// goes with it. Not to be called from two threads at once.
  bool factorize(const Eigen::SparseMatrix<double>& a, double shift, long tag = 0);
  /// (a + shift·I)⁻¹ b with the last successful factorisation, from any thread (several at
  /// once, and while the next factorisation is made), without the BLAS lock; `tag`: that
  /// factorisation's. Empty when there is none of b's size.
  Eigen::VectorXd solve(const Eigen::VectorXd& b, long* tag = nullptr) const;
  /// The last successful factorisation's tag (0 before any).
  long tag() const;
  bool valid() const;
  int rows() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace virtual_origami::core
