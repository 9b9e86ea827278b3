#include "virtual_origami/curved/spd_factorization.h"

#include <algorithm>

#include <Eigen/CholmodSupport>

namespace virtual_origami::core
{
struct SpdFactorization::Impl
{
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> llt;
  Eigen::SparseMatrix<double> pattern;  // the matrix the analysis was done for (values unused)
  // Not positive definite is an answer here (the damping then rises), not a warning to print.
  Impl() { llt.cholmod().print = 0; }
};

namespace
{
bool samePattern(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b)
{
  return a.rows() == b.rows() && a.cols() == b.cols() && a.nonZeros() == b.nonZeros() &&
         std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
}
}  // namespace

SpdFactorization::SpdFactorization() : impl_(std::make_unique<Impl>()) {}
SpdFactorization::~SpdFactorization() = default;

bool SpdFactorization::factorize(const Eigen::SparseMatrix<double>& a, double shift)
{
  valid_ = false;
  if (!a.isCompressed() || !samePattern(a, impl_->pattern))
  {
    impl_->pattern = a;
    impl_->pattern.makeCompressed();
    impl_->llt.analyzePattern(impl_->pattern);
    ++analyses_;
  }
  impl_->llt.setShift(shift);
  impl_->llt.factorize(a);
  valid_ = impl_->llt.info() == Eigen::Success;
  rows_ = static_cast<int>(a.rows());
  return valid_;
}

Eigen::VectorXd SpdFactorization::solve(const Eigen::VectorXd& b) const
{
  return impl_->llt.solve(b);
}

}  // namespace virtual_origami::core
