#include <sealfe/dynamics/seal_dynamics_input.h>
#include <sealfe/film/surface_features.h>

#include <deal.II/base/mpi.h>

#include <algorithm>

#include <cmath>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
void SealDynamicsInput::declare_parameters(dealii::ParameterHandler &prm)
{
  // Defaults: Varney & Green (Varney & Green (2017)) Table 2 with delta = I_tr/I_pr = 2, chi = 0.5
  // mrad.
  RingProperties rotor_default, stator_default;
  rotor_default.transverse_inertia = 0.2;
  rotor_default.polar_inertia = 0.1;
  rotor_default.support_stiffness = 5e5;
  rotor_default.support_damping = 20;
  rotor_default.rotating_damping = 1;
  rotor_default.dynamic_misalignment = 0.5e-3;
  stator_default.transverse_inertia = 1.7e-3;
  stator_default.polar_inertia = 3.4e-3;
  stator_default.support_stiffness = 363.9;
  stator_default.support_damping = 0.22;
  prm.enter_subsection("Seal dynamics");
  prm.declare_entry("Configuration", "FMS with flexible rotor",
                    dealii::Patterns::Selection("FMS|FMR|FMRR|FMS with flexible rotor"),
                    "Which rings are flexibly mounted. FMS: flexible stator, rigid rotor; FMR: "
                    "rigid stator, flexible rotor; FMRR: both flexible, both may spin (speeds "
                    "from Operating conditions); FMS with flexible rotor: FMRR equations with a "
                    "non-spinning stator and the shaft + seat as the rotor ring.");
  prm.declare_entry("Film model", to_string(FilmLevel::closed_form),
                    dealii::Patterns::Selection(film_level_pattern()),
                    "Film stiffness and damping. closed form = level 0: Green & Etsion narrow "
                    "seal (k11, d11, (omega1 + omega2)/2 d11), untilted coned face, full film. "
                    "table = level 1: interpolated from the CSV of `sealfe table` (Table file). "
                    "finite element = level 2: the FE Reynolds solve linearised about the "
                    "Geometry as given (subsections Discretization, Cavitation, Roughness, "
                    "Coefficients), at Film speed nodes speeds of a sweep.");
  prm.declare_entry("Table file", "", dealii::Patterns::Anything(),
                    "Film model = table only: the coefficient table (CSV of `sealfe table`), "
                    "relative to the working directory. It must hold this seal (every quantity "
                    "it did not sweep equal to the Geometry and Operating conditions here) and "
                    "cover the swept speeds: the film depends on the ring speeds through their "
                    "mean only, so a table over the rotor speed (stator at 0) serves an FMRR "
                    "sweep if its rotor speeds cover rotor speed + stator speed.");
  prm.declare_entry("Table interpolation", "cubic", dealii::Patterns::Selection("cubic|linear"),
                    "Film model = table only: cubic Lagrange on 4 nodes per axis (O(h^4)) or "
                    "multilinear (O(h^2)).");
  prm.declare_entry("Film speed nodes", "9", dealii::Patterns::Integer(0),
                    "Film model = finite element only: for a speed sweep the FE coefficients are "
                    "computed at this many equally spaced speeds of the swept ring over the "
                    "sweep and interpolated in between (cubic Lagrange; exact in full film, "
                    "where K is affine in the mean speed and D does not depend on it). 0: an FE "
                    "computation at every speed the sweep evaluates (hundreds or thousands). 1 "
                    "is not allowed.");
  declare_ring_parameters(prm, "Rotor ring", rotor_default,
                          "ring spinning at Operating conditions/Rotor speed");
  declare_ring_parameters(prm, "Stator ring", stator_default,
                          "ring spinning at Operating conditions/Stator speed (0 for a stator)");
  prm.leave_subsection();
}

