// The dense kernels behind the sparse direct solver (MUMPS's frontal matrices run in BLAS-3):
// makes OpenBLAS use the vector instructions of the CPU it runs on when it does not recognise
// that CPU and falls back to its generic SSE3 ("Prescott") kernels.
#pragma once

#include <string>

namespace sealfe::numerics
{
/// What the process's BLAS runs on, after use_cpu_blas_kernels().
struct BlasKernels
{
  /// OpenBLAS's kernel set ("SkylakeX", "Haswell", ...); empty when the BLAS is not an OpenBLAS
  /// that chooses its kernels at run time (then nothing was changed).
  std::string kernels;
  /// Who chose them: "OpenBLAS" (its own CPU detection), "OPENBLAS_CORETYPE" (the user's
  /// environment) or "sealfe" (OpenBLAS fell back to Prescott on a CPU with AVX2 or AVX-512).
  std::string chosen_by;
  /// Threads OpenBLAS may run a call on (small calls take one; 1 for a single-threaded build;
  /// 0 when unknown: not an OpenBLAS).
  int threads = 0;
};

/// OpenBLAS built with DYNAMIC_ARCH (Debian's) picks its kernels from the CPU model when it is
/// loaded. A model newer than the release (OpenBLAS 0.3.21 in Debian 12 on Intel family 6 model
/// 207) gets the SSE3 fallback, which made MUMPS's factorisations of the JFO Newton systems
/// 1.15-1.9x slower there (doc/performance.md "BLAS kernels"). If the user has not set
/// OPENBLAS_CORETYPE and OpenBLAS took that fallback on a CPU whose features allow AVX-512 or
/// AVX2 kernels (__builtin_cpu_supports, which also checks that the OS saves those registers),
/// re-initialise OpenBLAS's kernel table with those (the documented OPENBLAS_CORETYPE choice, made
/// in-process). Call first in main(), before any BLAS call and before other threads start; calling
/// it again changes nothing.
BlasKernels use_cpu_blas_kernels();

/// The state after the last use_cpu_blas_kernels() (what it found if it was never called).
BlasKernels blas_kernels();

/// Caps a multithreaded OpenBLAS (Debian's libopenblas0-pthread) at `threads` threads a call,
/// the threads deal.II gives this rank (MultithreadInfo::n_threads(): the node's cores shared by
/// its ranks), never above OpenBLAS's own count (OPENBLAS_NUM_THREADS where set, else the cores
/// the process may run on): ranks on one node that no launcher binds then do not take every core
/// each. MUMPS's dense fronts run in it: on two threads the JFO's factorisations of 1e6 unknowns
/// take ~0.5 s less (doc/performance.md, Session 37). Nothing changes with a single-threaded or
/// another BLAS. Returns the threads OpenBLAS may now use (0: not an OpenBLAS).
int use_blas_threads(int threads);
} // namespace sealfe::numerics
