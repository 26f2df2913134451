#include <sealfe/closed_form/narrow_seal.h>
#include <sealfe/closed_form/narrow_seal_film.h>
#include <sealfe/coefficients/finite_element_film.h>
#include <sealfe/dynamics/equilibrium.h>
#include <sealfe/dynamics/film_levels.h>
#include <sealfe/dynamics/transient_study.h>
#include <sealfe/film/cavitation.h>
#include <sealfe/film/film_output.h>
#include <sealfe/io/csv.h>
#include <sealfe/io/interrupt.h>
#include <sealfe/io/output.h>
#include <sealfe/io/python_plot.h>
#include <sealfe/numerics/number_lists.h>

#include <deal.II/base/data_out_base.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
namespace
{
/// Counts the evaluations of a film (the equilibrium's cost in summary.json).
class CountedFilm : public FilmForceModel
{
public:
  explicit CountedFilm(std::shared_ptr<const FilmForceModel> film) : film(std::move(film)) {}
  FilmLevel level() const override { return film->level(); }
  std::string description() const override { return film->description(); }
  FilmLoads loads(const FilmState &state) const override
  {
    ++count;
    return film->loads(state);
  }
  FilmCoefficients coefficients(const FilmState &state) const override
  {
    return film->coefficients(state);
  }
  bool turns_rotor_features() const override { return film->turns_rotor_features(); }
  unsigned long evaluations() const { return count; }

private:
  std::shared_ptr<const FilmForceModel> film;
  mutable unsigned long count = 0;
};

/// The film of the level the prm chooses (Transient/Film level): level 0 the narrow seal with the
/// prm's cavitation (none or half-Sommerfeld) and quadrature, level 1 a table of FE loads made
/// beforehand (Transient/Table file), level 2 an FE solve at each evaluation (any cavitation
/// model; the mesh and DoFs are built once and reused).
std::shared_ptr<const FilmForceModel> make_film(dealii::ParameterHandler &prm,
                                                const FlexibleStatorSeal &seal)
{
  prm.enter_subsection("Transient");
  const FilmLevel level = film_level_from_string(prm.get("Film level"));
  const std::string table_file = prm.get("Table file");
  const std::string interpolation = prm.get("Table interpolation");
  prm.leave_subsection();
  CavitationSettings cavitation;
  cavitation.parse_parameters(prm);
  if (level == FilmLevel::closed_form)
  {
    if (cavitation.is_nonlinear())
      throw std::runtime_error("Cavitation: the closed-form film (level 0) gives none or "
                               "half-sommerfeld only, not reynolds or jfo (use Transient/Film "
                               "level = finite element)");
    NarrowSealQuadrature quadrature;
    quadrature.parse_parameters(prm);
    return std::make_shared<NarrowSealFilm>(seal.geometry, seal.conditions, quadrature,
                                            cavitation.model, cavitation.pressure);
  }
  FilmLevelSources sources;
  if (level == FilmLevel::table)
  {
    if (table_file.empty())
      throw std::runtime_error("Transient: Film level = table needs Transient/Table file (the "
                               "CSV of `sealfe table` with load columns over the states the "
                               "transient visits)");
    try
    {
      sources.table = std::make_shared<const CoefficientTable>(
          table_file, interpolation == "linear" ? CoefficientTable::Interpolation::linear
                                                : CoefficientTable::Interpolation::cubic);
    }
    catch (const std::exception &e)
    {
      throw std::runtime_error(std::string("Transient: Table file: ") + e.what());
    }
    sources.table_name = table_file;
  }
  else
  {
    sources.film_solver.parse_solver_parameters(prm);
    sources.coefficient_method.parse_parameters(prm);
    if (sources.film_solver.contact.enabled())
      throw std::runtime_error("Contact/Model must be none for the transient's finite-element "
                               "film: Face contact adds the asperity contact with the local "
                               "film, the film's own would count it twice");
    // one FE solve per evaluation: the discretisation error is estimated once, not each time
    sources.film_solver.estimate_error = false;
  }
  return make_film_force_model(level, seal.geometry, seal.conditions, sources);
}

void declare_case(dealii::ParameterHandler &prm)
{
  // the finite-element film's subsections first: the transient's own defaults (Cavitation,
  // Contact via Face contact) are declared after them and win
  FilmSettings::declare_solver_parameters(prm);
  CoefficientSettings::declare_parameters(prm);
  FlexibleStatorSeal::declare_parameters(prm);
  TransientSettings::declare_parameters(prm);
  // the level-0 film of the transient needs only a coarse quadrature (smooth, mostly
  // uncavitated pressure); the narrow-seal defaults of `sealfe solve` are for 1e-10 accuracy
  prm.enter_subsection("Narrow seal");
  prm.declare_entry("Radial quadrature points", "8", dealii::Patterns::Integer(1),
                    "Gauss-Legendre points per radial piece of the narrow-seal loads.");
  prm.declare_entry("Angular quadrature points", "64", dealii::Patterns::Integer(4),
                    "Points around the face of the narrow-seal loads.");
  prm.leave_subsection();
}
} // namespace

