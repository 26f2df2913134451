#include <sealfe/annular/annular_seal.h>
#include <sealfe/applications/application.h>
#include <sealfe/applications/response.h>
#include <sealfe/applications/stability.h>
#include <sealfe/applications/table_sweep.h>
#include <sealfe/applications/transient.h>
#include <sealfe/closed_form/narrow_seal.h>
#include <sealfe/coefficients/coefficient_solver.h>
#include <sealfe/dynamics/seal_dynamics.h>
#include <sealfe/film/film_settings.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/operating_conditions.h>
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/io/output.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace sealfe
{
using namespace dealii;

namespace
{
/// One sub-command: its parameters and what it does. `distributed` sub-commands run on every MPI
/// rank (finite-element solves); the others run on rank 0 only.
struct SubCommand
{
  std::string name;
  std::string purpose;
  bool face_seal; // declares the shared Geometry / Operating conditions subsections
  bool distributed;
  std::function<void(ParameterHandler &)> declare;
  std::function<nlohmann::json(ParameterHandler &, const std::string &, MPI_Comm)> run;
};

/// Level 2 of the film for `sealfe stability` and `sealfe response` (Seal dynamics/Film model =
/// finite element): the coefficient solver of the prm's Discretization, Cavitation, Roughness and
/// Coefficients subsections. These sub-commands run on rank 0 only, so the solver works on
/// MPI_COMM_SELF. Empty for the other film models (their prm needs no FE settings).
FilmCoefficientProvider finite_element_film(ParameterHandler &prm)
{
  prm.enter_subsection("Seal dynamics");
  const bool wanted = prm.get("Film model") == "finite element";
  prm.leave_subsection();
  if (!wanted)
    return {};
  auto solver = std::make_shared<CoefficientSolver>(MPI_COMM_SELF);
  solver->parse_parameters(prm);
  auto count = std::make_shared<unsigned int>(0);
  return [solver, count](const FilmThickness &film, const OperatingConditions &conditions)
  {
    const auto start = std::chrono::steady_clock::now();
    FilmCoefficients k = solver->coefficients(film, conditions);
    std::ostringstream model;
    model << k.model << ", " << solver->reynolds().n_dofs() << " dofs, degree "
          << solver->reynolds().degree();
    k.model = model.str();
    std::cerr << "sealfe: level-2 film coefficients #" << ++*count << " at rotor speed "
              << conditions.rotor_speed << ", stator speed " << conditions.stator_speed
              << " rad/s (" << solver->reynolds().n_dofs() << " dofs, "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
              << " s)" << std::endl;
    return k;
  };
}

std::vector<SubCommand> sub_commands()
{
  return {
      {"solve", "pressure field, loads, leakage -> summary.json, VTU/PVD", true, true,
       solve::declare_parameters, solve::run},
      {"coefficients", "film stiffness and damping about the operating point -> summary.json", true,
       true, coefficients::declare_parameters, coefficients::run},
      {"table", "coefficients and loads over a grid of operating points -> CSV", true, true,
       table::declare_parameters, table::run},
      {"stability", "linear stability, eigenvalues and threshold speeds -> summary.json, CSV", true,
       false,
       [](ParameterHandler &prm)
       {
         stability::declare_parameters(prm);
         CoefficientSolver::declare_parameters(prm); // Film model = finite element
       },
       [](ParameterHandler &prm, const std::string &dir, MPI_Comm)
       {
         output::make_directory(dir);
         return stability::run(prm, dir, finite_element_film(prm));
       }},
      {"response", "steady-state forced response over a speed range -> CSV, PNG", true, false,
       [](ParameterHandler &prm)
       {
         response::declare_parameters(prm);
         CoefficientSolver::declare_parameters(prm); // Film model = finite element
       },
       [](ParameterHandler &prm, const std::string &dir, MPI_Comm)
       {
         output::make_directory(dir);
         return response::run(prm, dir, finite_element_film(prm));
       }},
      {"annular", "annular (radial-clearance) seal stiffness, leakage, optimum -> JSON, CSV", false,
       false, annular::declare_parameters,
       [](ParameterHandler &prm, const std::string &dir, MPI_Comm)
       {
         output::make_directory(dir);
         return annular::run(prm, dir);
       }},
      {"equilibrium", "axial operating point under the closing force -> summary.json", true, false,
       equilibrium::declare_parameters,
       [](ParameterHandler &prm, const std::string &dir, MPI_Comm)
       { return equilibrium::run(prm, dir); }},
      {"transient", "start-up/run/shut-down transient (Green 2002) -> CSV, PNG", true, false,
       transient::declare_parameters,
       [](ParameterHandler &prm, const std::string &dir, MPI_Comm)
       { return transient::run(prm, dir); }},
  };
}

void declare_common(ParameterHandler &prm, const SubCommand &command)
{
  prm.declare_entry("Output directory", "sealfe-output", Patterns::Anything(),
                    "Directory for summary.json, used_parameters.prm and the field/table files "
                    "(created if needed).");
  if (command.face_seal)
  {
    FilmThickness::declare_parameters(prm);
    OperatingConditions::declare_parameters(prm);
  }
  command.declare(prm);
}

/// deal.II exceptions carry a multi-line report; keep the "additional information" on one line.
std::string one_line(const std::exception &e)
{
  std::string text;
  if (const auto *d = dynamic_cast<const ExceptionBase *>(&e))
  {
    std::ostringstream s;
    d->print_info(s);
    text = s.str();
  }
  else
    text = e.what();
  std::string line;
  bool space = false;
  for (const char c : text)
  {
    if (std::isspace(static_cast<unsigned char>(c)))
      space = !line.empty();
    else
    {
      if (space)
        line += ' ';
      line += c;
      space = false;
    }
  }
  return line;
}

/// deal.II mangles entry names in its JSON output (non-alphanumerics as _XX hex).
std::string demangle(const std::string &s)
{
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i] == '_' && i + 2 < s.size() + 0 && std::isxdigit(s[i + 1]) && std::isxdigit(s[i + 2]))
    {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    }
    else
      out += s[i];
  return out;
}