void SealDynamicsInput::parse_parameters(dealii::ParameterHandler &prm)
{
  geometry.parse_parameters(prm);
  operating.parse_parameters(prm);
  prm.enter_subsection("Seal dynamics");
  configuration = configuration_from_string(prm.get("Configuration"));
  film_level = film_level_from_string(prm.get("Film model"));
  table_file = prm.get("Table file");
  table_interpolation = prm.get("Table interpolation");
  film_speed_nodes = prm.get_integer("Film speed nodes");
  rotor = parse_ring_parameters(prm, "Rotor ring");
  stator = parse_ring_parameters(prm, "Stator ring");
  prm.leave_subsection();
  if (film_level == FilmLevel::finite_element)
    try
    {
      film_solver.parse_solver_parameters(prm);
      coefficient_method.parse_parameters(prm);
    }
    catch (const dealii::ExceptionBase &)
    {
      throw std::runtime_error(
          "Seal dynamics: Film model = finite element needs the finite-element solver's "
          "parameters (subsections Discretization, Cavitation, Roughness, Contact, Coefficients: "
          "CoefficientSolver::declare_parameters)");
    }
}

void SealDynamicsInput::validate() const
{
  geometry.validate();
  operating.validate();
  if (configuration == SealConfiguration::fms_flexible_rotor && operating.stator_speed != 0.0)
  {
    std::ostringstream s;
    s << "Seal dynamics: Configuration = FMS with flexible rotor needs Operating conditions/"
      << "Stator speed = 0 (got " << operating.stator_speed << " rad/s); use FMRR";
    throw std::runtime_error(s.str());
  }
  if (configuration == SealConfiguration::fms && operating.stator_speed != 0.0)
  {
    std::ostringstream s;
    s << "Seal dynamics: Configuration = FMS has a non-spinning stator: Operating conditions/"
      << "Stator speed must be 0 (got " << operating.stator_speed << " rad/s)";
    throw std::runtime_error(s.str());
  }
  // Rotor-borne features turn relative to the stator; the linear studies hold the film's
  // coefficients at rotor angle 0 (Phase). Exact when N >= 3 identical features sit on an
  // axisymmetric film (K, D commute with the turn by 2 pi / N, so they do with every turn);
  // otherwise the coefficients are periodic in time and the study is of the snapshot.
  if (geometry.features_on_rotor() && (geometry.tilt != 0 || geometry.wave_amplitude != 0 ||
                                       geometry.expression || geometry.features->count() < 3))
  {
    // once per process and on rank 0 only: validate() runs once per swept value and per rank
    static bool warned = false;
    if (!warned && dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      std::cerr << "sealfe: warning: the rotor's surface features turn over a film that is not "
                   "axisymmetric (tilt, waviness, a film formula) or number fewer than 3: the "
                   "coefficients depend on the rotor angle; the linear study takes those at "
                   "Phase (doc/textures.md, Which frame)\n";
    warned = true;
  }
  // Level 0 checks the narrow seal, level 1 reads the table and checks that it holds this seal,
  // level 2 builds the solver (no FE solve).
  film_force_model();
  if (film_level == FilmLevel::finite_element)
  {
    if (film_speed_nodes == 1)
      throw std::runtime_error("Seal dynamics: Film speed nodes must be 0 (an FE computation at "
                               "every speed) or at least 2 (got 1)");
  }
  AngularSealDynamics(configuration, rotor, stator, FilmModel()).validate();
}

std::shared_ptr<const CoefficientTable> SealDynamicsInput::table() const
{
  if (table_file.empty())
    throw std::runtime_error("Seal dynamics: Film model = table needs a Table file (the CSV "
                             "written by sealfe table)");
  return tables.get(
      table_file + "\n" + table_interpolation,
      [&]
      {
        try
        {
          return std::make_shared<const CoefficientTable>(
              table_file, table_interpolation == "linear" ? CoefficientTable::Interpolation::linear
                                                          : CoefficientTable::Interpolation::cubic);
        }
        catch (const std::exception &e)
        {
          throw std::runtime_error(std::string("Seal dynamics: Table file: ") + e.what());
        }
      });
}

std::shared_ptr<const FilmForceModel> SealDynamicsInput::film_force_model() const
{
  FilmLevelSources sources;
  sources.film_solver = film_solver;
  sources.coefficient_method = coefficient_method;
  sources.table_name = table_file;
  if (film_level != FilmLevel::table)
    return make_film_force_model(film_level, geometry, operating, sources);
  sources.table = table();
  try
  {
    return make_film_force_model(film_level, geometry, operating, sources);
  }
  catch (const std::exception &e)
  {
    const std::string what = e.what();
    throw std::runtime_error(
        what.rfind("Seal dynamics:", 0) == 0 ? what : "Seal dynamics: Film model = table: " + what);
  }
}

FilmModel SealDynamicsInput::film() const
{
  FilmModel exact =
      coefficients_at_speeds(film_force_model(), FilmState::from(geometry, operating));
  if (film_level != FilmLevel::table)
    return exact;
  // Level 1: errors during the lookups say that they come from the table.
  return [exact](const double rotor_speed, const double stator_speed)
  {
    try
    {
      return exact(rotor_speed, stator_speed);
    }
    catch (const std::exception &e)
    {
      const std::string what = e.what();
      throw std::runtime_error(what.rfind("Seal dynamics:", 0) == 0
                                   ? what
                                   : "Seal dynamics: Film model = table: " + what);
    }
  };
}

SweepFilm SealDynamicsInput::sweep_film(const AngularSealDynamics::SweptRing swept,
                                        const double fixed_speed, const double from,
                                        const double to) const
{
  const bool swept_rotor = swept == AngularSealDynamics::SweptRing::rotor;
  SweepFilm s;
  s.model = film();
  if (film_level == FilmLevel::closed_form)
    s.description = {{"method",
                      "closed form (level 0) at every speed: k11 and d11 do not depend "
                      "on speed, the cross-coupled stiffness is (omega1 + omega2)/2 d11"}};
  else if (film_level == FilmLevel::table)
  {
    // Fail before the sweep, with the sweep named, if it leaves the table.
    for (const double w : {from, to})
      try
      {
        s.model(swept_rotor ? w : fixed_speed, swept_rotor ? fixed_speed : w);
      }
      catch (const std::exception &e)
      {
        std::ostringstream m;
        m << "Seal dynamics: Film model = table: the sweep of the "
          << (swept_rotor ? "rotor" : "stator") << " speed over [" << from << ", " << to
          << "] rad/s (other ring at " << fixed_speed << " rad/s) leaves the table: " << e.what();
        throw std::runtime_error(m.str());
      }
    s.description = {{"method", "table lookup (level 1) at every speed, interpolated by the "
                                "table in the mean speed and its other axes"},
                     {"table", table_file},
                     {"interpolation", table_interpolation},
                     {"table_axes", table()->axes()}};
  }
  else if (film_speed_nodes == 0)
    s.description = {{"method", "finite element (level 2) at every speed the sweep evaluates"}};
  else
  {
    auto interpolation = std::make_shared<SpeedInterpolatedFilm>(s.model, swept, fixed_speed, from,
                                                                 to, film_speed_nodes);
    s.interpolation = interpolation;
    s.model = [interpolation](const double rotor_speed, const double stator_speed)
    { return (*interpolation)(rotor_speed, stator_speed); };
    s.description = interpolation->to_json();
  }
  return s;
}

AngularSealDynamics SealDynamicsInput::build() const
{
  return build(film());
}

AngularSealDynamics SealDynamicsInput::build(FilmModel film_model) const
{
  return AngularSealDynamics(configuration, rotor, stator, std::move(film_model));
}

double SealDynamicsInput::contact_tilt() const
{
  const double ri = geometry.inner_radius, ro = geometry.outer_radius, C0 = geometry.clearance;
  return std::min(C0 / ri, (C0 + geometry.coning * (ro - ri)) / ro);
}

std::string SealDynamicsInput::parameter_names()
{
  return "Clearance|Coning|Inner radius|Outer radius|Inner pressure|Outer pressure|Viscosity|"
         "Rotor speed|Stator speed|"
         "Rotor ring transverse inertia|Rotor ring polar inertia|Rotor ring support stiffness|"
         "Rotor ring support damping|Rotor ring rotating damping|"
         "Stator ring transverse inertia|Stator ring polar inertia|"
         "Stator ring support stiffness|Stator ring support damping|"
         "Stator ring rotating damping";
}

void SealDynamicsInput::set(const std::string &name, const double value,
                            const bool hold_normalized_coning)
{
  auto ring = [&](RingProperties &r, const std::string &what)
  {
    if (what == "transverse inertia")
      r.transverse_inertia = value;
    else if (what == "polar inertia")
      r.polar_inertia = value;
    else if (what == "support stiffness")
      r.support_stiffness = value;
    else if (what == "support damping")
      r.support_damping = value;
    else if (what == "rotating damping")
      r.rotating_damping = value;
    else
      return false;
    return true;
  };
  const auto &film_names = FilmSettings::settable_names();
  if (std::find(film_names.begin(), film_names.end(), name) != film_names.end())
  {
    // The film's quantities through the film's one name -> field map.
    if (name == "Clearance" && hold_normalized_coning)
      geometry.coning *= value / geometry.clearance;
    FilmSettings film = film_solver;
    film.geometry = geometry;
    film.conditions = operating;
    film.set(name, value);
    geometry = film.geometry;
    operating = film.conditions;
  }
  else if (!((name.rfind("Rotor ring ", 0) == 0 && ring(rotor, name.substr(11))) ||
             (name.rfind("Stator ring ", 0) == 0 && ring(stator, name.substr(12)))))
    throw std::runtime_error("Seal dynamics: unknown parameter '" + name + "' (one of " +
                             parameter_names() + ")");
}

double SealDynamicsInput::get(const std::string &name) const
{
  auto ring = [&](const RingProperties &r, const std::string &what)
  {
    if (what == "transverse inertia")
      return r.transverse_inertia;
    if (what == "polar inertia")
      return r.polar_inertia;
    if (what == "support stiffness")
      return r.support_stiffness;
    if (what == "support damping")
      return r.support_damping;
    if (what == "rotating damping")
      return r.rotating_damping;
    throw std::runtime_error("Seal dynamics: unknown parameter '" + name + "' (one of " +
                             parameter_names() + ")");
  };
  const auto &film_names = FilmSettings::settable_names();
  if (std::find(film_names.begin(), film_names.end(), name) != film_names.end())
  {
    FilmSettings film = film_solver;
    film.geometry = geometry;
    film.conditions = operating;
    return film.get(name);
  }
  if (name.rfind("Rotor ring ", 0) == 0)
    return ring(rotor, name.substr(11));
  if (name.rfind("Stator ring ", 0) == 0)
    return ring(stator, name.substr(12));
  throw std::runtime_error("Seal dynamics: unknown parameter '" + name + "' (one of " +
                           parameter_names() + ")");
}

void declare_speed_sweep(dealii::ParameterHandler &prm, const std::string &from,
                         const std::string &to, const std::string &points,
                         const std::string &points_documentation)
{
  prm.declare_entry("Speed from", from, dealii::Patterns::Double(),
                    "First (lowest) speed of the swept ring (rad/s).");
  prm.declare_entry("Speed to", to, dealii::Patterns::Double(),
                    "Last (highest) speed of the swept ring (rad/s).");
  prm.declare_entry("Speed points", points, dealii::Patterns::Integer(2), points_documentation);
}

} // namespace sealfe
