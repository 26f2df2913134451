#include <sealfe/film/film_summary.h>
#include <sealfe/film/grid_convergence.h>
#include <sealfe/film/round_off.h>

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>

namespace sealfe
{
namespace
{
/// Error estimate of the loads from solves on meshes twice and four times as coarse
/// (grid_convergence.h); the 4x coarser one is skipped (two-mesh estimate, flagged) when the mesh
/// cannot be coarsened twice or its solve fails.
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
  // Copies of the whole settings, on the meshes twice and four times as coarse. A failure does
  // not cost the converged fine result: the estimate is reported unavailable (or two-mesh), with
  // the reason.
  double time = 0;
  auto add_time = [&](const ReynoldsSolver &s)
  {
    for (const auto &[k, v] : s.stage_times())
      time += v;
  };
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
  add_time(coarse);
  std::optional<FilmLoads> cc;
  std::string why_two_mesh = third_mesh_unavailable(solver);
  dealii::types::global_dof_index coarsest_dofs = 0;
  if (why_two_mesh.empty())
  {
    ReynoldsSolver coarsest(settings, comm);
    try
    {
      cc = coarsest.run(2);
      coarsest_dofs = coarsest.n_dofs();
    }
    catch (std::exception &x)
    {
      why_two_mesh = std::string("the solve on the 4x coarser mesh failed: ") + x.what();
    }
    add_time(coarsest);
  }
  timings["error_estimate"] = time;
  nlohmann::json e =
      grid_convergence_of_loads(settings, solver.degree(), loads, c, cc, why_two_mesh);
  e["method"] = "grid convergence index of the solves on the 2x and 4x coarser meshes "
                "(observed order, Fs = 1.25 asymptotic, 3 otherwise), at least the difference to "
                "the 2x coarser mesh / (2^k - 1)";
  e["available"] = true;
  e["coarse_dofs"] = coarse.n_dofs();
  e["coarser_dofs"] = cc ? nlohmann::json::array({coarse.n_dofs(), coarsest_dofs})
                         : nlohmann::json::array({coarse.n_dofs()});
  if (root && e.contains("warning"))
    std::cerr << "sealfe: warning: " << e["warning"].get<std::string>() << std::endl;
  return e;
}
} // namespace

std::string third_mesh_unavailable(const ReynoldsSolver &solver)
{
  const AnnulusMesh &mesh = solver.mesh();
  if (mesh.can_coarsen(2))
    return "";
  if (!mesh.mesh_file.empty())
    return "the mesh from the Mesh file '" + mesh.mesh_file + "' cannot be coarsened twice";
  return "the mesh of " + std::to_string(mesh.radial_cells) + " x " +
         std::to_string(mesh.circumferential_cells) +
         " cells cannot be coarsened twice (cell counts divisible by 4 and at least 12 "
         "circumferential cells are needed)";
}