namespace equilibrium
{
void declare_parameters(dealii::ParameterHandler &prm)
{
  declare_case(prm);
}

nlohmann::json run(dealii::ParameterHandler &prm, const std::string &)
{
  FlexibleStatorSeal seal;
  seal.parse_parameters(prm);
  seal.validate();
  const auto film = std::make_shared<CountedFilm>(make_film(prm, seal));
  FilmState state;
  state.rotor_speed = seal.conditions.rotor_speed;
  state.stator_speed = seal.conditions.stator_speed;
  state.inner_pressure = seal.conditions.inner_pressure;
  state.outer_pressure = seal.conditions.outer_pressure;
  SealEquilibrium eq = solve_equilibrium(seal, *film, state);

  // the tilts: the steady state of the transient's equations at these conditions held constant
  // (in the frame turning with the shaft under runout, the inertial one under a stator
  // misalignment), started from the axisymmetric balance
  FlexibleStatorSeal held = seal;
  held.ramps.speed = Ramp{state.rotor_speed, state.rotor_speed, 0, 1e300, 1e300};
  held.ramps.outer_pressure = Ramp{state.outer_pressure, state.outer_pressure, 0, 1e300, 1e300};
  held.ramps.inner_pressure = Ramp{state.inner_pressure, state.inner_pressure, 0, 1e300, 1e300};
  TransientSettings settings;
  settings.parse_parameters(prm);
  // no integration: the Transient subsection gives the frame; End time and Output interval are
  // set only so that the checks of an integration that does not happen cannot refuse the run
  settings.end_time = 1;
  settings.output_interval = 1;
  TransientState guess{};
  guess[0] = eq.axial_offset;
  guess[6] = eq.coning;
  const SteadyWhirl whirl = solve_steady_whirl(held, *film, settings, guess);
  const TransientState &y = whirl.state;
  const StatorTransient steady(held, *film, settings);
  state = steady.film_state(0, y);
  const TransientSample at = steady.sample(0, y);
  eq.axial_offset = y[0] - y[12]; // the gap's offset (stator less an axially flexible rotor)
  eq.coning = at.coning;
  eq.film = film->loads(state);
  eq.contact = seal.contact.loads(state.apply(seal.geometry));
  eq.support_force = -seal.stator.axial_stiffness * y[0];

  const FilmCoefficients k = central_difference_coefficients(*film, state, eq.contact.min_film,
                                                             seal.geometry.outer_radius);
  // contact stiffness: central difference of the contact force in z
  const double dz = 1e-3 * eq.contact.min_film;
  FilmState up = state, down = state;
  up.axial_offset += dz;
  down.axial_offset -= dz;
  const double kc = -(seal.contact.loads(up.apply(seal.geometry)).force -
                      seal.contact.loads(down.apply(seal.geometry)).force) /
                    (2 * dz);
  nlohmann::json s;
  s["clearance"] = seal.geometry.clearance + eq.axial_offset;
  s["axial_offset"] = eq.axial_offset;
  const double min_film = state.apply(seal.geometry).minimum().value;
  s["min_film"] = min_film;
  s["min_film_over_sigma"] = min_film / seal.contact.composite_roughness();
  s["coning"] = eq.coning;
  s["opening_force"] = eq.film.force_z;
  s["contact_force"] = eq.contact.force;
  s["support_force"] = eq.support_force;
  s["closing_force"] = eq.closing_force;
  s["leakage_inner"] = eq.film.leakage_inner;
  s["leakage_outer"] = eq.film.leakage_outer;
  s["friction_torque"] = eq.film.friction_torque;
  s["film_coefficients"] = k.to_json();
  s["stiffness"] = {{"axial_film", k.stiffness[0][0]},
                    {"axial_contact", kc},
                    {"axial_support", seal.stator.axial_stiffness},
                    {"axial_total", k.stiffness[0][0] + kc + seal.stator.axial_stiffness},
                    {"angular_film", k.tilt_direct_stiffness()},
                    {"cross_coupled_film", k.tilt_cross_stiffness()}};
  s["damping"] = {{"axial_film", k.damping[0][0]},
                  {"axial_support", seal.stator.axial_damping},
                  {"angular_film", k.tilt_direct_damping()}};
  s["roots_found"] = eq.roots_found;
  s["film_model"] = film->description();
  s["film_evaluations"] = film->evaluations();
  s["relative_tilt"] = at.relative_tilt;
  s["stator_tilt"] = at.stator_tilt();
  s["stator_tilt_x"] = at.stator_tilt_x;
  s["stator_tilt_y"] = at.stator_tilt_y;
  s["rotor_tilt"] = std::hypot(at.rotor_tilt_x, at.rotor_tilt_y);
  s["film_moment_x"] = at.film_moment_x;
  s["film_moment_y"] = at.film_moment_y;
  s["contact_moment_x"] = at.contact_moment_x;
  s["contact_moment_y"] = at.contact_moment_y;
  s["stator_axial_offset"] = y[0];
  s["rotor_axial_offset"] = y[12];
  s["tilt_newton_iterations"] = whirl.newton_iterations;
  s["tilt_continuation_steps"] = whirl.continuation_steps;
  s["tilts"] = "steady state of the transient's equations (tilts at t = 0, shaft angle 0; under "
               "runout the stator whirls with the shaft and these turn with it)";
  std::cout << "sealfe equilibrium: clearance " << seal.geometry.clearance + eq.axial_offset
            << " m, min film / sigma " << s["min_film_over_sigma"].get<double>() << ", coning "
            << eq.coning << " rad, relative tilt " << at.relative_tilt << " rad, leakage "
            << eq.film.leakage_inner << " m^3/s\n";
  return s;
}
} // namespace equilibrium
} // namespace sealfe

