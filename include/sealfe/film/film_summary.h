// The report of one finite-element film solve (`sealfe solve`): loads, discretisation, the
// cavitation and roughness models as used, and the discretisation error of the loads.
#pragma once

#include <sealfe/film/film_loads.h>
#include <sealfe/film/film_settings.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/mpi.h>

#include <nlohmann/json.hpp>

namespace sealfe
{
/// summary.json content of the solve `solver` (of `settings`) that gave `loads`: the loads, dofs,
/// degree, iterations, the discrete mass balance, "cavitation", "roughness", and
/// "error_estimate": the loads' difference to a solve of the same settings on a mesh twice as
/// coarse / (2^k - 1) (estimate_load_errors), if the solver's Error estimate is on and the mesh
/// can be coarsened. "stage_wall_time" holds the solver's stage times and the estimate's.
nlohmann::json finite_element_solve_summary(const FilmSettings &settings,
                                            const ReynoldsSolver &solver, const FilmLoads &loads,
                                            MPI_Comm comm);
} // namespace sealfe
