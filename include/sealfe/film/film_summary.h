// The report of one finite-element film solve (`sealfe solve`): loads, discretisation, the
// cavitation and roughness models as used, and the discretisation error of the loads.
#pragma once

#include <sealfe/film/film_loads.h>
#include <sealfe/film/film_settings.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/mpi.h>

#include <nlohmann/json.hpp>

#include <string>

namespace sealfe
{
/// summary.json content of the solve `solver` (of `settings`) that gave `loads`: the loads, dofs,
/// degree, iterations, the discrete mass balance, the nodal minimum pressure and the
/// interpolation undershoot below p_cav (with pressure_undershoot_warning), "cavitation",
/// "roughness", and
/// "error_estimate": the loads' difference to a solve of the same settings on a mesh twice as
/// coarse / (2^k - 1) (estimate_load_errors), if the solver's Error estimate is on and the mesh
/// can be coarsened. "stage_wall_time" holds the solver's stage times and the estimate's.
/// Why the solver's loads get no error estimate ("" if they do): the estimate is off, or the mesh
/// cannot be coarsened (a mesh file without global refinements, odd or too few cells).
std::string error_estimate_unavailable(const ReynoldsSolver &solver);

/// The flow (m^3/s) the discrete mass balance is measured against: the largest of the Couette flow
/// through a radial line of the dam, (|w_r| + |w_s|) C0 (ro^2 - ri^2) / 4, the flat-film
/// Poiseuille leakage 2 pi C0^3 |po - pi| / (12 mu ln(ro/ri)), the squeeze flow and the two
/// leakages. It vanishes only when nothing drives a flow (then the residual is 0).
double mass_balance_flow_scale(const FilmThickness &film, const OperatingConditions &conditions,
                               const FilmLoads &loads);

/// The warning ("" if none) when the interpolated pressure of a reynolds/jfo solve dips below its
/// nodes (FilmLoads::pressure_undershoot) by more than 1 % of the peak pressure above p_cav.
std::string pressure_undershoot_warning(const FilmLoads &loads, double cavitation_pressure);

nlohmann::json finite_element_solve_summary(const FilmSettings &settings,
                                            const ReynoldsSolver &solver, const FilmLoads &loads,
                                            MPI_Comm comm);
} // namespace sealfe
