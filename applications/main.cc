// sealfe: the command-line entry point; it only dispatches to the sub-commands.
//
// To add a sub-command `foo`: write applications/foo.cc defining `SubCommand foo_command()`
// (declare its parameters, parse them, call the area code, print the headline, write the outputs;
// see applications/stability.cc), declare foo_command() in applications/driver.h and add it to
// the list below. CMake builds every applications/*.cc into the executable.
#include "driver.h"

#include <sealfe/numerics/blas_kernels.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <cstdlib>
#include <string>

namespace
{
/// A run without a launcher (no mpirun/srun environment) is one rank talking to nobody. Open MPI
/// would still open its transports and probe the node for peers, which costs ~0.25 s of a
/// ~0.5 s small run (doc/performance.md). Ask for the shared-memory-free, isolated singleton
/// instead; a setting the user made in the environment or on mpirun's command line wins (setenv
/// does not overwrite), one made in an MCA parameter file does not (the environment overrides
/// those files).
/// Under Open MPI's mpirun with every rank on this node (OMPI_COMM_WORLD_LOCAL_SIZE equal to
/// OMPI_COMM_WORLD_SIZE) the ranks talk through shared memory, by the ob1 layer, which Open MPI
/// picks only after opening the cm layer and its PSM/PSM2 (Omni-Path) transports: ~0.2 s per run
/// (`mpirun -np 2` of a bare MPI_Init program: 0.41-0.49 s, with ob1 asked for 0.22-0.27 s;
/// doc/performance.md "Two ranks, session 10"). Across nodes the choice is left to Open MPI.
void choose_transport()
{
  const char *size = std::getenv("OMPI_COMM_WORLD_SIZE"),
             *local_size = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  if (size != nullptr)
  {
    if (local_size != nullptr && std::string(size) == local_size)
      setenv("OMPI_MCA_pml", "ob1", 0);
    return;
  }
  for (const char *launcher_variable : {"PMIX_RANK", "PMI_RANK", "PMI_SIZE", "SLURM_PROCID"})
    if (std::getenv(launcher_variable) != nullptr)
      return;
  setenv("OMPI_MCA_pml", "ob1", 0);
  setenv("OMPI_MCA_btl", "self", 0);
  setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
}
} // namespace

int main(int argc, char **argv)
{
  // before any BLAS call: the factorisations' dense kernels for this CPU
  sealfe::numerics::use_cpu_blas_kernels();
  choose_transport();
  // Threads: deal.II's rule (no limit given), each rank the node's cores shared by its ranks on
  // the node: one rank of a 2-core machine has two, which the full-film assembly, the multigrid's
  // products and line solves and the CG's products use (doc/performance.md, Session 36); `mpirun
  // -np 2` has one each. DEAL_II_NUM_THREADS in the environment caps it.
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv);
  // the BLAS (MUMPS's dense fronts) on the same threads, not on every core of the node per rank
  sealfe::numerics::use_blas_threads(static_cast<int>(dealii::MultithreadInfo::n_threads()));
  using namespace sealfe::applications;
  return run_command_line(argc, argv,
                          {solve_command(), coefficients_command(), table_command(),
                           stability_command(), response_command(), annular_command(),
                           equilibrium_command(), transient_command()});
}
