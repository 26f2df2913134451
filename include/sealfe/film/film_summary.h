// The report of one finite-element film solve (`sealfe solve`): loads, discretisation, the
// cavitation and roughness models as used, and the discretisation error of the loads.
#pragma once

#include <sealfe/film/film_loads.h>
#include <sealfe/film/film_settings.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/mpi.h>

#include <nlohmann/json.hpp>

#include <optional>
#include <string>

namespace sealfe
{
/// summary.json content of the solve `solver` (of `settings`) that gave `loads`: the loads, dofs,
/// degree, iterations, the discrete mass balance, the nodal minimum pressure and the
/// interpolation undershoot below p_cav (with pressure_undershoot_warning), "cavitation",
/// "roughness", and "error_estimate": the loads' grid convergence index from solves of the same
/// settings on meshes twice and four times as coarse (grid_convergence_of_loads), if the
/// solver's Error estimate is on and the mesh can be coarsened. "stage_wall_time" holds the
/// solver's stage times and the estimate's.
/// Why the solver's loads get no error estimate ("" if they do): the estimate is off, or the mesh
/// cannot be coarsened (a mesh file without global refinements, odd or too few cells).
std::string error_estimate_unavailable(const ReynoldsSolver &solver);
/// Why there is no third (4x coarser) mesh for the estimate ("" if there is one).
std::string third_mesh_unavailable(const ReynoldsSolver &solver);

/// The error_estimate entries of the loads of a degree-k solve `fine` from the same solve on
/// meshes 2x (`coarse`) and 4x (`coarsest`, if any; else `why_two_mesh`) as coarse: per load
/// the estimate (grid_convergence) and under "grid_convergence" its verdict; "asymptotic" (every
/// load), "expected_order" (2k, or 1 when a cavitation model has a cavity on any of the meshes),
/// and "warning" naming the loads out of the asymptotic range, if any.
nlohmann::json grid_convergence_of_loads(const FilmSettings &settings, unsigned int degree,
                                         const FilmLoads &fine, const FilmLoads &coarse,
                                         const std::optional<FilmLoads> &coarsest,
                                         const std::string &why_two_mesh);

/// The flow (m^3/s) the discrete mass balance is measured against: the largest of the Couette flow
/// through a radial line of the dam, (|w_r| + |w_s|) C0 (ro^2 - ri^2) / 4, the flat-film
/// Poiseuille leakage 2 pi C0^3 |po - pi| / (12 mu ln(ro/ri)), the squeeze flow and the two
/// leakages. It vanishes only when nothing drives a flow (then the residual is 0).
double mass_balance_flow_scale(const FilmThickness &film, const OperatingConditions &conditions,
                               const FilmLoads &loads);

/// The warning ("" if none) when the interpolated pressure of a reynolds/jfo solve dips below its
/// nodes (FilmLoads::pressure_undershoot) by more than 1 % of the peak pressure above p_cav.
std::string pressure_undershoot_warning(const FilmLoads &loads, double cavitation_pressure);

/// The headline of load `name` (a key of summary.json, unit `unit`) as a user should read it:
/// "0 N m (round-off: computed -4.3e-14, below its bound 1.8e-11)" when its magnitude is below
/// the round-off bound (round_off/absolute_bound), else the value with its discretisation error
/// estimate beside it (error_estimate/<name>) when there is one.
std::string load_with_uncertainty(const nlohmann::json &summary, const std::string &name,
                                  const std::string &unit);

/// summary.json's block of a linear solver's work (`linear_solver`, and the coefficient set's
/// `coefficient_linear_solver`): the method and direct package with the counts of `statistics`.
nlohmann::json linear_solver_summary(const FilmLinearSolver::Statistics &statistics,
                                     const std::string &method, const std::string &direct_package);

nlohmann::json finite_element_solve_summary(const FilmSettings &settings,
                                            const ReynoldsSolver &solver, const FilmLoads &loads,
                                            MPI_Comm comm);
} // namespace sealfe
