#include <sealfe/numerics/blas_kernels.h>

#include <dlfcn.h>
#include <strings.h>

#include <algorithm>
#include <cstdlib>

namespace sealfe::numerics
{
namespace
{
using NameFunction = char *(*)();
using VoidFunction = void (*)();
using GetThreadsFunction = int (*)();
using SetThreadsFunction = void (*)(int);

/// OpenBLAS's thread count, looked up in the loaded libraries like its kernel selection (a
/// single-threaded OpenBLAS has both functions and always runs on one thread).
int openblas_threads()
{
  const auto get =
      reinterpret_cast<GetThreadsFunction>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  return get ? get() : 0;
}

/// OpenBLAS's run-time kernel selection, looked up in the loaded libraries: a BLAS without it
/// (reference BLAS, BLIS, MKL, an OpenBLAS built for one CPU) is left alone.
struct OpenBlasDynamicArch
{
  NameFunction corename =
      reinterpret_cast<NameFunction>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
  // gotoblas_dynamic_init() reads OPENBLAS_CORETYPE and fills the kernel table unless it is set
  // already; gotoblas_dynamic_quit() unsets it. Both are exported by DYNAMIC_ARCH builds.
  VoidFunction init = reinterpret_cast<VoidFunction>(dlsym(RTLD_DEFAULT, "gotoblas_dynamic_init"));
  VoidFunction quit = reinterpret_cast<VoidFunction>(dlsym(RTLD_DEFAULT, "gotoblas_dynamic_quit"));
  bool available() const { return corename && init && quit; }
};

/// The best kernel set OpenBLAS 0.3.21 has for the CPU's features, or nullptr.
const char *kernels_for_this_cpu()
{
  __builtin_cpu_init();
  // OpenBLAS's SkylakeX kernels use AVX-512 F, CD, BW, DQ and VL; Haswell's AVX2 and FMA.
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
      __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl"))
    return "SkylakeX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
    return "Haswell";
  return nullptr;
}

BlasKernels found(const OpenBlasDynamicArch &openblas)
{
  if (!openblas.available())
    return {};
  return {openblas.corename(), std::getenv("OPENBLAS_CORETYPE") ? "OPENBLAS_CORETYPE" : "OpenBLAS"};
}

BlasKernels state;
bool decided = false;
} // namespace

BlasKernels use_cpu_blas_kernels()
{
  if (decided)
    return state;
  decided = true;
  const OpenBlasDynamicArch openblas;
  state = found(openblas);
  const char *better = kernels_for_this_cpu();
  if (state.chosen_by != "OpenBLAS" || strcasecmp(state.kernels.c_str(), "Prescott") != 0 ||
      !better)
    return state;
  // In-process what OPENBLAS_CORETYPE does at load time; the environment is left as it was (the
  // variable would otherwise reach child processes such as the plotting scripts).
  setenv("OPENBLAS_CORETYPE", better, 1);
  openblas.quit();
  openblas.init();
  unsetenv("OPENBLAS_CORETYPE");
  state = {openblas.corename(), "sealfe"};
  return state;
}

BlasKernels blas_kernels()
{
  BlasKernels now = decided ? state : found(OpenBlasDynamicArch());
  now.threads = openblas_threads(); // (use_blas_threads may have changed it since)
  return now;
}

int use_blas_threads(const int threads)
{
  const auto set =
      reinterpret_cast<SetThreadsFunction>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  // OpenBLAS's own count before the first call: OPENBLAS_NUM_THREADS (or OMP_NUM_THREADS) where
  // set, else the cores this process may run on (a launcher's binding). deal.II's count ignores
  // the binding, so it is only a cap: never more threads than OpenBLAS would take by itself.
  static const int own_count = openblas_threads();
  if (set && threads >= 1 && own_count >= 1)
    set(std::min(threads, own_count));
  return openblas_threads();
}
} // namespace sealfe::numerics
