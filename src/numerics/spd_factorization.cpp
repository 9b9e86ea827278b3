#include "virtual_origami/numerics/spd_factorization.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <mutex>

#include <Eigen/CholmodSupport>

#include "nested_dissection.h"
#include "one_core_openmp.h"

namespace virtual_origami::numerics
{
namespace
{
/// Eigen's supernodal LLᵀ with its symbolic factor reachable, so that it can be copied out and in.
class SupernodalLLT : public Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower>
{
public:
  /// The symbolic factor right after analyzePattern (before any numeric factorisation).
  const cholmod_factor* factor() const { return m_cholmodFactor; }
  /// Takes a copy of another analysis of the same pattern in place of analyzePattern.
  bool adopt(const cholmod_factor* symbolic)
  {
    if (m_cholmodFactor)
      cholmod_free_factor(&m_cholmodFactor, &cholmod());
    m_cholmodFactor = cholmod_copy_factor(const_cast<cholmod_factor*>(symbolic), &cholmod());
    m_isInitialized = m_cholmodFactor != nullptr;
    m_info = m_cholmodFactor ? Eigen::Success : Eigen::NumericalIssue;
    m_analysisIsOk = m_cholmodFactor != nullptr;
    m_factorizationIsOk = false;
    return m_analysisIsOk;
  }
};
}  // namespace

class SpdFactorization::SharedAnalysis
{
public:
  SharedAnalysis() { cholmod_start(&common_); }
  ~SharedAnalysis()
  {
    if (symbolic_)
      cholmod_free_factor(&symbolic_, &common_);
    cholmod_finish(&common_);
  }
  SharedAnalysis(const SharedAnalysis&) = delete;
  SharedAnalysis& operator=(const SharedAnalysis&) = delete;

  std::mutex mutex;
  Eigen::SparseMatrix<double> pattern;

  const cholmod_factor* symbolic() const { return symbolic_; }
  void keep(const Eigen::SparseMatrix<double>& analysed, const cholmod_factor* symbolic)
  {
    if (symbolic_)
      cholmod_free_factor(&symbolic_, &common_);
    symbolic_ = cholmod_copy_factor(const_cast<cholmod_factor*>(symbolic), &common_);
    pattern = symbolic_ ? analysed : Eigen::SparseMatrix<double>();
  }

private:
  cholmod_common common_;
  cholmod_factor* symbolic_ = nullptr;
};

bool factorisationsOnOneCore()
{
  const char* asked = std::getenv("OMP_NUM_THREADS");
  return !(asked && std::atoi(asked) > 1);
}

namespace
{
using SetInt = void (*)(int);

/// Debian's CHOLMOD runs parts of its supernodal factorisation on four OpenMP threads whatever
/// the cores (its num_threads clause ignores OMP_NUM_THREADS). On the 2 cores the nodes and rviz
/// share, they spun and switched: a 1,681-vertex Miura-ori's turn preview spent 45 % of its CPU
/// time in libgomp and the kernel's futexes, and took half the CPU time on one thread. So the
/// threads that factorise keep to one core (no nested OpenMP level), unless OMP_NUM_THREADS asks
/// for more. Per thread (OpenMP's settings are), once; looked up in the process, where CHOLMOD
/// loaded libgomp (absent: a CHOLMOD without OpenMP, nothing to do). Where this library's
/// GOMP_parallel is the one CHOLMOD calls (one_core_openmp.cpp), its regions skip libgomp
/// altogether; this covers a process where it is not.
void keepFactorisationsOnOneCore()
{
  thread_local bool done = false;
  if (done)
    return;
  done = true;
  if (!factorisationsOnOneCore())
    return;
  static const auto set_max_active_levels = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
  static const auto set_num_threads = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_num_threads"));
  if (set_max_active_levels)
    set_max_active_levels(0);
  if (set_num_threads)
    set_num_threads(1);
}
}  // namespace

std::unique_lock<std::mutex> lockBlas()
{
  static std::mutex blas;
  keepFactorisationsOnOneCore();
  return std::unique_lock<std::mutex>(blas);
}

std::shared_ptr<SpdFactorization::SharedAnalysis> SpdFactorization::makeSharedAnalysis()
{
  return std::make_shared<SharedAnalysis>();
}

struct SpdFactorization::Impl
{
  SupernodalLLT llt;
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
    std::unique_lock<std::mutex> shared_lock;
    if (shared_)
    {
      shared_lock = std::unique_lock<std::mutex>(shared_->mutex);
      if (shared_->symbolic() && samePattern(impl_->pattern, shared_->pattern) &&
          impl_->llt.adopt(shared_->symbolic()))
      {
        shared_lock.unlock();
        return finishFactorize(a, shift);
      }
    }
    analyzeWithNestedDissection(impl_->llt, impl_->pattern);
    ++analyses_;
    if (shared_ && impl_->llt.info() == Eigen::Success)
      shared_->keep(impl_->pattern, impl_->llt.factor());
  }
  return finishFactorize(a, shift);
}

bool SpdFactorization::finishFactorize(const Eigen::SparseMatrix<double>& a, double shift)
{
  impl_->llt.setShift(shift);
  const std::unique_lock<std::mutex> blas = lockBlas();
  impl_->llt.factorize(a);
  valid_ = impl_->llt.info() == Eigen::Success;
  rows_ = static_cast<int>(a.rows());
  return valid_;
}

Eigen::VectorXd SpdFactorization::solve(const Eigen::VectorXd& b) const
{
  const std::unique_lock<std::mutex> blas = lockBlas();
  return impl_->llt.solve(b);
}

}  // namespace virtual_origami::numerics
