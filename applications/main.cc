// sealfe: the command-line entry point; it only dispatches to the sub-commands.
//
// To add a sub-command `foo`: write applications/foo.cc defining `SubCommand foo_command()`
// (declare its parameters, parse them, call the area code, print the headline, write the outputs;
// see applications/stability.cc), declare foo_command() in applications/driver.h and add it to
// the list below. CMake builds every applications/*.cc into the executable.
#include "driver.h"

#include <deal.II/base/mpi.h>

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  using namespace sealfe::applications;
  return run_command_line(argc, argv,
                          {solve_command(), coefficients_command(), table_command(),
                           stability_command(), response_command(), annular_command(),
                           equilibrium_command(), transient_command()});
}
