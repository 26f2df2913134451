// Application: the `sealfe <sub-command> [file.prm]` front end — argument parsing, parameter
// files, dispatch to the sub-commands, summary.json, and one-line errors with a non-zero exit.
#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <nlohmann/json.hpp>

#include <string>

namespace sealfe
{
/// Run the command line; returns the process exit status. MPI must be initialised.
int run_application(int argc, char **argv);

namespace solve
{
/// `sealfe solve`: pressure field, loads, leakage of one operating point (finite element or
/// narrow-seal model), with an error estimate for the FE loads.
void declare_parameters(dealii::ParameterHandler &prm);
nlohmann::json run(dealii::ParameterHandler &prm, const std::string &output_directory,
                   MPI_Comm comm);
} // namespace solve
} // namespace sealfe