/// `--print-parameters`: every entry in prm syntax with its default value, pattern and
/// documentation (deal.II's own styles print either the defaults or the patterns, not both).
void print_parameters(const ParameterHandler &prm, std::ostream &out)
{
  std::ostringstream json_text;
  prm.print_parameters(json_text, ParameterHandler::JSON);
  const auto json = nlohmann::json::parse(json_text.str());
  std::function<void(const nlohmann::json &, const std::string &)> print =
      [&](const nlohmann::json &node, const std::string &indent)
  {
    for (const auto &[key, value] : node.items()) // entries first, then subsections
      if (value.contains("value"))
      {
        out << indent << "# " << value.value("documentation", std::string()) << "\n"
            << indent << "#   default: " << value.value("default_value", std::string())
            << "   pattern: " << value.value("pattern_description", std::string()) << "\n"
            << indent << "set " << demangle(key) << " = "
            << value.value("default_value", std::string()) << "\n\n";
      }
    for (const auto &[key, value] : node.items())
      if (!value.contains("value"))
      {
        out << indent << "subsection " << demangle(key) << "\n";
        print(value, indent + "  ");
        out << indent << "end\n\n";
      }
  };
  print(json, "");
}

void print_usage(std::ostream &out)
{
  out << "usage: sealfe <sub-command> [file.prm]\n"
         "       sealfe --print-parameters [sub-command]\n\nsub-commands:\n";
  for (const auto &c : sub_commands())
    out << "  " << std::left << std::setw(14) << c.name << c.purpose << "\n";
}
} // namespace

