#include "virtual_origami/curved/kept_factor.h"

#include <algorithm>
#include <memory>
#include <mutex>
#include <vector>

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

/// A copy of CHOLMOD's supernodal LLᵀ of P·A·Pᵀ and its back-substitutions, supernode by
/// supernode with Eigen's dense kernels: no BLAS (whose serial build shares its buffers
/// between threads) and one row index per row of a supernode, not per entry as the
/// simplicial form reads.
struct SupernodalFactor
{
  /// Frees an array taken from a CHOLMOD factor, as CHOLMOD would.
  struct FreeWithCholmod
  {
    void operator()(void* p) const
    {
      SuiteSparse_free(p);
    }
  };
  Eigen::Index n = 0;
  std::vector<int> perm;   // row k of the factor is row perm[k] of A
  std::vector<int> super;  // supernode s: columns super[s] to super[s + 1] − 1
  std::vector<int> pi;     // its rows: row_index[pi[s]] to row_index[pi[s + 1] − 1]
  std::vector<long> px;    // its dense block (rows × columns, by columns) from values[px[s]]
  // The two large arrays are taken from the factor, not copied (at 10,000 vertices 7 million
  // entries: a copy was a tenth of a factorisation, in the memory the frames' solves read).
  std::unique_ptr<int, FreeWithCholmod> row_index;
  std::unique_ptr<double, FreeWithCholmod> values;
  Eigen::Index widest = 0;  // the most rows below a supernode's diagonal block

  /// Takes `f`'s values and row indices (left null in it: cholmod_free_factor skips them).
  explicit SupernodalFactor(cholmod_factor& f)
    : n(static_cast<Eigen::Index>(f.n))
    , perm(static_cast<const int*>(f.Perm), static_cast<const int*>(f.Perm) + f.n)
    , super(static_cast<const int*>(f.super), static_cast<const int*>(f.super) + f.nsuper + 1)
    , pi(static_cast<const int*>(f.pi), static_cast<const int*>(f.pi) + f.nsuper + 1)
    , px(static_cast<const int*>(f.px), static_cast<const int*>(f.px) + f.nsuper + 1)
    , row_index(static_cast<int*>(f.s))
    , values(static_cast<double*>(f.x))
  {
    f.s = nullptr;
    f.x = nullptr;
    for (size_t s = 0; s + 1 < super.size(); ++s)
      widest = std::max<Eigen::Index>(widest, (pi[s + 1] - pi[s]) - (super[s + 1] - super[s]));
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& b) const
  {
    using Block = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
    Eigen::VectorXd y(n), below(widest);
    for (Eigen::Index k = 0; k < n; ++k)
      y[k] = b[perm[k]];
    const int supernodes = static_cast<int>(super.size()) - 1;
    const auto block = [&](int s, Eigen::Index& columns, Eigen::Index& rows_below, const int*& rows) {
      columns = super[s + 1] - super[s];
      const Eigen::Index rows_all = pi[s + 1] - pi[s];
      rows_below = rows_all - columns;
      rows = row_index.get() + pi[s] + columns;
      return Block(values.get() + px[s], rows_all, columns, Eigen::OuterStride<>(rows_all));
    };
    // L z = P b: each supernode's diagonal block, then its rows below pushed onward.
    for (int s = 0; s < supernodes; ++s)
    {
      Eigen::Index columns = 0, rows_below = 0;
      const int* rows = nullptr;
      const Block l = block(s, columns, rows_below, rows);
      auto part = y.segment(super[s], columns);
      l.topRows(columns).triangularView<Eigen::Lower>().solveInPlace(part);
      if (rows_below == 0)
        continue;
      below.head(rows_below).noalias() = l.bottomRows(rows_below) * part;
      for (Eigen::Index i = 0; i < rows_below; ++i)
        y[rows[i]] -= below[i];
    }
    // Lᵀ w = z, the supernodes in reverse.
    for (int s = supernodes - 1; s >= 0; --s)
    {
      Eigen::Index columns = 0, rows_below = 0;
      const int* rows = nullptr;
      const Block l = block(s, columns, rows_below, rows);
      auto part = y.segment(super[s], columns);
      if (rows_below > 0)
      {
        for (Eigen::Index i = 0; i < rows_below; ++i)
          below[i] = y[rows[i]];
        part.noalias() -= l.bottomRows(rows_below).transpose() * below.head(rows_below);
      }
      l.topRows(columns).triangularView<Eigen::Lower>().transpose().solveInPlace(part);
    }
    Eigen::VectorXd x(n);
    for (Eigen::Index k = 0; k < n; ++k)
      x[perm[k]] = y[k];
    return x;
  }
};
}  // namespace

struct KeptFactor::Impl
{
  // The factorising thread's workspace (the solves call no CHOLMOD).
  cholmod_common factor_common{};
  mutable std::mutex solve_mutex;  // guards the kept factor's swap and its tag
  cholmod_factor* symbolic = nullptr;
  std::shared_ptr<const SupernodalFactor> kept;
  long tag = 0;
  Eigen::SparseMatrix<double> pattern;

  Impl()
  {
    cholmod_start(&factor_common);
    factor_common.print = 0;
    factor_common.supernodal = CHOLMOD_SUPERNODAL;
    // A nested-dissection order: about half the flops of the minimum degree on a sheet.
    factor_common.method[0].ordering = CHOLMOD_METIS;
    factor_common.postorder = 1;
  }
  ~Impl()
  {
    if (symbolic)
      cholmod_free_factor(&symbolic, &factor_common);
    cholmod_finish(&factor_common);
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
  // factor as it was.
  cholmod_factor* factor = cholmod_copy_factor(m.symbolic, &m.factor_common);
  if (!factor)
    return false;
  double beta[2] = { shift, 0.0 };
  bool positive = false;
  {
    const std::unique_lock<std::mutex> blas = numerics::lockBlas();
    cholmod_factorize_p(&view, beta, nullptr, 0, factor, &m.factor_common);
    positive = m.factor_common.status == CHOLMOD_OK && factor->minor == factor->n && factor->is_super;
  }
  std::shared_ptr<const SupernodalFactor> made;
  if (positive)
    made = std::make_shared<const SupernodalFactor>(*factor);
  cholmod_free_factor(&factor, &m.factor_common);
  if (!made)
    return false;
  const std::lock_guard<std::mutex> lock(m.solve_mutex);
  m.kept = std::move(made);  // a solve under way keeps the one it began with
  m.tag = tag;
  return true;
}

Eigen::VectorXd KeptFactor::solve(const Eigen::VectorXd& b, long* tag) const
{
  std::shared_ptr<const SupernodalFactor> factor;
  {
    const std::lock_guard<std::mutex> lock(impl_->solve_mutex);
    if (tag)
      *tag = impl_->tag;
    factor = impl_->kept;
  }
  if (!factor || factor->n != b.size())
    return Eigen::VectorXd();
  return factor->solve(b);
}

long KeptFactor::tag() const
{
  const std::lock_guard<std::mutex> lock(impl_->solve_mutex);
  return impl_->tag;
}

bool KeptFactor::valid() const
{
  const std::lock_guard<std::mutex> lock(impl_->solve_mutex);
  return impl_->kept != nullptr;
}

int KeptFactor::rows() const
{
  const std::lock_guard<std::mutex> lock(impl_->solve_mutex);
  return impl_->kept ? static_cast<int>(impl_->kept->n) : 0;
}

}  // namespace virtual_origami::core
