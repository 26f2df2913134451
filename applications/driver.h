// The `sealfe <sub-command> [file.prm]` driver shared by the front ends in applications/: the
// sub-command record, argument handling, parameter files, --print-parameters, summary.json and
// one-line errors with a non-zero exit status.
#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

namespace sealfe::applications
{
/// One sub-command: its parameters and what it does.
struct SubCommand
{
  std::string name;
  std::string purpose; ///< one line for --help
  /// Whether the shared Geometry / Operating conditions subsections are declared (face seals).
  bool face_seal = true;
  /// Whether run() is called on every MPI rank (finite-element solves) or on rank 0 only.
  bool distributed = false;
  /// Declares the sub-command's own subsections (the driver declares Output directory and, for
  /// face seals, Geometry and Operating conditions).
  std::function<void(dealii::ParameterHandler &)> declare;
  /// Parses, computes, prints the headline (rank 0), writes the output files into the directory
  /// (output::make_directory, once the input is checked) and returns the summary. The driver
  /// adds sub_command, version, git_revision, mpi_ranks and wall_time and writes summary.json and
  /// used_parameters.prm.
  std::function<nlohmann::json(dealii::ParameterHandler &, const std::string &output_directory,
                               MPI_Comm)>
      run;
};

/// The sub-commands, one per file applications/<name>.cc.
SubCommand solve_command();
SubCommand coefficients_command();
SubCommand table_command();
SubCommand stability_command();
SubCommand response_command();
SubCommand annular_command();
SubCommand equilibrium_command();
SubCommand transient_command();

/// Runs the command line against `commands`; returns the process exit status (0, 1 on an error
/// reported on one stderr line, 2 for a missing sub-command). MPI must be initialised.
int run_command_line(int argc, char **argv, const std::vector<SubCommand> &commands);

/// deal.II exceptions carry a multi-line report; this is its "additional information" (or what())
/// on one line.
std::string one_line(const std::exception &e);

} // namespace sealfe::applications
