#include "virtual_origami/curved/kept_factor.h"

#include <mutex>

#include <cholmod.h>

#include "virtual_origami/numerics/spd_factorization.h"

namespace virtual_origami::core
{
namespace
{
/// A CHOLMOD view of an Eigen matrix's lower triangle (no copy).
cholmod_sparse lowerView(const Eigen::SparseMatrix<double>& a)
{
  cholmod_sparse view{};
  view.nrow = static_cast<size_t>(a.rows());
  view.ncol = static_cast<size_t>(a.cols());
  view.nzmax = static_cast<size_t>(a.nonZeros());
  view.p = const_cast<int*>(a.outerIndexPtr());
  view.i = const_cast<int*>(a.innerIndexPtr());
  view.x = const_cast<double*>(a.valuePtr());
  view.stype = -1;
  view.itype = CHOLMOD_INT;
  view.xtype = CHOLMOD_REAL;
  view.dtype = CHOLMOD_DOUBLE;
  view.sorted = 1;
  view.packed = 1;
  return view;
}

bool samePattern(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b)
{
  return a.rows() == b.rows() && a.nonZeros() == b.nonZeros() &&
         std::equal(a.outerIndexPtr(), a.outerIndexPtr() + a.outerSize() + 1, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros(), b.innerIndexPtr());
}
}  // namespace

struct KeptFactor::Impl
{
  // The factorising thread's workspace and the solving threads' (CHOLMOD's common is not
  // shared between threads).
  cholmod_common factor_common{};
  mutable cholmod_common solve_common{};
  mutable std::mutex solve_mutex;  // guards solve_common and the simplicial factor's swap
  cholmod_factor* symbolic = nullptr;
  cholmod_factor* simplicial = nullptr;
  long tag = 0;
  Eigen::SparseMatrix<double> pattern;

  Impl()
  {
    cholmod_start(&factor_common);
    cholmod_start(&solve_common);
    factor_common.print = 0;
    solve_common.print = 0;
    factor_common.supernodal = CHOLMOD_SUPERNODAL;
    // A nested-dissection order: about half the flops of the minimum degree on a sheet.
    factor_common.method[0].ordering = CHOLMOD_METIS;
    factor_common.postorder = 1;
  }
  ~Impl()
  {
    if (symbolic)
      cholmod_free_factor(&symbolic, &factor_common);
    if (simplicial)
      cholmod_free_factor(&simplicial, &solve_common);
    cholmod_finish(&factor_common);
    cholmod_finish(&solve_common);
  }
};

KeptFactor::KeptFactor() : impl_(std::make_unique<Impl>())
{}
KeptFactor::~KeptFactor() = default;

bool KeptFactor::factorize(const Eigen::SparseMatrix<double>& a_in, double shift, long tag)
{
  Impl& m = *impl_;
  Eigen::SparseMatrix<double> a = a_in;
  a.makeCompressed();
  cholmod_sparse view = lowerView(a);
  if (!m.symbolic || !samePattern(a, m.pattern))
  {
    if (m.symbolic)
      cholmod_free_factor(&m.symbolic, &m.factor_common);
    // Nested dissection (METIS) for a large mesh's matrix: a third to half fewer flops than
    // CHOLMOD's own choice on a 10,000-node sheet (as numerics' factorisations choose).
    m.factor_common.nmethods = a.rows() >= 3000 ? 1 : 0;
    m.symbolic = cholmod_analyze(&view, &m.factor_common);
    if (!m.symbolic && m.factor_common.nmethods == 1)
    {
      m.factor_common.nmethods = 0;
      m.symbolic = cholmod_analyze(&view, &m.factor_common);
    }
    if (!m.symbolic)
      return false;
    m.pattern = a;
  }
  // The numeric factor is made in a copy of the analysis, so a failure leaves the last good
  // simplicial factor as it was.
  cholmod_factor* factor = cholmod_copy_factor(m.symbolic, &m.factor_common);
  if (!factor)
    return false;
  double beta[2] = { shift, 0.0 };
  bool positive = false;
  {
    const std::unique_lock<std::mutex> blas = numerics::lockBlas();
    cholmod_factorize_p(&view, beta, nullptr, 0, factor, &m.factor_common);
    positive = m.factor_common.status == CHOLMOD_OK && factor->minor == factor->n;
    // Simplicial LLᵀ: its solves are loops over the columns, no BLAS.
    if (positive)
      positive = cholmod_change_factor(CHOLMOD_REAL, 1, 0, 1, 1, factor, &m.factor_common) != 0;
  }
  if (!positive)
  {
    cholmod_free_factor(&factor, &m.factor_common);
    return false;
  }
  const std::lock_guard<std::mutex> lock(m.solve_mutex);
  if (m.simplicial)
    cholmod_free_factor(&m.simplicial, &m.solve_common);
  m.simplicial = factor;  // same allocator (malloc) for either common
  m.tag = tag;
  return true;
}

Eigen::VectorXd KeptFactor::solve(const Eigen::VectorXd& b, long* tag) const
{
  Impl& m = *impl_;
  const std::lock_guard<std::mutex> lock(m.solve_mutex);
  if (tag)
    *tag = m.tag;
  if (!m.simplicial || static_cast<Eigen::Index>(m.simplicial->n) != b.size())
    return Eigen::VectorXd();
  cholmod_dense rhs{};
  rhs.nrow = static_cast<size_t>(b.size());
  rhs.ncol = 1;
  rhs.nzmax = rhs.nrow;
  rhs.d = rhs.nrow;
  rhs.x = const_cast<double*>(b.data());
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, m.simplicial, &rhs, &m.solve_common);
  if (!x)
    return Eigen::VectorXd();
  Eigen::VectorXd out = Eigen::Map<Eigen::VectorXd>(static_cast<double*>(x->x), b.size());
  cholmod_free_dense(&x, &m.solve_common);
  return out;
}

long KeptFactor::tag() const
{
  const std::lock_guard<std::mutex> lock(impl_->solve_mutex);
  return impl_->tag;
}

bool KeptFactor::valid() const
{
  const std::lock_guard<std::mutex> lock(impl_->solve_mutex);
  return impl_->simplicial != nullptr;
}

int KeptFactor::rows() const
{
  const std::lock_guard<std::mutex> lock(impl_->solve_mutex);
  return impl_->simplicial ? static_cast<int>(impl_->simplicial->n) : 0;
}

}  // namespace virtual_origami::core
