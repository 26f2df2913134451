#include <sealfe/film/film_summary.h>
#include <sealfe/film/round_off.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace sealfe
{
namespace
{
/// Error estimate of the loads from a second solve on a mesh twice as coarse.
nlohmann::json load_error_estimate(const FilmSettings &settings, const ReynoldsSolver &solver,
                                   const FilmLoads &loads, MPI_Comm comm, nlohmann::json &timings)
{
  const bool root = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  const std::string unavailable = error_estimate_unavailable(solver);
  if (!unavailable.empty())
  {
    if (root && solver.error_estimate_enabled())
      std::cerr << "sealfe: warning: no error estimate: " << unavailable << std::endl;
    return {{"method", "none: " + unavailable}, {"available", false}};
  }
  // A copy of the whole settings, on the mesh twice as coarse. Its failure does not cost the
  // converged fine result: the estimate is reported unavailable, with the reason.
  ReynoldsSolver coarse(settings, comm);
  FilmLoads c;
  try
  {
    c = coarse.run(1);
  }
  catch (std::exception &x)
  {
    const std::string reason =
        std::string("the error-estimate solve on the 2x coarser mesh failed: ") + x.what();
    if (root)
      std::cerr << "sealfe: warning: no error estimate: " << reason << std::endl;
    return {{"method", "none: " + reason}, {"available", false}};
  }
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
          {"available", true},
          {"coarse_dofs", coarse.n_dofs()}};
}
} // namespace

std::string error_estimate_unavailable(const ReynoldsSolver &solver)
{
  if (!solver.error_estimate_enabled())
    return "Error estimate = false";
  const AnnulusMesh &mesh = solver.mesh();
  if (mesh.can_coarsen(1))
    return "";
  if (!mesh.mesh_file.empty())
    return "the mesh from the Mesh file '" + mesh.mesh_file +
           "' cannot be coarsened (use Global refinements >= 1 to have one)";
  return "the mesh of " + std::to_string(mesh.radial_cells) + " x " +
         std::to_string(mesh.circumferential_cells) +
         " cells cannot be halved (even counts and at least 6 circumferential cells are needed)";
}

std::string pressure_undershoot_warning(const FilmLoads &loads, const double cavitation_pressure)
{
  // Measured against the pressure rise the film builds above the cavity (its peak above p_cav).
  const double peak = loads.max_pressure - cavitation_pressure;
  if (!(peak > 0) || !(loads.pressure_undershoot > 0.01 * peak))
    return "";
  std::ostringstream s;
  s << std::setprecision(3) << "the interpolated pressure dips " << loads.pressure_undershoot
    << " Pa (" << 100 * loads.pressure_undershoot / peak
    << " % of the peak above the cavitation pressure) below its nodes at the cavity edge, which "
       "the solver keeps at p_cav; this dip removes "
    << -loads.pressure_undershoot_force
    << " N from force_z (pressure_undershoot_force). Refine the mesh or use degree 1 to reduce "
       "it (doc/cavitation.md)";
  return s.str();
}

double mass_balance_flow_scale(const FilmThickness &film, const OperatingConditions &conditions,
                               const FilmLoads &loads)
{
  const double ri = film.inner_radius, ro = film.outer_radius, C0 = film.clearance;
  // Couette flow through a radial line of the dam, (|w_r| + |w_s|)/2 int_ri^ro C0 r dr
  const double couette = 0.25 *
                         (std::abs(conditions.rotor_speed) + std::abs(conditions.stator_speed)) *
                         C0 * (ro * ro - ri * ri);
  // radial Poiseuille flow of the flat film of clearance C0 under the supply difference
  const double poiseuille = 2 * M_PI * C0 * C0 * C0 *
                            std::abs(conditions.outer_pressure - conditions.inner_pressure) /
                            (12 * conditions.viscosity * std::log(ro / ri));
  return std::max({couette, poiseuille, std::abs(loads.squeeze_flow), std::abs(loads.leakage_inner),
                   std::abs(loads.leakage_outer), std::numeric_limits<double>::min()});
}

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
  // to a flow scale that vanishes only with every driving term (zero to solver tolerance for none
  // and jfo; doc/reynolds.md, Leakage).
  const double imbalance = std::abs(loads.leakage_inner + loads.leakage_outer + loads.squeeze_flow);
  const double scale = mass_balance_flow_scale(settings.geometry, settings.conditions, loads);
  summary["mass_balance_residual"] = imbalance == 0 ? 0.0 : imbalance / scale;
  summary["mass_balance_flow_scale"] = scale;
  const nlohmann::json round_off =
      estimate_round_off(settings.geometry, settings.conditions, loads).to_json();
  summary["round_off"] = round_off;
  if (round_off.contains("warning") && dealii::Utilities::MPI::this_mpi_process(comm) == 0)
    std::cerr << "sealfe: warning: " << round_off["warning"].get<std::string>() << std::endl;
  summary["min_pressure_nodal"] = loads.min_pressure_nodal;
  summary["pressure_undershoot"] = loads.pressure_undershoot;
  summary["pressure_undershoot_force"] = loads.pressure_undershoot_force;
  const std::string undershoot = pressure_undershoot_warning(loads, solver.cavitation.pressure);
  if (!undershoot.empty())
  {
    summary["pressure_undershoot_warning"] = undershoot;
    if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
      std::cerr << "sealfe: warning: " << undershoot << std::endl;
  }
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
