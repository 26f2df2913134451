// GoogleTest main for the finite-element tests: MPI (and deal.II's MPI-aware parts) first, and
// the BLAS kernels the application uses (applications/main.cc), on one thread.
#include <sealfe/numerics/blas_kernels.h>

#include <deal.II/base/mpi.h>

#include <gtest/gtest.h>

int main(int argc, char **argv)
{
  sealfe::numerics::use_cpu_blas_kernels();
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  // one thread, the BLAS's too (ctest runs tests side by side; ThreadedKernels raises deal.II's)
  sealfe::numerics::use_blas_threads(1);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