namespace sealfe
{
namespace transient
{
void declare_parameters(dealii::ParameterHandler &prm)
{
  declare_case(prm);
  prm.enter_subsection("Transient");
  prm.declare_entry("Plot", "true", dealii::Patterns::Bool(),
                    "Write transient.png (histories like Green 2002 Figs. 4-5) with "
                    "scripts/plot_transient.py, if python3 with matplotlib is found.");
  prm.declare_entry("Field output times", "", dealii::Patterns::Anything(),
                    "Film level = finite element: times (s, list or start : stop : count) at "
                    "which the film's fields (pressure, film thickness, liquid fraction) are "
                    "written, at the first output row at or after each; a time series "
                    "transient_fields.pvd for ParaView. Empty: none.");
  prm.leave_subsection();
}

namespace
{
std::string csv_text(const std::vector<TransientSample> &rows)
{
  const std::string none = csv::dimensionless;
  csv::Writer out({{"time", "s"},
                   {"rotor_speed", "rad/s"},
                   {"rotor_angle", "rad"},
                   {"inner_pressure", "Pa"},
                   {"outer_pressure", "Pa"},
                   {"axial_offset", "m"},
                   {"stator_tilt", "rad"},
                   {"stator_precession", "rad"},
                   {"relative_tilt", "rad"},
                   {"coning", "rad"},
                   {"min_film", "m"},
                   {"min_film_over_sigma", none},
                   {"heating_film", "m"},
                   {"film_force", "N"},
                   {"contact_force", "N"},
                   {"closing_force", "N"},
                   {"film_moment_x", "N m"},
                   {"film_moment_y", "N m"},
                   {"contact_moment_x", "N m"},
                   {"contact_moment_y", "N m"},
                   {"leakage_inner", "m^3/s"},
                   {"friction_torque", "N m"},
                   {"leaked_volume", "m^3"}});
  for (const auto &s : rows)
    out.add_row({s.time,           s.rotor_speed,     s.rotor_angle,      s.inner_pressure,
                 s.outer_pressure, s.axial_offset,    s.stator_tilt(),    s.stator_precession(),
                 s.relative_tilt,  s.coning,          s.min_film,         s.min_film_over_sigma,
                 s.heating_film,   s.film_force,      s.contact_force,    s.closing_force,
                 s.film_moment_x,  s.film_moment_y,   s.contact_moment_x, s.contact_moment_y,
                 s.leakage_inner,  s.friction_torque, s.leaked_volume});
  return out.text();
}

nlohmann::json sample_json(const TransientSample &s)
{
  return {{"time", s.time},
          {"rotor_speed", s.rotor_speed},
          {"axial_offset", s.axial_offset},
          {"stator_tilt", s.stator_tilt()},
          {"relative_tilt", s.relative_tilt},
          {"coning", s.coning},
          {"min_film", s.min_film},
          {"min_film_over_sigma", s.min_film_over_sigma},
          {"film_force", s.film_force},
          {"contact_force", s.contact_force},
          {"leakage_inner", s.leakage_inner},
          {"leaked_volume", s.leaked_volume}};
}

/// Lift-off / touch-down events (IDA's root finding), the largest contact force (over the output
/// rows) and the leaked volume.
nlohmann::json events(const StatorTransient::Result &result)
{
  const auto &rows = result.samples;
  nlohmann::json first_lift_off = nullptr, last_touch_down = nullptr;
  double max_contact = 0, t_max = 0;
  for (const auto &row : rows)
    if (row.contact_force > max_contact)
    {
      max_contact = row.contact_force;
      t_max = row.time;
    }
  nlohmann::json all = nlohmann::json::array();
  for (const auto &e : result.contact_events)
  {
    const nlohmann::json event = {{"time", e.time}, {"rotor_speed", e.rotor_speed}};
    all.push_back({{"time", e.time},
                   {"rotor_speed", e.rotor_speed},
                   {"event", e.lift_off ? "lift-off" : "touch-down"}});
    if (e.lift_off && first_lift_off.is_null())
      first_lift_off = event;
    if (!e.lift_off)
      last_touch_down = event;
  }
  return {{"contact_events", all},
          {"first_lift_off", first_lift_off},
          {"last_touch_down", last_touch_down},
          {"max_contact_force", max_contact},
          {"time_of_max_contact_force", t_max},
          {"leaked_volume", rows.empty() ? 0.0 : rows.back().leaked_volume}};
}

} // namespace

nlohmann::json run(dealii::ParameterHandler &prm, const std::string &dir)
{
  const auto start = std::chrono::steady_clock::now();
  FlexibleStatorSeal seal;
  seal.parse_parameters(prm);
  seal.validate();
  TransientSettings settings;
  settings.parse_parameters(prm);
  settings.validate();
  prm.enter_subsection("Transient");
  const bool want_plot = prm.get_bool("Plot");
  const std::vector<double> field_times =
      numerics::parse_number_list(prm.get("Field output times"), "Transient/Field output times");
  prm.leave_subsection();
  const auto film = make_film(prm, seal);

  StatorTransient transient(seal, *film, settings);
  // the fields of a level-2 film at the chosen times, written while the run goes on
  std::vector<std::pair<double, std::string>> field_records;
  std::size_t next_field = 0;
  if (!field_times.empty())
  {
    const auto fe = std::dynamic_pointer_cast<const FiniteElementFilm>(film);
    if (!fe)
      throw std::runtime_error("Transient: Field output times need Film level = finite element "
                               "(the closed form and the table have no fields)");
    output::make_directory(dir);
    transient.after_output = [&, fe](const double t)
    {
      if (next_field == field_times.size() || t < field_times[next_field] - 1e-12)
        return;
      while (next_field < field_times.size() && t >= field_times[next_field] - 1e-12)
        ++next_field;
      // drawn in the stator frame: rotor-borne features where they stand at t
      field_records.emplace_back(t, write_film_fields(fe->reynolds(), dir, "transient_fields",
                                                      field_records.size(), FieldSelection(),
                                                      fe->frame_angle()));
    };
  }
  // SIGINT / SIGTERM stop the integration after the current output row: the rows so far are
  // published as an incomplete run
  const StatorTransient::Result result = [&]
  {
    const interrupt::StopOnSignal stop_on_signal;
    return transient.run();
  }();
  output::make_directory(dir);
  if (!field_records.empty())
  {
    std::ostringstream pvd;
    dealii::DataOutBase::write_pvd_record(pvd, field_records);
    output::write_file_atomically(dir, "transient_fields.pvd", pvd.str());
  }
  output::write_file_atomically(dir, "transient.csv", csv_text(result.samples));

  nlohmann::json s = events(result);
  s["complete"] = result.complete;
  if (!result.complete)
    s["stop_reason"] = result.stop_reason;
  s["end_time"] = result.samples.empty() ? 0.0 : result.samples.back().time;
  s["final_state"] =
      result.samples.empty() ? nlohmann::json(nullptr) : sample_json(result.samples.back());
  s["film_model"] = film->description();
  s["film_evaluations"] = result.film_evaluations;
  s["steps"] = result.steps;
  s["integrator"] = {{"error_test_failures", result.error_test_failures},
                     {"convergence_failures", result.convergence_failures},
                     {"jacobian_setups", result.jacobian_setups}};
  s["thermal_coning_film"] = seal.thermal.film_name();
  s["integration_wall_time"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json files = {"transient.csv"};
  if (!field_records.empty())
    files.push_back("transient_fields.pvd");
  if (want_plot && !result.samples.empty())
  {
    const PlotResult plot =
        // C0 and ro of this seal normalise the kinematics (the script's defaults are Green 2002's)
        run_plot_script("plot_transient.py",
                        {dir + "/transient.csv", dir + "/transient.png",
                         numerics::to_prm_string(seal.geometry.clearance),
                         numerics::to_prm_string(seal.geometry.outer_radius)},
                        dir + "/transient.png");
    if (plot.made)
      files.push_back("transient.png");
    else
    {
      s["plot_note"] = plot.note;
      report_skipped_plot("sealfe transient", plot);
    }
  }
  s["files"] = files;
  s["csv_notes"] = {
      {"transient.csv",
       "one row per Output interval: axial_offset = Z (Green 2002 Eq. 26, positive opening the "
       "film); stator_tilt and stator_precession are the magnitude and direction of the stator's "
       "tilt vector; min_film_over_sigma = min film / combined roughness sigma; heating_film is "
       "the film thickness that drives thermal coning; leakage_inner is the flow out through "
       "r = ri; leaked_volume its time integral"}};
  if (!result.complete)
  {
    throw output::IncompleteRun("transient: " + result.stop_reason +
                                    "; the rows computed so far "
                                    "are in " +
                                    dir + "/transient.csv, summary.json says complete = false",
                                s);
  }
  std::cout << "sealfe transient: " << result.samples.size() << " rows, " << result.steps
            << " steps, " << result.film_evaluations << " film evaluations\n";
  return s;
}
} // namespace transient
} // namespace sealfe
