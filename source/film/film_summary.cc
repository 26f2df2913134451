#include <sealfe/film/film_summary.h>

#include <algorithm>
#include <cmath>

namespace sealfe
{
namespace
{
/// Error estimate of the loads from a second solve on a mesh twice as coarse.
nlohmann::json load_error_estimate(const FilmSettings &settings, const ReynoldsSolver &solver,
                                   const FilmLoads &loads, MPI_Comm comm, nlohmann::json &timings)
{
  if (!solver.error_estimate_enabled() || !solver.mesh().can_coarsen(1))
    return {{"method", "none: disabled or the mesh cannot be coarsened"}};
  // A copy of the whole settings, on the mesh twice as coarse.
  ReynoldsSolver coarse(settings, comm);
  const FilmLoads c = coarse.run(1);
  const FilmLoads e = estimate_load_errors(loads, c, solver.degree());
  double time = 0;
  for (const auto &[k, v] : coarse.stage_times())
    time += v;
  timings["error_estimate"] = time;
  return {{"force_z", e.force_z},
          {"moment_x", e.moment_x},
          {"moment_y", e.moment_y},
          {"moment_restoring", e.moment_restoring},
          {"moment_transverse", e.moment_transverse},
          {"leakage_inner", e.leakage_inner},
          {"leakage_outer", e.leakage_outer},
          {"friction_torque", e.friction_torque},
          {"cavitated_fraction", e.cavitated_fraction},
          {"method", "difference to a 2x coarser mesh / (2^k - 1)"},
          {"coarse_dofs", coarse.n_dofs()}};
}
} // namespace

nlohmann::json finite_element_solve_summary(const FilmSettings &settings,
                                            const ReynoldsSolver &solver, const FilmLoads &loads,
                                            MPI_Comm comm)
{
  nlohmann::json summary = loads.to_json();
  summary["model"] = "finite element";
  summary["dofs"] = solver.n_dofs();
  summary["polynomial_degree"] = solver.degree();
  summary["linear_iterations"] = solver.linear_iterations();
  const FilmLinearSolver &linear = solver.linear_solver_statistics();
  summary["linear_solver"] = {
      {"method", linear.method_name()},
      {"factorizations", linear.statistics().factorizations},
      {"solves", linear.statistics().solves},
      {"krylov_iterations", linear.statistics().krylov_iterations},
      {"max_krylov_iterations", linear.statistics().max_krylov_iterations},
      {"reused_preconditioners", linear.statistics().reused_preconditioners}};
  summary["leakage_imbalance"] = loads.leakage_inner + loads.leakage_outer;
  // Discrete mass balance: what leaves through the two circles plus the squeeze flow, relative
  // to the larger leakage (zero to solver tolerance for none and jfo).
  summary["mass_balance_residual"] =
      std::abs(loads.leakage_inner + loads.leakage_outer + loads.squeeze_flow) /
      std::max({std::abs(loads.leakage_inner), std::abs(loads.leakage_outer), 1e-300});
  const char *names[] = {"none", "half-sommerfeld", "reynolds", "jfo"};
  summary["cavitation"] = {{"model", names[static_cast<int>(solver.cavitation.model)]},
                           {"cavitation_pressure", solver.cavitation.pressure},
                           {"nonlinear_iterations", solver.nonlinear_iterations()},
                           {"coarse_level_iterations", solver.coarse_nonlinear_iterations()},
                           {"final_residual", solver.nonlinear_residual()}};
  summary["roughness"] = {{"model", solver.flow_factors.is_smooth() ? "none" : "patir-cheng"},
                          {"composite_roughness", solver.flow_factors.composite_roughness()},
                          {"clamped_evaluations", solver.flow_factors.clamp_count()},
                          {"contact_model", solver.contact.enabled() ? "gw-ceb" : "none"}};
  nlohmann::json timings = solver.stage_times();
  summary["error_estimate"] = load_error_estimate(settings, solver, loads, comm, timings);
  summary["stage_wall_time"] = timings;
  return summary;
}

} // namespace sealfe