nlohmann::json grid_convergence_of_loads(const FilmSettings &settings, const unsigned int degree,
                                         const FilmLoads &fine, const FilmLoads &coarse,
                                         const std::optional<FilmLoads> &coarsest,
                                         const std::string &why_two_mesh)
{
  const FilmLoads floor = estimate_load_errors(fine, coarse, degree);
  double cavitated = std::max(fine.cavitated_fraction, coarse.cavitated_fraction);
  if (coarsest)
    cavitated = std::max(cavitated, coarsest->cavitated_fraction);
  const bool cavitating = settings.cavitation.model != Cavitation::none && cavitated > 0;
  const double expected = expected_load_order(degree, cavitating);
  // Scales of each kind of quantity, below which differences are round-off.
  const double force_scale =
      std::max({std::abs(fine.force_z),
                std::max(std::abs(fine.max_pressure), std::abs(fine.min_pressure)) * fine.area,
                std::numeric_limits<double>::min()});
  const double moment_scale = force_scale * settings.geometry.outer_radius;
  const double flow_scale = mass_balance_flow_scale(settings.geometry, settings.conditions, fine);
  const double friction_scale =
      std::max(std::abs(fine.friction_torque), moment_scale * settings.geometry.clearance);
  struct Quantity
  {
    const char *name;
    double FilmLoads::*member;
    double scale;
  };
  const Quantity quantities[] = {{"force_z", &FilmLoads::force_z, force_scale},
                                 {"moment_x", &FilmLoads::moment_x, moment_scale},
                                 {"moment_y", &FilmLoads::moment_y, moment_scale},
                                 {"moment_restoring", &FilmLoads::moment_restoring, moment_scale},
                                 {"moment_transverse", &FilmLoads::moment_transverse, moment_scale},
                                 {"leakage_inner", &FilmLoads::leakage_inner, flow_scale},
                                 {"leakage_outer", &FilmLoads::leakage_outer, flow_scale},
                                 {"friction_torque", &FilmLoads::friction_torque, friction_scale},
                                 {"cavitated_fraction", &FilmLoads::cavitated_fraction, 1.0}};
  nlohmann::json e, details;
  std::string flagged;
  bool all_asymptotic = true;
  for (const Quantity &q : quantities)
  {
    const GridConvergence g =
        grid_convergence(fine.*q.member, coarse.*q.member,
                         coarsest ? std::optional<double>((*coarsest).*q.member) : std::nullopt,
                         expected, floor.*q.member, grid_convergence_noise * q.scale, why_two_mesh);
    e[q.name] = g.estimate;
    details[q.name] = g.to_json();
    all_asymptotic = all_asymptotic && g.asymptotic;
    if (deserves_warning(g, q.scale))
    {
      flagged += std::string(flagged.empty() ? "" : ", ") + q.name + " (" + g.convergence +
                 (std::isfinite(g.observed_order)
                      ? ", observed order " + std::to_string(g.observed_order).substr(0, 4)
                      : std::string()) +
                 ")";
    }
  }
  e["grid_convergence"] = details;
  e["asymptotic"] = all_asymptotic;
  e["expected_order"] = expected;
  if (!flagged.empty())
    e["warning"] = "the error estimate of " + flagged +
                   " is not in the asymptotic range (expected "
                   "order " +
                   std::to_string(static_cast<int>(expected)) +
                   "): it is widened (Fs = 3) and may not bound the error; refine the mesh";
  return e;
}

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

namespace
{
/// The number at `path` in `j`, 0 if there is none (an estimate that was not made).
double number_at(const nlohmann::json &j, std::initializer_list<std::string> path)
{
  const nlohmann::json *node = &j;
  for (const std::string &key : path)
  {
    if (!node->is_object() || !node->contains(key))
      return 0.0;
    node = &node->at(key);
  }
  return node->is_number() ? node->get<double>() : 0.0;
}
} // namespace

std::string load_with_uncertainty(const nlohmann::json &summary, const std::string &name,
                                  const std::string &unit)
{
  const double value = summary.at(name).get<double>();
  const double round_off = number_at(summary, {"round_off", "absolute_bound", name});
  const double discretisation = number_at(summary, {"error_estimate", name});
  std::ostringstream s;
  s << std::setprecision(6);
  if (std::abs(value) <= round_off)
  {
    s << "0 " << unit << std::setprecision(2) << " (round-off: computed " << value
      << ", below its bound " << round_off << ")";
    return s.str();
  }
  s << value << " " << unit;
  if (discretisation > 0)
    s << std::setprecision(2) << " (+- " << discretisation << " discretisation)";
  return s.str();
}

