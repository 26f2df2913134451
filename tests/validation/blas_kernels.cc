// The BLAS kernels the direct solver's dense fronts run in: the CPU's vector kernels where it has
// them (numerics::use_cpu_blas_kernels, called by the test main as by the application), and
// products within the standard rounding-error bound with them.
#include <sealfe/numerics/blas_kernels.h>

#include <gtest/gtest.h>

#include <sched.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

extern "C" void dgemm_(const char *transa, const char *transb, const int *m, const int *n,
                       const int *k, const double *alpha, const double *a, const int *lda,
                       const double *b, const int *ldb, const double *beta, double *c,
                       const int *ldc);

namespace
{
using sealfe::numerics::blas_kernels;

TEST(BlasKernels, VectorKernelsWhereTheCpuHasThem)
{
  const auto blas = blas_kernels();
  if (blas.kernels.empty())
    GTEST_SKIP() << "the BLAS is not an OpenBLAS that chooses its kernels at run time";
  if (std::getenv("OPENBLAS_CORETYPE"))
    GTEST_SKIP() << "OPENBLAS_CORETYPE is set: the user's choice stands";
  __builtin_cpu_init();
  if (!(__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")))
    GTEST_SKIP() << "this CPU has neither AVX2 nor AVX-512";
  // OpenBLAS's generic fallback (SSE3) is what use_cpu_blas_kernels replaces
  EXPECT_STRCASENE(blas.kernels.c_str(), "Prescott") << "chosen by " << blas.chosen_by;
  EXPECT_TRUE(blas.chosen_by == "OpenBLAS" || blas.chosen_by == "sealfe") << blas.chosen_by;
}

TEST(BlasKernels, ThreadsAreTheOnesGiven)
{
  // use_blas_threads caps OpenBLAS at the rank's threads (applications/main.cc; one here, the test
  // main's) and at OpenBLAS's own count; a single-threaded OpenBLAS stays at one
  if (blas_kernels().threads == 0)
    GTEST_SKIP() << "the BLAS is not an OpenBLAS";
  EXPECT_EQ(blas_kernels().threads, 1); // the test main's
  const int two = sealfe::numerics::use_blas_threads(2);
  EXPECT_TRUE(two == 1 || two == 2) << two;
  EXPECT_EQ(blas_kernels().threads, two);
  // never more than OpenBLAS's own count, at most the cores this process may run on (OpenBLAS
  // alone would take up to its compiled limit, 64 or more)
  cpu_set_t allowed;
  ASSERT_EQ(sched_getaffinity(0, sizeof(allowed), &allowed), 0);
  const int many = sealfe::numerics::use_blas_threads(1000);
  EXPECT_GE(many, 1);
  EXPECT_LE(many, CPU_COUNT(&allowed));
  EXPECT_EQ(sealfe::numerics::use_blas_threads(1), 1);
  EXPECT_EQ(sealfe::numerics::use_blas_threads(0), 1); // not a count: nothing changes
}

TEST(BlasKernels, CalledAgainChangesNothing)
{
  const auto before = blas_kernels();
  const auto again = sealfe::numerics::use_cpu_blas_kernels();
  EXPECT_EQ(again.kernels, before.kernels);
  EXPECT_EQ(again.chosen_by, before.chosen_by);
}

// C = A B in floating point satisfies |C - fl(C)| <= gamma_n |A| |B| entry by entry,
// gamma_n = n u / (1 - n u) (Higham, Accuracy and Stability of Numerical Algorithms, 2002,
// Eq. 3.13), whatever the order of the sums a blocked kernel takes. Checked against products
// summed in long double (64-bit mantissa: its own error is below 2^-11 of the bound).
TEST(BlasKernels, MatrixProductWithinTheRoundingErrorBound)
{
  const int m = 67, n = 131, k = 257; // not multiples of any kernel's blocking
  std::mt19937 random(2002);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<double> A(m * k), B(k * n), C(m * n, 0.0);
  for (double &a : A)
    a = value(random);
  for (double &b : B)
    b = value(random);
  const double one = 1.0, zero = 0.0;
  dgemm_("N", "N", &m, &n, &k, &one, A.data(), &m, B.data(), &k, &zero, C.data(), &m);
  const double u = std::ldexp(1.0, -53);
  const double gamma = k * u / (1 - k * u);
  double worst = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < m; ++i)
    {
      long double exact = 0, magnitude = 0;
      for (int l = 0; l < k; ++l)
      {
        exact += static_cast<long double>(A[i + l * m]) * B[l + j * k];
        magnitude += std::fabs(A[i + l * m] * B[l + j * k]);
      }
      const double error = std::fabs(static_cast<double>(exact - C[i + j * m]));
      worst = std::max(worst, error / (gamma * static_cast<double>(magnitude)));
    }
  EXPECT_LE(worst, 1.0) << "kernels " << blas_kernels().kernels;
  std::cout << "largest error / bound " << worst << " (kernels " << blas_kernels().kernels << ", "
            << blas_kernels().chosen_by << ")\n";
}
} // namespace
