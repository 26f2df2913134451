#include <sealfe/coefficients/coefficient_solver.h>
#include <sealfe/film/film_summary.h>
#include <sealfe/film/grid_convergence.h>
#include <sealfe/numerics/number_lists.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

namespace sealfe
{
using namespace dealii;

void CoefficientSettings::declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Coefficients");
  prm.declare_entry(
      "Method", "perturbation", Patterns::Selection("perturbation|finite difference"),
      "perturbation: linearise the discrete Reynolds system about the solved pressure and solve "
      "it once per degree of freedom (z, tilt_x, tilt_y) and per rate, reusing the factorisation "
      "of the operating-point solve (6 extra linear solves; where CG solves the film, 3 adjoint "
      "solves with its preconditioner, one per load). finite difference: central "
      "differences of the full nonlinear solve (12 extra solves), to check the perturbation "
      "method.");
  prm.declare_entry("Relative step", "1e-4", Patterns::Double(),
                    "Finite difference only: the steps are this times C0 (axial), C0/ro (tilt), "
                    "and for the rates these times omega_ref = max(|rotor speed|, |stator speed|, "
                    "1 rad/s). Truncation error ~ step^2, round-off ~ 1e-13/step: 1e-4 balances "
                    "them to about 1e-8.");
  prm.declare_entry("Axial step", "0", Patterns::Double(),
                    "Finite difference only: axial step (m); 0 means Relative step * C0.");
  prm.declare_entry("Tilt step", "0", Patterns::Double(),
                    "Finite difference only: tilt step (rad); 0 means Relative step * C0/ro.");
  prm.leave_subsection();
}

void CoefficientSettings::parse_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Coefficients");
  method =
      prm.get("Method") == "finite difference" ? Method::finite_difference : Method::perturbation;
  relative_step = prm.get_double("Relative step");
  axial_step = prm.get_double("Axial step");
  tilt_step = prm.get_double("Tilt step");
  prm.leave_subsection();
  auto check = [](const double v, const char *name, const bool zero_allowed)
  {
    if (!std::isfinite(v) || v < 0 || (!zero_allowed && v == 0))
    {
      std::ostringstream s;
      s << "Coefficients: '" << name << "' must be " << (zero_allowed ? "zero or " : "")
        << "positive (got " << v << ")";
      throw std::runtime_error(s.str());
    }
  };
  check(relative_step, "Relative step", false);
  check(axial_step, "Axial step", true);
  check(tilt_step, "Tilt step", true);
  if (relative_step >= 0.5)
    throw std::runtime_error("Coefficients: 'Relative step' must be well below 1 (got " +
                             numerics::to_prm_string(relative_step) + "); 1e-4 is a good value");
}

CoefficientSettings::Steps CoefficientSettings::steps(const FilmThickness &film,
                                                      const OperatingConditions &conditions) const
{
  Steps s;
  s.axial = axial_step > 0 ? axial_step : relative_step * film.clearance;
  s.tilt = tilt_step > 0 ? tilt_step : relative_step * film.clearance / film.outer_radius;
  const double omega_ref =
      std::max({std::abs(conditions.rotor_speed), std::abs(conditions.stator_speed), 1.0});
  s.axial_rate = s.axial * omega_ref;
  s.tilt_rate = s.tilt * omega_ref;
  return s;
}

std::string to_string(const CoefficientSettings::Method method)
{
  return method == CoefficientSettings::Method::finite_difference ? "finite difference"
                                                                  : "perturbation";
}