nlohmann::json linear_solver_summary(const FilmLinearSolver::Statistics &statistics,
                                     const std::string &method, const std::string &direct_package)
{
  return {{"method", method},
          {"direct_package", direct_package},
          {"factorizations", statistics.factorizations},
          {"solves", statistics.solves},
          {"krylov_iterations", statistics.krylov_iterations},
          {"max_krylov_iterations", statistics.max_krylov_iterations},
          {"symbolic_reuses", statistics.symbolic_reuses},
          {"reused_preconditioners", statistics.reused_preconditioners},
          {"workspace_retries", statistics.workspace_retries},
          {"substructured_factorizations", statistics.substructured_factorizations},
          {"single_precision_factorizations", statistics.single_precision_factorizations},
          {"refinement_steps", statistics.refinement_steps},
          {"refinement_fallbacks", statistics.refinement_fallbacks},
          {"nested_dissection_analyses", statistics.nested_dissection_analyses}};
}

nlohmann::json finite_element_solve_summary(const FilmSettings &settings,
                                            const ReynoldsSolver &solver, const FilmLoads &loads,
                                            MPI_Comm comm)
{
  nlohmann::json summary = loads.to_json();
  summary["model"] = "finite element";
  summary["dofs"] = solver.n_dofs();
  summary["polynomial_degree"] = solver.degree();
  summary["mapping_degree"] = solver.settings.mapping_degree();
  summary["linear_iterations"] = solver.linear_iterations();
  const FilmLinearSolver &linear = solver.linear_solver_statistics();
  summary["linear_solver"] =
      linear_solver_summary(linear.statistics(), linear.method_name(), linear.direct_package());
  summary["leakage_imbalance"] = loads.leakage_inner + loads.leakage_outer;
  // Discrete mass balance: what leaves through the two circles plus the squeeze flow, relative
  // to a flow scale that vanishes only with every driving term (zero to solver tolerance for none
  // and jfo; doc/reynolds.md, Leakage).
  const double imbalance = std::abs(loads.leakage_inner + loads.leakage_outer + loads.squeeze_flow);
  const double scale = mass_balance_flow_scale(settings.geometry, settings.conditions, loads);
  summary["mass_balance_residual"] = imbalance == 0 ? 0.0 : imbalance / scale;
  summary["mass_balance_flow_scale"] = scale;
  const RoundOffEstimate round_off_estimate =
      estimate_round_off(settings.geometry, settings.conditions, loads);
  nlohmann::json round_off = round_off_estimate.to_json();
  round_off["absolute_bound"] =
      round_off_bounds_of_loads(round_off_estimate, settings.geometry, scale);
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
  summary["cavitation"] = {
      {"model", names[static_cast<int>(solver.cavitation.model)]},
      {"cavitation_pressure", solver.cavitation.pressure},
      {"nonlinear_iterations", solver.nonlinear_iterations()},
      {"coarse_level_iterations", solver.coarse_nonlinear_iterations()},
      {"newton_steps", solver.newton_steps()},
      {"active_set_rounds", solver.active_set_rounds()},
      {"band_factorizations", solver.band_rounds()},
      {"band_workspace_retries", solver.band_workspace_retries()},
      {"low_rank_updates", solver.low_rank_updates()},
      {"coarse_level_factorizations", solver.coarse_level_factorizations()},
      {"coarse_level_krylov_iterations", solver.coarse_level_krylov_iterations()},
      {"coarse_level_workspace_retries", solver.coarse_level_workspace_retries()},
      {"final_residual", solver.nonlinear_residual()}};
  summary["roughness"] = {{"model", solver.flow_factors.is_smooth() ? "none" : "patir-cheng"},
                          {"composite_roughness", solver.flow_factors.composite_roughness()},
                          {"clamped_evaluations", solver.flow_factors.clamp_count()},
                          {"contact_model", solver.contact.enabled() ? "gw-ceb" : "none"}};
  nlohmann::json timings = solver.stage_times();
  summary["error_estimate"] = load_error_estimate(settings, solver, loads, comm, timings);
  summary["stage_wall_time"] = timings;
  summary["stage_detail_wall_time"] = solver.detail_times();
  return summary;
}

} // namespace sealfe
