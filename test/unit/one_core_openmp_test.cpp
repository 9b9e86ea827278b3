// CHOLMOD's OpenMP regions run on the calling thread (src/numerics/one_core_openmp.cpp): the
// region entry CHOLMOD calls is the core library's, a region's body runs once there as thread 0
// of a team of one, and a supernodal factorisation through it solves as before.
#include <dlfcn.h>

#include <cstdlib>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "grid_laplacian.h"
#include "virtual_origami/numerics/spd_factorization.h"

using ::testing::HasSubstr;
using namespace virtual_origami::numerics;

namespace
{
using RegionBody = void (*)(void*);
using Parallel = void (*)(RegionBody, void*, unsigned, unsigned);
using OmpInt = int (*)();

/// What a region's body saw: how often it ran, its thread's number and its team's size.
struct Seen
{
  int calls = 0;
  int thread = -1;
  int team = -1;
};

void recordRegion(void* data)
{
  Seen& seen = *static_cast<Seen*>(data);
  ++seen.calls;
  // libgomp is in the process as CHOLMOD's dependency: its answers, as CHOLMOD's regions ask.
  seen.thread = reinterpret_cast<OmpInt>(dlsym(RTLD_DEFAULT, "omp_get_thread_num"))();
  seen.team = reinterpret_cast<OmpInt>(dlsym(RTLD_DEFAULT, "omp_get_num_threads"))();
}

bool moreThreadsAsked()
{
  const char* asked = std::getenv("OMP_NUM_THREADS");
  return asked && std::atoi(asked) > 1;
}
}  // namespace

TEST(OneCoreOpenMp, CholmodsRegionsEnterTheCoreLibrary)
{
  void* entry = dlsym(RTLD_DEFAULT, "GOMP_parallel");
  ASSERT_NE(entry, nullptr);
  Dl_info where{};
  ASSERT_NE(dladdr(entry, &where), 0);
  EXPECT_THAT(std::string(where.dli_fname), HasSubstr("libvirtual_origami_core"));
}

TEST(OneCoreOpenMp, ARegionRunsOnceAsThreadZeroOfATeamOfOne)
{
  if (moreThreadsAsked())
    GTEST_SKIP() << "OMP_NUM_THREADS asks for more threads: libgomp runs the regions";
  if (!dlsym(RTLD_DEFAULT, "omp_get_thread_num"))
    GTEST_SKIP() << "no OpenMP runtime in the process: this CHOLMOD enters no region";
  Seen seen;
  // As CHOLMOD asks: four threads, no flags.
  reinterpret_cast<Parallel>(dlsym(RTLD_DEFAULT, "GOMP_parallel"))(recordRegion, &seen, 4, 0);
  EXPECT_EQ(seen.calls, 1);
  EXPECT_EQ(seen.thread, 0);
  EXPECT_EQ(seen.team, 1);
}

TEST(OneCoreOpenMp, ASupernodalFactorisationThroughItSolves)
{
  // The 2-D Laplacian of a 70 × 70 grid plus the identity (4,900 rows: nested dissection, large
  // supernodes, every region of CHOLMOD's numeric factorisation), against a known solution.
  const int n = 70 * 70;
  const Eigen::SparseMatrix<double> lower = virtual_origami::test::gridLaplacianLower(70);
  const Eigen::SparseMatrix<double> full = lower.selfadjointView<Eigen::Lower>();
  const Eigen::VectorXd solution = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  SpdFactorization factor;
  ASSERT_TRUE(factor.factorize(lower, 0.0));
  EXPECT_LT((factor.solve(full * solution) - solution).cwiseAbs().maxCoeff(), 1e-12);
  // Refactorised with a shift, as the solvers do every step.
  ASSERT_TRUE(factor.factorize(lower, 1.0));
  const Eigen::SparseMatrix<double> shifted = full + Eigen::SparseMatrix<double>(Eigen::VectorXd::Ones(n).asDiagonal());
  EXPECT_LT((factor.solve(shifted * solution) - solution).cwiseAbs().maxCoeff(), 1e-12);
}