int run_application(int argc, char **argv)
{
  const MPI_Comm comm = MPI_COMM_WORLD;
  const bool root = Utilities::MPI::this_mpi_process(comm) == 0;
  const std::vector<std::string> args(argv + 1, argv + argc);
  try
  {
    if (args.empty() || args[0] == "--help" || args[0] == "-h")
    {
      if (root)
        print_usage(args.empty() ? std::cerr : std::cout);
      return args.empty() ? 2 : 0;
    }
    const auto commands = sub_commands();
    auto find = [&](const std::string &name) -> const SubCommand &
    {
      for (const auto &c : commands)
        if (c.name == name)
          return c;
      throw std::runtime_error("unknown sub-command '" + name + "' (see sealfe --help)");
    };

    if (args[0] == "--print-parameters")
    {
      const SubCommand &command = find(args.size() > 1 ? args[1] : "solve");
      ParameterHandler prm;
      declare_common(prm, command);
      if (root)
        print_parameters(prm, std::cout);
      return 0;
    }

    const SubCommand &command = find(args[0]);
    if (args.size() > 2)
      throw std::runtime_error("too many arguments (usage: sealfe " + command.name +
                               " [file.prm])");
    const auto start = std::chrono::steady_clock::now();
    ParameterHandler prm;
    declare_common(prm, command);
    if (args.size() == 2)
    {
      const std::string &file = args[1];
      std::ifstream probe(file);
      if (!probe)
        throw std::runtime_error("parameter file '" + file + "' is missing or unreadable");
      try
      {
        prm.parse_input(file, "", /*skip_undefined=*/false, /*assert_mandatory=*/false);
      }
      catch (std::exception &e)
      {
        throw std::runtime_error("parameter file '" + file + "': " + one_line(e));
      }
    }
    const std::string directory = prm.get("Output directory");

    nlohmann::json summary;
    if (command.distributed || root)
      summary = command.run(prm, directory, comm);
    if (root)
    {
      output::make_directory(directory);
      summary["sub_command"] = command.name;
      summary["mpi_ranks"] = Utilities::MPI::n_mpi_processes(comm);
      summary["wall_time"] =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      output::write_used_parameters(directory, prm);
      output::write_summary(directory, summary);
      std::cout << "sealfe " << command.name << ": wrote " << directory << "/summary.json and "
                << directory << "/used_parameters.prm\n";
    }
    return 0;
  }
  catch (std::exception &e)
  {
    if (root)
      std::cerr << "sealfe: error: " << one_line(e) << std::endl;
    return 1;
  }
}

// ------------------------------------------------------------------------------------------------
// sealfe solve

