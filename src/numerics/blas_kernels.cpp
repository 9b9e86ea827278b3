#include "virtual_origami/numerics/blas_kernels.h"

#include <dlfcn.h>

#include <cstdlib>

namespace virtual_origami::numerics
{
namespace
{
using CoreName = char* (*)();
using DynamicInit = void (*)();

/// OpenBLAS's own entry points, looked up in the process (absent: another BLAS).
template <typename Function>
Function openBlas(const char* name)
{
  return reinterpret_cast<Function>(dlsym(RTLD_DEFAULT, name));
}

/// Runs when the core library loads: after OpenBLAS's own start-up (a library it depends on
/// through CHOLMOD), before anything can call it. OpenBLAS built for many CPUs (Debian's is)
/// chooses again when its choice is dropped, by OPENBLAS_CORETYPE where that is set.
__attribute__((constructor)) void chooseBlasKernels()
{
  if (std::getenv("OPENBLAS_CORETYPE"))
    return;  // the user's choice, which OpenBLAS has followed
  const auto core_name = openBlas<CoreName>("openblas_get_corename");
  const auto quit = openBlas<DynamicInit>("gotoblas_dynamic_quit");
  const auto init = openBlas<DynamicInit>("gotoblas_dynamic_init");
  const std::string wanted = blasKernelsForThisCpu();
  // Only where OpenBLAS fell back to its oldest x86-64 kernels: a CPU it knows keeps its choice.
  if (!core_name || !quit || !init || wanted.empty() || std::string(core_name()) != "Prescott")
    return;
  setenv("OPENBLAS_CORETYPE", wanted.c_str(), 0);
  quit();
  init();
}
}  // namespace

std::string blasKernels()
{
  const auto core_name = openBlas<CoreName>("openblas_get_corename");
  return core_name ? std::string(core_name()) : std::string();
}

std::string blasKernelsForThisCpu()
{
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    return "Haswell";
  return "";
}

}  // namespace virtual_origami::numerics
