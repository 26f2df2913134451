// `sealfe coefficients`: the film stiffness K and damping D (and the loads) of one operating point
// by the finite-element solve, with an error estimate of every entry and Green & Etsion's
// narrow-seal values for comparison.
#include "driver.h"

#include <sealfe/closed_form/green_etsion.h>
#include <sealfe/coefficients/coefficient_solver.h>
#include <sealfe/film/film_settings.h>

#include <deal.II/base/utilities.h>

#include <iomanip>
#include <iostream>
#include <sstream>

namespace sealfe::applications
{
using namespace dealii;

namespace
{
/// Level 0 on the same seal, so that a user sees what the closed form would have said (it
/// describes the untilted, unwaved coned face in full film only).
nlohmann::json narrow_seal_reference(const FilmThickness &film,
                                     const OperatingConditions &conditions)
{
  try
  {
    const GreenEtsionCoefficients narrow(film, conditions);
    nlohmann::json n =
        narrow.coefficients(conditions.rotor_speed, conditions.stator_speed).to_json();
    n["note"] = "Green & Etsion narrow-seal closed form (level 0): untilted coned face, full film, "
                "error O((1 - ri/ro)^2)";
    return n;
  }
  catch (std::exception &e)
  {
    return {{"note", std::string("not available: ") + e.what()}};
  }
}

void print_headline(const CoefficientResult &r)
{
  auto print = [](const char *name, const FilmCoefficients::Matrix3 &m, const char *unit)
  {
    std::cout << "  " << name << " (" << unit << ")\n";
    for (const auto &row : m)
      std::cout << "    " << std::setw(14) << row[0] << std::setw(14) << row[1] << std::setw(14)
                << row[2] << "\n";
  };
  std::cout << std::setprecision(6) << "sealfe coefficients (finite element, "
            << to_string(r.method) << ", " << r.dofs << " dofs, degree " << r.degree << ")\n"
            << "  force_z            " << r.loads.force_z << " N\n"
            << "  moment_x, moment_y " << r.loads.moment_x << ", " << r.loads.moment_y << " N m\n";
  print("stiffness K = -dF/dq, q = (z, tilt_x, tilt_y)", r.coefficients.stiffness,
        "N/m, N/rad; N m/m, N m/rad");
  print("damping D = -dF/dq_dot", r.coefficients.damping, "N s/m, N s/rad; N m s/m, N m s/rad");
  std::cout << "  angular k, c, d    " << r.coefficients.tilt_direct_stiffness() << ", "
            << r.coefficients.tilt_cross_stiffness() << ", " << r.coefficients.tilt_direct_damping()
            << "\n";
  // What the coefficient set cost the linear solver (issue 13: Krylov iterations bounded).
  const bool krylov = r.linear_method != "direct";
  // FilmLinearSolver::Statistics::factorizations: KLU/MUMPS factorisations, or multigrid/AMG
  // set-ups (gmres-amg: either, its fallback is KLU)
  const char *set_up = !krylov                          ? " factorisation"
                       : r.linear_method == "gmres-amg" ? " AMG set-up or factorisation"
                                                        : " preconditioner set-up";
  auto work = [&](const FilmLinearSolver::Statistics &w)
  {
    std::ostringstream s;
    s << w.solves << (w.solves == 1 ? " solve" : " solves");
    if (w.factorizations > 0)
      s << ", " << w.factorizations << set_up << (w.factorizations == 1 ? "" : "s");
    if (w.krylov_iterations > 0)
      s << ", " << w.max_krylov_iterations << " Krylov iterations at most";
    return s.str();
  };
  std::cout << "  linear solver      " << r.linear_method
            << (r.direct_package.empty() ? "" : " (" + r.direct_package + ")")
            << ": operating point " << work(r.operating_point_linear) << "; coefficient set "
            << work(r.coefficient_linear)
            << (r.coefficient_linear.factorizations == 0
                    ? (krylov ? " (with its preconditioner)" : " (with its factorisation)")
                    : "")
            << "\n"
            << "  time: solve " << r.solve_time << " s, coefficients " << r.coefficient_time
            << " s, error estimate " << r.error_estimate_time << " s\n";
}

nlohmann::json run(ParameterHandler &prm, const std::string &, MPI_Comm comm)
{
  FilmSettings film_settings;
  film_settings.parse_parameters(prm);
  film_settings.geometry.validate();
  film_settings.conditions.validate();
  CoefficientSettings coefficient_settings;
  coefficient_settings.parse_parameters(prm);
  CoefficientSolver solver(film_settings, coefficient_settings, comm);

  const CoefficientResult r = solver.compute();
  nlohmann::json summary = r.to_json();
  summary["narrow_seal_reference"] =
      narrow_seal_reference(film_settings.geometry, film_settings.conditions);
  if (Utilities::MPI::this_mpi_process(comm) == 0)
  {
    print_headline(r);
    if (!r.has_error_estimate && film_settings.estimate_error)
      std::cerr << "sealfe: warning: no error estimate: " << r.no_error_estimate_reason
                << std::endl;
    if (r.has_error_estimate && r.load_estimate.contains("warning"))
      std::cerr << "sealfe: warning: " << r.load_estimate["warning"].get<std::string>()
                << std::endl;
    if (r.has_error_estimate && r.coefficients_warning)
      std::cerr << "sealfe: warning: the error estimate of some stiffness or damping entries is "
                   "not in the asymptotic range (error_estimate/coefficients_grid_convergence): "
                   "it is widened (Fs = 3) and may not bound the error; refine the mesh"
                << std::endl;
  }
  return summary;
}
} // namespace

SubCommand coefficients_command()
{
  return {"coefficients",
          "film stiffness and damping about the operating point -> summary.json",
          /*face_seal=*/true,
          /*distributed=*/true,
          CoefficientSolver::declare_parameters,
          run};
}
} // namespace sealfe::applications
