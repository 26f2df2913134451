// `sealfe solve`: pressure field, loads and leakage of one operating point, by the finite-element
// Reynolds solve (level 2, with an error estimate of the loads) or the narrow-seal closed form
// (level 0).
#include "driver.h"

#include <sealfe/closed_form/narrow_seal.h>
#include <sealfe/film/film_force_model.h>
#include <sealfe/film/film_output.h>
#include <sealfe/film/film_settings.h>
#include <sealfe/film/film_summary.h>
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/io/output.h>

#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>

#include <iomanip>
#include <iostream>

namespace sealfe::applications
{
using namespace dealii;

namespace
{
void declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Film model");
  prm.declare_entry(
      "Model", to_string(FilmLevel::finite_element),
      Patterns::Selection(to_string(FilmLevel::closed_form) + "|" +
                          to_string(FilmLevel::finite_element) + "|narrow seal"),
      "The film level (the names of Seal dynamics/Film model). finite element: full 2D Reynolds "
      "solve on the annulus (level 2). closed form: the narrow-seal pressure (level 0, ri/ro -> "
      "1). narrow seal: the former name of closed form, still accepted.");
  prm.leave_subsection();
  prm.enter_subsection("Output");
  prm.declare_entry("Write fields", "true", Patterns::Bool(),
                    "Write the film's fields as VTU/PVD (FE model); which ones: Fields.");
  FieldSelection::declare_parameters(prm);
  prm.leave_subsection();
  FilmSettings::declare_solver_parameters(prm); // Geometry, Operating conditions: the driver
  NarrowSealQuadrature::declare_parameters(prm);
}

/// The loads of `summary`, each with its discretisation error estimate beside it, and shown as 0
/// when below its round-off bound (film_summary.h, load_with_uncertainty).
void print_loads(const nlohmann::json &summary)
{
  std::cout << "  force_z              " << load_with_uncertainty(summary, "force_z", "N") << "\n"
            << "  moment_x             " << load_with_uncertainty(summary, "moment_x", "N m")
            << "\n"
            << "  moment_y             " << load_with_uncertainty(summary, "moment_y", "N m")
            << "\n"
            << "  leakage inner circle " << load_with_uncertainty(summary, "leakage_inner", "m^3/s")
            << "\n"
            << "  leakage outer circle " << load_with_uncertainty(summary, "leakage_outer", "m^3/s")
            << "\n                       (leakage: positive out of the film through that circle)\n"
            << "  friction torque      " << load_with_uncertainty(summary, "friction_torque", "N m")
            << "\n";
}

/// Level 0: the closed-form loads of the narrow seal.
nlohmann::json solve_closed_form(ParameterHandler &prm, const FilmSettings &settings,
                                 const bool root)
{
  NarrowSealQuadrature quadrature;
  quadrature.parse_parameters(prm);
  Timer t;
  const FilmLoads loads = compute(settings.geometry, settings.conditions, settings.cavitation.model,
                                  quadrature, settings.cavitation.pressure);
  nlohmann::json summary = loads.to_json();
  summary["model"] = "narrow seal";
  summary["dofs"] = 0;
  summary["leakage_imbalance"] = loads.leakage_inner + loads.leakage_outer;
  summary["error_estimate"] = {
      {"method", "none: closed-form model; its modelling error against the full Reynolds "
                 "equation grows like (1 - ri/ro)^2 (doc/narrow_seal.md)"}};
  summary["stage_wall_time"] = {{"narrow_seal", t.wall_time()}};
  if (root)
  {
    std::cout << std::setprecision(6) << "sealfe solve (narrow seal)\n";
    print_loads(summary);
  }
  return summary;
}

nlohmann::json run(ParameterHandler &prm, const std::string &directory, MPI_Comm comm)
{
  FilmSettings settings; // everything the film solvers need, parsed once
  settings.parse_parameters(prm);
  settings.conditions.validate(); // the film is validated by the model (touch-down may be allowed)
  prm.enter_subsection("Film model");
  const std::string model = prm.get("Model");
  prm.leave_subsection();
  prm.enter_subsection("Output");
  const bool write_fields = prm.get_bool("Write fields");
  FieldSelection fields;
  fields.parse_parameters(prm);
  prm.leave_subsection();
  const bool root = Utilities::MPI::this_mpi_process(comm) == 0;
  if (model != to_string(FilmLevel::finite_element))
    return solve_closed_form(prm, settings, root);
  if (write_fields)
    fields.check_against(settings); // before the solve: a bad list costs nothing

  ReynoldsSolver solver(settings, comm);
  // Inputs are checked before any mesh file is read or output is touched.
  const FilmLoads loads = solver.run();
  nlohmann::json summary = finite_element_solve_summary(settings, solver, loads, comm);
  if (write_fields)
  {
    if (root)
      output::make_directory(directory);
    MPI_Barrier(comm);
    Timer t;
    summary["fields"] = write_film_output(solver, directory, fields);
    summary["stage_wall_time"]["output"] = t.wall_time();
  }
  if (root)
  {
    std::cout << std::setprecision(6) << "sealfe solve (finite element, " << solver.n_dofs()
              << " dofs, degree " << solver.degree() << ")\n";
    print_loads(summary);
    std::cout << "  min film             " << loads.min_film << " m\n";
    if (write_fields)
      std::cout << "  fields               " << directory << "/solution.pvd\n";
  }
  return summary;
}
} // namespace

SubCommand solve_command()
{
  return {"solve",
          "pressure field, loads, leakage -> summary.json, VTU/PVD",
          /*face_seal=*/true,
          /*distributed=*/true,
          declare_parameters,
          run};
}
} // namespace sealfe::applications