namespace
{
using Matrix3 = FilmCoefficients::Matrix3;

/// F = (F_z, M_x, M_y) of a set of loads.
std::array<double, 3> generalized_force(const FilmLoads &l)
{
  return {{l.force_z, l.moment_x, l.moment_y}};
}

/// dh/dq_j of the flexible ring's degrees of freedom q = (z, tilt_x, tilt_y): the face moves by
/// w = z + tilt_x y - tilt_y x (film_thickness.h), and the same functions are d(dh/dt)/dq_dot_j.
const std::array<std::function<double(double, double)>, 3> &mode_shapes()
{
  static const std::array<std::function<double(double, double)>, 3> shapes = {
      {[](double, double) { return 1.0; }, [](double r, double t) { return r * std::sin(t); },
       [](double r, double t) { return -r * std::cos(t); }}};
  return shapes;
}

/// The film with degree of freedom j (0..2 displacements, 3..5 rates) moved by `step`.
FilmThickness perturbed(const FilmThickness &film, const unsigned int j, const double step)
{
  FilmThickness f = film;
  switch (j)
  {
  case 0:
    f.axial_offset += step;
    break;
  case 1:
    f.set_tilt_vector(film.tilt_x() + step, film.tilt_y());
    break;
  case 2:
    f.set_tilt_vector(film.tilt_x(), film.tilt_y() + step);
    break;
  case 3:
    f.axial_velocity += step;
    break;
  case 4:
    f.tilt_rate_x += step;
    break;
  default:
    f.tilt_rate_y += step;
    break;
  }
  return f;
}

double seconds_since(const std::chrono::steady_clock::time_point &start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string linearization_note(const CoefficientSettings::Method method,
                               const CavitationSettings &cavitation)
{
  if (method == CoefficientSettings::Method::finite_difference)
    return "central differences of the nonlinear solve (the cavitation boundary moves with the "
           "perturbation)";
  if (cavitation.model == Cavitation::none)
    return "full film: exact derivative of the discrete Reynolds system";
  if (cavitation.model == Cavitation::half_sommerfeld)
    return "half-Sommerfeld: frozen cavitation boundary, the perturbed pressure counts only "
           "where p > p_cav; this is the derivative of the clipped loads (the clipped integrand "
           "is continuous at the boundary), except at quadrature points that sit on p_cav";
  if (cavitation.model == Cavitation::reynolds)
    return "Reynolds (Swift-Stieber): linearised at the converged active set, which is frozen "
           "(the perturbed pressure is zero at the nodes held at p_cav)";
  if (cavitation.model == Cavitation::jfo)
    return "JFO: the Jacobian of the converged complementarity system at its cavitated set "
           "(pressure and liquid fraction perturbed together; the set itself is not moved)";
  return "linearisation of the solver's cavitation model (ReynoldsSolver::linearized_loads)";
}

/// The loads that get an error estimate, by their summary.json names.
const std::vector<std::pair<const char *, double FilmLoads::*>> &load_members()
{
  static const std::vector<std::pair<const char *, double FilmLoads::*>> m = {
      {"force_z", &FilmLoads::force_z},
      {"moment_x", &FilmLoads::moment_x},
      {"moment_y", &FilmLoads::moment_y},
      {"moment_restoring", &FilmLoads::moment_restoring},
      {"moment_transverse", &FilmLoads::moment_transverse},
      {"leakage_inner", &FilmLoads::leakage_inner},
      {"leakage_outer", &FilmLoads::leakage_outer},
      {"friction_torque", &FilmLoads::friction_torque},
      {"cavitated_fraction", &FilmLoads::cavitated_fraction}};
  return m;
}

nlohmann::json verdict_rows(const std::array<std::array<GridConvergence, 3>, 3> &m)
{
  nlohmann::json a = nlohmann::json::array();
  for (const auto &row : m)
    a.push_back({row[0].to_json(), row[1].to_json(), row[2].to_json()});
  return a;
}

nlohmann::json rows(const Matrix3 &m)
{
  nlohmann::json a = nlohmann::json::array();
  for (const auto &row : m)
    a.push_back({row[0], row[1], row[2]});
  return a;
}
} // namespace

nlohmann::json CoefficientResult::to_json() const
{
  nlohmann::json j = loads.to_json();
  const nlohmann::json k = coefficients.to_json(); // (items() of a temporary would dangle)
  for (const auto &[key, value] : k.items())
    j[key] = value;
  j["model"] = "finite element";
  j["coefficient_method"] = to_string(method);
  j["linearization"] = linearization;
  if (method == CoefficientSettings::Method::finite_difference)
    j["finite_difference_steps"] = {{"axial", steps.axial},
                                    {"tilt", steps.tilt},
                                    {"axial_rate", steps.axial_rate},
                                    {"tilt_rate", steps.tilt_rate}};
  j["dofs"] = dofs;
  j["polynomial_degree"] = degree;
  j["mapping_degree"] = mapping_degree;
  j["units"] = {{"stiffness",
                 {{"N/m", "N/rad", "N/rad"},
                  {"N m/m", "N m/rad", "N m/rad"},
                  {"N m/m", "N m/rad", "N m/rad"}}},
                {"damping",
                 {{"N s/m", "N s/rad", "N s/rad"},
                  {"N m s/m", "N m s/rad", "N m s/rad"},
                  {"N m s/m", "N m s/rad", "N m s/rad"}}}};
  if (has_error_estimate)
  {
    nlohmann::json e = load_error.to_json();
    for (const char *k : {"min_film", "max_pressure", "min_pressure", "area"})
      e.erase(k);
    e["stiffness"] = rows(stiffness_error);
    e["damping"] = rows(damping_error);
    for (const char *k : {"grid_convergence", "asymptotic", "expected_order", "warning"})
      if (load_estimate.contains(k))
        e[k] = load_estimate[k];
    e["coefficients_asymptotic"] = coefficients_asymptotic;
    e["coefficients_grid_convergence"] = {{"stiffness", verdict_rows(stiffness_convergence)},
                                          {"damping", verdict_rows(damping_convergence)}};
    e["method"] = "grid convergence index of the computations on the 2x and 4x coarser meshes "
                  "(observed order, Fs = 1.25 asymptotic, 3 otherwise), at least the difference "
                  "to the 2x coarser mesh / (2^k - 1)";
    e["available"] = true;
    e["coarse_dofs"] = coarse_dofs;
    e["coarser_dofs"] = coarsest_dofs > 0 ? nlohmann::json::array({coarse_dofs, coarsest_dofs})
                                          : nlohmann::json::array({coarse_dofs});
    j["error_estimate"] = e;
  }
  else
    j["error_estimate"] = {{"method", "none: " + no_error_estimate_reason}, {"available", false}};
  j["stage_wall_time"] = {{"solve", solve_time},
                          {"coefficients", coefficient_time},
                          {"error_estimate", error_estimate_time}};
  // The cost of the coefficient set relative to the solve it linearises (target <= 1.5).
  j["coefficient_cost_ratio"] = solve_time > 0 ? coefficient_time / solve_time : 0.0;
  j["linear_solver"] = linear_solver_summary(operating_point_linear, linear_method, direct_package);
  j["coefficient_linear_solver"] =
      linear_solver_summary(coefficient_linear, linear_method, direct_package);
  return j;
}

CoefficientSolver::CoefficientSolver(MPI_Comm comm) : comm(comm), solver(comm) {}

CoefficientSolver::CoefficientSolver(const FilmSettings &film_settings,
                                     const CoefficientSettings &coefficient_settings, MPI_Comm comm)
    : settings(coefficient_settings), comm(comm), solver(film_settings, comm)
{
}

void CoefficientSolver::declare_parameters(ParameterHandler &prm)
{
  ReynoldsSolver::declare_parameters(prm);
  CoefficientSettings::declare_parameters(prm);
}

void CoefficientSolver::parse_parameters(ParameterHandler &prm)
{
  solver.parse_parameters(prm);
  settings.parse_parameters(prm);
}

std::pair<FilmLoads, FilmCoefficients>
CoefficientSolver::compute_on_mesh(const FilmThickness &film, const OperatingConditions &conditions,
                                   const unsigned int coarsening, MeshCost &cost)
{
  FilmCoefficients c;
  c.level = 2;
  c.model = "finite element (" + to_string(settings.method) + ")";
  c.rotor_speed = conditions.rotor_speed;
  c.stator_speed = conditions.stator_speed;
  FilmLoads base;

  if (settings.method == CoefficientSettings::Method::perturbation)
  {
    auto start = std::chrono::steady_clock::now();
    base = solver.run(film, conditions, coarsening);
    cost.solve_time = seconds_since(start);
    cost.solve_linear = solver.linear_solver_statistics().statistics();
    solver.reset_linear_solver_statistics(); // from here: the coefficient set's solves
    start = std::chrono::steady_clock::now();
    // Columns of K: dh = dh/dq_j; columns of D: d(dh/dt) = dh/dq_j.
    std::vector<ReynoldsSolver::FilmPerturbation> directions(6);
    for (unsigned int j = 0; j < 3; ++j)
    {
      directions[j].dh = mode_shapes()[j];
      directions[3 + j].dh_dt = mode_shapes()[j];
    }
    // only force_z, moment_x and moment_y: with CG three adjoint solves, not six
    const std::vector<std::array<double, 3>> derivatives =
        solver.linearized_generalized_forces(directions);
    for (unsigned int j = 0; j < 3; ++j)
    {
      const auto &dF = derivatives[j];
      const auto &dF_rate = derivatives[3 + j];
      for (unsigned int i = 0; i < 3; ++i)
      {
        c.stiffness[i][j] = -dF[i];
        c.damping[i][j] = -dF_rate[i];
      }
    }
    cost.coefficient_time = seconds_since(start);
    cost.coefficient_linear = solver.linear_solver_statistics().statistics();
  }
  else
  {
    // The mesh is graded by C0 and coning only (ReynoldsSolver::setup_system), so every
    // perturbed solve uses the same mesh and the differences carry no remeshing noise.
    const CoefficientSettings::Steps s = settings.steps(film, conditions);
    const std::array<double, 6> step = {
        {s.axial, s.tilt, s.tilt, s.axial_rate, s.tilt_rate, s.tilt_rate}};
    auto start = std::chrono::steady_clock::now();
    cost.coefficient_linear = FilmLinearSolver::Statistics();
    for (unsigned int j = 0; j < 6; ++j)
    {
      const auto plus =
          generalized_force(solver.run(perturbed(film, j, step[j]), conditions, coarsening));
      cost.coefficient_linear += solver.linear_solver_statistics().statistics();
      const auto minus =
          generalized_force(solver.run(perturbed(film, j, -step[j]), conditions, coarsening));
      cost.coefficient_linear += solver.linear_solver_statistics().statistics();
      for (unsigned int i = 0; i < 3; ++i)
      {
        const double derivative = (plus[i] - minus[i]) / (2 * step[j]);
        (j < 3 ? c.stiffness[i][j] : c.damping[i][j - 3]) = -derivative;
      }
    }
    cost.coefficient_time = seconds_since(start);
    // The operating point last, so that the solver is left holding its solution.
    start = std::chrono::steady_clock::now();
    base = solver.run(film, conditions, coarsening);
    cost.solve_time = seconds_since(start);
    cost.solve_linear = solver.linear_solver_statistics().statistics();
  }
  return {base, c};
}

FilmCoefficients CoefficientSolver::coefficients(const FilmThickness &film,
                                                 const OperatingConditions &conditions,
                                                 const unsigned int coarsening)
{
  MeshCost cost;
  return compute_on_mesh(film, conditions, coarsening, cost).second;
}

CoefficientResult CoefficientSolver::compute(const FilmThickness &film,
                                             const OperatingConditions &conditions)
{
  CoefficientResult r;
  r.method = settings.method;
  r.linearization = linearization_note(settings.method, solver.cavitation);
  if (settings.method == CoefficientSettings::Method::finite_difference)
    r.steps = settings.steps(film, conditions);

  // The coarse meshes first, so that the solver ends holding the fine solution.
  FilmLoads coarse_loads;
  FilmCoefficients coarse;
  std::optional<std::pair<FilmLoads, FilmCoefficients>> coarsest;
  r.no_error_estimate_reason = error_estimate_unavailable(solver);
  r.has_error_estimate = r.no_error_estimate_reason.empty();
  std::string why_two_mesh;
  if (r.has_error_estimate)
  {
    const auto start = std::chrono::steady_clock::now();
    MeshCost coarse_cost;
    // The estimate's failure does not cost the fine result: it is reported unavailable (or, for
    // the 4x coarser mesh, two-mesh).
    why_two_mesh = third_mesh_unavailable(solver);
    if (why_two_mesh.empty())
    {
      try
      {
        coarsest = compute_on_mesh(film, conditions, 2, coarse_cost);
        r.coarsest_dofs = solver.n_dofs();
      }
      catch (std::exception &e)
      {
        why_two_mesh = std::string("the solve on the 4x coarser mesh failed: ") + e.what();
      }
    }
    try
    {
      std::tie(coarse_loads, coarse) = compute_on_mesh(film, conditions, 1, coarse_cost);
      r.coarse_dofs = solver.n_dofs();
    }
    catch (std::exception &e)
    {
      r.has_error_estimate = false;
      r.no_error_estimate_reason =
          std::string("the error-estimate solve on the 2x coarser mesh failed: ") + e.what();
    }
    r.error_estimate_time = seconds_since(start);
  }

  MeshCost fine_cost;
  std::tie(r.loads, r.coefficients) = compute_on_mesh(film, conditions, 0, fine_cost);
  r.solve_time = fine_cost.solve_time;
  r.coefficient_time = fine_cost.coefficient_time;
  r.operating_point_linear = fine_cost.solve_linear;
  r.coefficient_linear = fine_cost.coefficient_linear;
  r.linear_method = solver.linear_solver_statistics().method_name();
  r.direct_package = solver.linear_solver_statistics().direct_package();
  r.dofs = solver.n_dofs();
  r.degree = solver.degree();
  r.mapping_degree = solver.settings.mapping_degree();

  if (r.has_error_estimate)
  {
    // The same three-mesh rule as the loads of `sealfe solve` (grid_convergence_of_loads): the
    // coefficients are linear functionals of the perturbed pressure, which converges like p.
    const std::optional<FilmLoads> coarsest_loads =
        coarsest ? std::optional<FilmLoads>(coarsest->first) : std::nullopt;
    FilmSettings point = solver.settings;
    point.geometry = film;
    point.conditions = conditions;
    r.load_estimate = grid_convergence_of_loads(point, r.degree, r.loads, coarse_loads,
                                                coarsest_loads, why_two_mesh);
    for (const auto &[name, member] : load_members())
      r.load_error.*member = r.load_estimate[name].get<double>();
    const double expected = r.load_estimate["expected_order"];
    r.coefficients_asymptotic = true;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
      {
        // Entries of different units: the scale of (i, j) is sqrt(|X_ii X_jj|) of the fine
        // matrix (and its own size), below which differences are round-off.
        auto entry = [&](const FilmCoefficients::Matrix3 FilmCoefficients::*m,
                         FilmCoefficients::Matrix3 &error,
                         std::array<std::array<GridConvergence, 3>, 3> &verdict)
        {
          const auto &X = r.coefficients.*m;
          const double scale = std::max({std::sqrt(std::abs(X[i][i] * X[j][j])), std::abs(X[i][j]),
                                         std::numeric_limits<double>::min()});
          const double floor = richardson_error(X[i][j], (coarse.*m)[i][j], r.degree);
          verdict[i][j] = grid_convergence(
              X[i][j], (coarse.*m)[i][j],
              coarsest ? std::optional<double>((coarsest->second.*m)[i][j]) : std::nullopt,
              expected, floor, grid_convergence_noise * scale, why_two_mesh);
          error[i][j] = verdict[i][j].estimate;
          r.coefficients_asymptotic = r.coefficients_asymptotic && verdict[i][j].asymptotic;
          r.coefficients_warning = r.coefficients_warning || deserves_warning(verdict[i][j], scale);
        };
        entry(&FilmCoefficients::stiffness, r.stiffness_error, r.stiffness_convergence);
        entry(&FilmCoefficients::damping, r.damping_error, r.damping_convergence);
      }
  }
  return r;
}

CoefficientResult CoefficientSolver::compute()
{
  const FilmThickness film = solver.settings.geometry;
  const OperatingConditions conditions = solver.settings.conditions;
  return compute(film, conditions);
}

std::function<FilmCoefficients(double, double)>
CoefficientSolver::film_model(const FilmThickness &film, const OperatingConditions &conditions)
{
  auto cache = std::make_shared<std::map<std::pair<double, double>, FilmCoefficients>>();
  return [this, film, conditions, cache](const double rotor_speed, const double stator_speed)
  {
    const auto key = std::make_pair(rotor_speed, stator_speed);
    const auto hit = cache->find(key);
    if (hit != cache->end())
      return hit->second;
    OperatingConditions c = conditions;
    c.rotor_speed = rotor_speed;
    c.stator_speed = stator_speed;
    const FilmCoefficients k = coefficients(film, c);
    cache->emplace(key, k);
    return k;
  };
}

} // namespace sealfe