namespace solve
{
void declare_parameters(ParameterHandler &prm)
{
  prm.enter_subsection("Film model");
  prm.declare_entry("Model", "finite element", Patterns::Selection("finite element|narrow seal"),
                    "finite element: full 2D Reynolds solve on the annulus (level 2). narrow "
                    "seal: the closed-form narrow-seal pressure (level 0, ri/ro -> 1).");
  prm.leave_subsection();
  prm.enter_subsection("Output");
  prm.declare_entry("Write fields", "true", Patterns::Bool(),
                    "Write pressure, film thickness and volume flux as VTU/PVD (FE model).");
  prm.leave_subsection();
  FilmSettings::declare_solver_parameters(prm); // Geometry, Operating conditions: declare_common
  NarrowSealQuadrature::declare_parameters(prm);
}

nlohmann::json run(ParameterHandler &prm, const std::string &directory, MPI_Comm comm)
{
  // Everything the film solvers need, parsed once.
  FilmSettings settings;
  settings.parse_parameters(prm);
  const FilmThickness &film = settings.geometry;
  const OperatingConditions &conditions = settings.conditions;
  conditions.validate(); // the film is validated by the model (touch-down may be allowed)
  prm.enter_subsection("Film model");
  const std::string model = prm.get("Model");
  prm.leave_subsection();
  prm.enter_subsection("Output");
  const bool write_fields = prm.get_bool("Write fields");
  prm.leave_subsection();

  const bool root = Utilities::MPI::this_mpi_process(comm) == 0;
  nlohmann::json summary;
  if (model == "narrow seal")
  {
    const CavitationSettings &cavitation = settings.cavitation;
    NarrowSealQuadrature quadrature;
    quadrature.parse_parameters(prm);
    Timer t;
    const FilmLoads loads =
        compute(film, conditions, cavitation.model, quadrature, cavitation.pressure);
    summary = loads.to_json();
    summary["model"] = "narrow seal";
    summary["dofs"] = 0;
    summary["leakage_imbalance"] = loads.leakage_inner + loads.leakage_outer;
    summary["error_estimate"] = {
        {"method", "none: closed-form model; its modelling error against the full Reynolds "
                   "equation grows like (1 - ri/ro)^2 (doc/narrow_seal.md)"}};
    summary["stage_wall_time"] = {{"narrow_seal", t.wall_time()}};
    if (root)
      std::cout << std::setprecision(6) << "sealfe solve (narrow seal)\n"
                << "  force_z            " << loads.force_z << " N\n"
                << "  moment_x, moment_y " << loads.moment_x << ", " << loads.moment_y << " N m\n"
                << "  leakage in / out   " << loads.leakage_inner << ", " << loads.leakage_outer
                << " m^3/s\n"
                << "  friction torque    " << loads.friction_torque << " N m\n";
    return summary;
  }

  ReynoldsSolver solver(settings, comm);
  // Inputs are checked before any mesh file is read or output is touched.
  const FilmLoads loads = solver.run();
  summary = loads.to_json();
  summary["model"] = "finite element";
  summary["dofs"] = solver.n_dofs();
  summary["polynomial_degree"] = solver.degree();
  summary["linear_iterations"] = solver.linear_iterations();
  summary["leakage_imbalance"] = loads.leakage_inner + loads.leakage_outer;
  // Discrete mass balance: what leaves through the two circles plus the squeeze flow, relative
  // to the larger leakage (zero to solver tolerance for none and jfo).
  summary["mass_balance_residual"] =
      std::abs(loads.leakage_inner + loads.leakage_outer + loads.squeeze_flow) /
      std::max({std::abs(loads.leakage_inner), std::abs(loads.leakage_outer), 1e-300});
  {
    const char *names[] = {"none", "half-sommerfeld", "reynolds", "jfo"};
    summary["cavitation"] = {{"model", names[static_cast<int>(solver.cavitation.model)]},
                             {"cavitation_pressure", solver.cavitation.pressure},
                             {"nonlinear_iterations", solver.nonlinear_iterations()},
                             {"coarse_level_iterations", solver.coarse_nonlinear_iterations()},
                             {"final_residual", solver.nonlinear_residual()}};
  }
  summary["roughness"] = {{"model", solver.flow_factors.is_smooth() ? "none" : "patir-cheng"},
                          {"composite_roughness", solver.flow_factors.composite_roughness()},
                          {"clamped_evaluations", solver.flow_factors.clamp_count()},
                          {"contact_model", solver.contact.enabled() ? "gw-ceb" : "none"}};
  nlohmann::json timings = solver.stage_times();

  // Error estimate: a second solve on a mesh twice as coarse (estimate_load_errors).
  nlohmann::json estimate;
  if (solver.error_estimate_enabled() && solver.mesh().can_coarsen(1))
  {
    // A copy of the whole settings, on the mesh twice as coarse.
    ReynoldsSolver coarse(settings, comm);
    const FilmLoads c = coarse.run(1);
    const FilmLoads e = estimate_load_errors(loads, c, solver.degree());
    estimate = {{"force_z", e.force_z},
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
    timings["error_estimate"] = 0.0;
    for (const auto &[k, v] : coarse.stage_times())
      timings["error_estimate"] = timings["error_estimate"].get<double>() + v;
  }
  else
    estimate = {{"method", "none: disabled or the mesh cannot be coarsened"}};
  summary["error_estimate"] = estimate;

  if (write_fields)
  {
    if (root)
      output::make_directory(directory);
    MPI_Barrier(comm);
    Timer t;
    summary["fields"] = solver.write_output(directory);
    timings["output"] = t.wall_time();
  }
  summary["stage_wall_time"] = timings;

  if (root)
  {
    std::cout << std::setprecision(6) << "sealfe solve (finite element, " << solver.n_dofs()
              << " dofs, degree " << solver.degree() << ")\n"
              << "  force_z            " << loads.force_z << " N\n"
              << "  moment_x, moment_y " << loads.moment_x << ", " << loads.moment_y << " N m\n"
              << "  leakage in / out   " << loads.leakage_inner << ", " << loads.leakage_outer
              << " m^3/s\n"
              << "  friction torque    " << loads.friction_torque << " N m\n"
              << "  min film           " << loads.min_film << " m\n";
    if (write_fields)
      std::cout << "  fields             " << directory << "/solution.pvd\n";
  }
  return summary;
}
} // namespace solve

} // namespace sealfe
