// The core library names OpenBLAS's kernels by the CPU's instruction sets when it loads
// (src/numerics/blas_kernels.cpp): Debian's OpenBLAS falls back to SSE3 on CPUs newer than it.
#include <cctype>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "grid_laplacian.h"
#include "virtual_origami/numerics/blas_kernels.h"
#include "virtual_origami/numerics/spd_factorization.h"

using namespace virtual_origami::numerics;

namespace
{
std::string lowerCase(std::string s)
{
  for (char& c : s)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
}  // namespace

TEST(BlasKernels, FactorisationsRunOnTheKernelsForTheCpu)
{
  // A factorisation with supernodes (each a BLAS call): the 2-D Laplacian of a 40 × 40 grid
  // plus the identity, solved against a known solution.
  const int n = 40 * 40;
  const Eigen::SparseMatrix<double> lower = virtual_origami::test::gridLaplacianLower(40);
  const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  const Eigen::VectorXd solution = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  SpdFactorization factor;
  ASSERT_TRUE(factor.factorize(lower, 0.0));
  EXPECT_LT((factor.solve(full * solution) - solution).cwiseAbs().maxCoeff(), 1e-12);

  const std::string running = blasKernels();
  if (running.empty())
    GTEST_SKIP() << "the BLAS in this process is not OpenBLAS (scripts/install_deps.sh installs libopenblas0-serial)";
  // Named by the caller, that choice; otherwise never the SSE3 fallback where the CPU has more.
  if (const char* named = std::getenv("OPENBLAS_CORETYPE"))
  {
    EXPECT_EQ(lowerCase(running), lowerCase(named));
  }
  if (!blasKernelsForThisCpu().empty())
  {
    EXPECT_NE(running, "Prescott") << "OpenBLAS runs its SSE3 kernels on a CPU with " << blasKernelsForThisCpu()
                                   << "'s instruction sets";
  }
}
