// TableSweep: `sealfe table` — finite-element coefficients and loads over a grid of operating
// points, shared across MPI ranks, written as a CSV coefficient table (coefficient_table.h).
#pragma once

#include <sealfe/coefficients/coefficient_table.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/operating_conditions.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sealfe
{
/// The operating points of a sweep: the tensor-product grid of the swept quantities about a base
/// point, and `n_check` held-out points at the centres of grid cells spread over the grid (used
/// only to report the interpolation error of the table).
struct SweepPlan
{
  struct Axis
  {
    std::string name; // OperatingPoint column name
    std::vector<double> values;
  };
  std::vector<Axis> axes;
  std::vector<OperatingPoint> points; // grid points first (last axis fastest), then checks
  unsigned int n_grid = 0;

  static SweepPlan make(const OperatingPoint &base, const std::vector<Axis> &axes,
                        unsigned int n_check);
  bool is_check(const unsigned int i) const { return i >= n_grid; }
};

/// `sealfe table [sweep.prm]`: prm subsection "Table" (the swept quantities, the output file,
/// held-out points) on top of Geometry, Operating conditions (the base point) and the
/// coefficient solver's subsections. Every rank solves its share of the points with
/// MPI_COMM_SELF; rank 0 gathers the rows and writes the CSV. A failing point gets status
/// "failed: <why>" in its row and a line on stderr; the rest of the table is kept. SIGINT/SIGTERM
/// stop the sweep after the current round of points (all ranks together): the finished rows are
/// published with summary.json "complete": false, and `Resume = true` computes only the rest
/// (table_resume.h).
namespace table
{
void declare_parameters(dealii::ParameterHandler &prm);
nlohmann::json run(dealii::ParameterHandler &prm, const std::string &output_directory,
                   MPI_Comm comm);
} // namespace table

} // namespace sealfe
