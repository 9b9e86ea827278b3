// The BLAS kernels behind every supernodal factorisation (CHOLMOD calls Debian's OpenBLAS).
// OpenBLAS chooses its kernels by the CPU's model number when it loads, and Debian 12's
// (0.3.21) does not know the models that came after it: on them it falls back to its SSE3
// kernels ("Prescott"), and a factorisation takes about half as long again. When the core
// library loads, it names the kernels by the CPU's instruction sets instead (AVX-512:
// "SkylakeX", AVX2 with FMA: "Haswell"), before any BLAS call, unless OPENBLAS_CORETYPE was set
// or OpenBLAS knew the CPU.
#pragma once

#include <string>

namespace virtual_origami::numerics
{
/// The kernels OpenBLAS runs ("SkylakeX", "Haswell", "Prescott", …); empty where the BLAS in
/// the process is not OpenBLAS.
std::string blasKernels();

/// The kernels this CPU's instruction sets call for; empty where OpenBLAS's own choice stands.
std::string blasKernelsForThisCpu();
}  // namespace virtual_origami::numerics
