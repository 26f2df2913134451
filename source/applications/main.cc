// sealfe: command-line entry point (see include/sealfe/application.h).
#include <sealfe/applications/application.h>

#include <deal.II/base/mpi.h>

int main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  return sealfe::run_application(argc, argv);
}
