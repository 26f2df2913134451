#include <sealfe/dynamics/seal_dynamics_input.h>
#include <sealfe/dynamics/stability_study.h>
#include <sealfe/dynamics/whirl_modes.h>
#include <sealfe/io/csv.h>
#include <sealfe/io/python_plot.h>
#include <sealfe/numerics/number_lists.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
namespace stability
{
void declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  SealDynamicsInput::declare_parameters(prm);
  prm.enter_subsection("Stability");
  prm.declare_entry("Swept speed", "Rotor speed", Selection("Rotor speed|Stator speed"),
                    "Which ring's speed is swept for the stable range; the other keeps its value "
                    "from Operating conditions.");
  declare_speed_sweep(prm, "-20000", "20000", "801",
                      "Speeds at which stability is evaluated before each change of verdict is "
                      "refined by bisection; a stable or unstable band narrower than the spacing "
                      "can be missed.");
  // The names before the two studies shared one vocabulary (old parameter files keep working).
  prm.declare_alias("Speed from", "Sweep from");
  prm.declare_alias("Speed to", "Sweep to");
  prm.declare_alias("Speed points", "Grid points");
  prm.declare_entry("Criterion", "eigenvalues", Selection("eigenvalues|Routh-Hurwitz"),
                    "Stability test for the sweep: eigenvalues of the first-order system "
                    "(LAPACK; any film) or the Hurwitz determinants of Wileman & Green Appendix B "
                    "(isotropic film only). The summary reports both verdicts at the operating "
                    "point when both apply.");
  prm.declare_entry("Second parameter", "none",
                    Selection("none|" + SealDynamicsInput::parameter_names()),
                    "Optional study: the stable range is recomputed for each of the Second "
                    "parameter values and written to stability_sweep.csv.");
  prm.declare_entry("Second parameter values", "", Anything(),
                    "Values (SI units) of the second parameter: a list 'a, b, c' (used in "
                    "ascending order) or a range 'start : stop : count'.");
  prm.declare_entry("Hold normalized coning", "true", Bool(),
                    "When the second parameter is Clearance, scale Coning with it so that "
                    "beta* ro / C0 stays fixed (as Wileman & Green's Table 1 did).");
  prm.declare_entry("Plot", "true", Bool(),
                    "Draw stability_campbell.png (whirl frequency and damping ratio of each mode "
                    "against the swept speed) and, with a Second parameter, stability_map.png "
                    "(stable and unstable regions of swept speed against the second parameter) "
                    "with scripts/plot_campbell.py and scripts/plot_stability_map.py, if python3 "
                    "with matplotlib is found (else one line on stderr).");
  prm.declare_entry("Python", "", Anything(),
                    "Python interpreter for the plots; empty: the first of /usr/bin/python3 and "
                    "python3 that imports matplotlib.");
  prm.leave_subsection();
}

namespace
{
struct Sweep
{
  AngularSealDynamics::SweptRing swept;
  double from, to;
  unsigned int n;
  AngularSealDynamics::Criterion criterion;
};

/// SI unit of one of SealDynamicsInput::parameter_names() ("Clearance": "m"), for the CSV header.
std::string parameter_unit(const std::string &name)
{
  auto ends = [&](const std::string &tail)
  {
    return name.size() >= tail.size() &&
           name.compare(name.size() - tail.size(), tail.npos, tail) == 0;
  };
  if (name == "Clearance" || ends("radius"))
    return "m";
  if (name == "Coning")
    return "rad";
  if (ends("pressure"))
    return "Pa";
  if (name == "Viscosity")
    return "Pa s";
  if (ends("speed"))
    return "rad/s";
  if (ends("inertia"))
    return "kg m^2";
  if (ends("stiffness"))
    return "N m/rad";
  if (ends("damping"))
    return "N m s/rad";
  throw std::runtime_error("no unit for the parameter '" + name + "'");
}

/// Column name of one of SealDynamicsInput::parameter_names(): lower case, '_' for spaces.
std::string parameter_column(const std::string &name)
{
  std::string c;
  for (const char ch : name)
    c += ch == ' ' ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return c;
}

/// The stable interval that contains the swept ring's current speed, else the widest one.
nlohmann::json pick_range(const std::vector<AngularSealDynamics::SpeedInterval> &intervals,
                          const double current, bool &found, nlohmann::json &limits)
{
  found = false;
  const AngularSealDynamics::SpeedInterval *best = nullptr;
  for (const auto &i : intervals)
    if (i.low <= current && current <= i.high)
      best = &i;
  if (!best)
    for (const auto &i : intervals)
      if (!best || i.high - i.low > best->high - best->low)
        best = &i;
  if (!best)
  {
    limits = nullptr;
    return nullptr;
  }
  found = true;
  limits = {best->low_at_search_limit, best->high_at_search_limit};
  return {best->low, best->high};
}
} // namespace

nlohmann::json run(dealii::ParameterHandler &prm, const std::string &output_directory)
{
  SealDynamicsInput input;
  input.parse_parameters(prm);
  input.validate();

  prm.enter_subsection("Stability");
  const std::string swept_name = prm.get("Swept speed");
  Sweep sweep{swept_name == "Rotor speed" ? AngularSealDynamics::SweptRing::rotor
                                          : AngularSealDynamics::SweptRing::stator,
              prm.get_double("Speed from"), prm.get_double("Speed to"),
              static_cast<unsigned int>(prm.get_integer("Speed points")),
              prm.get("Criterion") == "eigenvalues"
                  ? AngularSealDynamics::Criterion::eigenvalues
                  : AngularSealDynamics::Criterion::routh_hurwitz};
  const std::string second = prm.get("Second parameter");
  const std::string second_values = prm.get("Second parameter values");
  const bool hold_beta = prm.get_bool("Hold normalized coning");
  const bool want_plot = prm.get_bool("Plot");
  const std::string python = prm.get("Python");
  prm.leave_subsection();

  if (!std::isfinite(sweep.from) || !std::isfinite(sweep.to) || !(sweep.to > sweep.from))
  {
    std::ostringstream s;
    s << "Stability: Speed to (" << sweep.to << " rad/s) must be greater than Speed from ("
      << sweep.from << " rad/s)";
    throw std::runtime_error(s.str());
  }
  std::vector<double> values;
  if (second != "none")
  {
    values = numerics::parse_number_list(second_values, "Stability: Second parameter values");
    if (values.empty())
      throw std::runtime_error("Stability: Second parameter = " + second +
                               " needs a list of Second parameter values");
  }

  const double wr = input.operating.rotor_speed, ws = input.operating.stator_speed;
  const bool swept_rotor = sweep.swept == AngularSealDynamics::SweptRing::rotor;
  const double fixed = swept_rotor ? ws : wr, current = swept_rotor ? wr : ws;
  // Level 2: the FE coefficients at a few speeds of the sweep, interpolated in between.
  const SweepFilm film = input.sweep_film(sweep.swept, fixed, sweep.from, sweep.to);
  const AngularSealDynamics dynamics = input.build(film.model);

  nlohmann::json summary;
  summary["configuration"] = to_string(input.configuration);
  const FilmCoefficients fc = dynamics.film_coefficients(wr, ws);
  const bool isotropic_film = fc.tilt_block_is_isotropic(1e-9);
  if (sweep.criterion == AngularSealDynamics::Criterion::routh_hurwitz && !isotropic_film)
    throw std::runtime_error("Stability: Criterion = Routh-Hurwitz needs an isotropic film "
                             "tilt block; use Criterion = eigenvalues");
  summary["film_model"] = fc.model;
  summary["film_model_level"] = static_cast<int>(input.film_level);
  summary["film_coefficients"] = fc.to_json();
  summary["film_speed_dependence"] = film.description;
  summary["rotor_speed"] = wr;
  summary["stator_speed"] = ws;
  const auto lambda = dynamics.eigenvalues(wr, ws);
  nlohmann::json ev = nlohmann::json::array(), whirl = nlohmann::json::array(),
                 zeta = nlohmann::json::array();
  for (const auto &l : lambda)
  {
    ev.push_back({l.real(), l.imag()});
    whirl.push_back(l.imag());
    zeta.push_back(std::abs(l) > 0 ? -l.real() / std::abs(l) : 0.0);
  }
  summary["eigenvalues"] = ev;
  summary["whirl_frequencies"] = whirl;
  summary["damping_ratios"] = zeta;
  summary["growth_rate"] = lambda.front().real();
  summary["stable"] = dynamics.is_stable(wr, ws);
  summary["stable_routh_hurwitz"] =
      isotropic_film ? nlohmann::json(dynamics.is_stable_routh_hurwitz(wr, ws)) : nullptr;

  summary["swept_speed"] = swept_rotor ? "rotor" : "stator";
  summary["sweep"] = {sweep.from, sweep.to};
  summary["criterion"] = sweep.criterion == AngularSealDynamics::Criterion::eigenvalues
                             ? "eigenvalues"
                             : "Routh-Hurwitz";
  const auto intervals = dynamics.stable_speed_intervals(sweep.swept, fixed, sweep.from, sweep.to,
                                                         sweep.n, sweep.criterion);
  bool found = false;
  nlohmann::json limits;
  summary["stable_range"] = pick_range(intervals, current, found, limits);
  summary["stable_range_at_search_limit"] = limits;
  nlohmann::json all = nlohmann::json::array();
  for (const auto &i : intervals)
    all.push_back({i.low, i.high});
  summary["stable_intervals"] = all;
  if (film.interpolation)
  {
    // The interpolation error where it matters: one FE computation midway between the nodes
    // around each end of the stable range (or around the operating speed without one).
    std::vector<double> at;
    if (found)
      for (unsigned int k = 0; k < 2; ++k)
        if (!limits[k].get<bool>())
          at.push_back(summary["stable_range"][k].get<double>());
    if (at.empty())
      at.push_back(current);
    summary["film_speed_dependence"]["interpolation_check"] =
        film.interpolation->check_report(at, input.geometry.outer_radius);
  }
  try
  {
    summary["undamped_thresholds"] = dynamics.undamped_threshold_speeds(sweep.swept, fixed);
  }
  catch (const std::runtime_error &)
  {
    summary["undamped_thresholds"] = nullptr; // film without c = (w1 + w2)/2 d11
  }

  // growth rate along the swept speed
  nlohmann::json files = nlohmann::json::array(), notes = nlohmann::json::object();
  {
    const std::string name = "stability_growth_rate.csv";
    csv::Writer table({{"swept_speed", "rad/s"},
                       {"rotor_speed", "rad/s"},
                       {"stator_speed", "rad/s"},
                       {"growth_rate", "1/s"},
                       {"stable", csv::dimensionless}});
    for (unsigned int i = 0; i < sweep.n; ++i)
    {
      const double w = sweep.from + (sweep.to - sweep.from) * i / (sweep.n - 1);
      const double r = swept_rotor ? w : fixed, s = swept_rotor ? fixed : w;
      table.add_row({w, r, s, dynamics.growth_rate(r, s), dynamics.is_stable(r, s)});
    }
    table.write(output_directory, name);
    notes[name] = "growth rate max Re(lambda) of the least stable mode against the " +
                  std::string(swept_rotor ? "rotor" : "stator") + " speed; the other ring at " +
                  numerics::to_prm_string(fixed) + " rad/s; stable = 1: every mode decays";
    files.push_back(name);
  }

  // Campbell diagram: every mode at every swept speed
  {
    const std::string name = "stability_campbell.csv";
    csv::Writer table({{"swept_speed", "rad/s"},
                       {"rotor_speed", "rad/s"},
                       {"stator_speed", "rad/s"},
                       {"mode", csv::dimensionless},
                       {"eigenvalue_real", "1/s"},
                       {"eigenvalue_imag", "1/s"},
                       {"whirl_frequency", "rad/s"},
                       {"damping_ratio", csv::dimensionless},
                       {"stator_share", csv::dimensionless}});
    for (unsigned int i = 0; i < sweep.n; ++i)
    {
      const double w = sweep.from + (sweep.to - sweep.from) * i / (sweep.n - 1);
      const double r = swept_rotor ? w : fixed, s = swept_rotor ? fixed : w;
      const auto modes = whirl_modes(dynamics, r, s);
      for (unsigned int m = 0; m < modes.size(); ++m)
        table.add_row({w, r, s, m, modes[m].eigenvalue.real(), modes[m].eigenvalue.imag(),
                       modes[m].whirl_frequency, modes[m].damping_ratio, modes[m].stator_share});
    }
    table.write(output_directory, name);
    notes[name] = "one row per mode and swept speed (Campbell diagram): mode numbers the modes "
                  "at one speed by decreasing eigenvalue_real (0 = least damped), not a mode "
                  "followed across speeds; lambda = eigenvalue_real + i eigenvalue_imag is the "
                  "eigenvalue with Im >= 0 of a conjugate pair; whirl_frequency = +Im(lambda) for "
                  "forward whirl (counter-clockwise, the sense of a positive speed), -Im(lambda) "
                  "backward, 0 for a real eigenvalue; damping_ratio = -Re(lambda)/|lambda| "
                  "(< 0: unstable); stator_share = the stator ring's share of the mode's tilt";
    files.push_back(name);
  }

  if (second != "none")
  {
    const std::string name = "stability_sweep.csv";
    csv::Writer csv_table({{parameter_column(second), parameter_unit(second)},
                           {"stable_low", "rad/s"},
                           {"stable_high", "rad/s"},
                           {"low_at_search_limit", csv::dimensionless},
                           {"high_at_search_limit", csv::dimensionless},
                           {"stable_interval_count", csv::dimensionless}});
    // the map: the verdict on the whole grid (second parameter x swept speed), every stable
    // region, not only the interval stable_low..stable_high
    const std::string map_name = "stability_map.csv";
    csv::Writer map_table({{parameter_column(second), parameter_unit(second)},
                           {"swept_speed", "rad/s"},
                           {"growth_rate", "1/s"},
                           {"stable", csv::dimensionless}});
    notes[name] = "stable range [stable_low, stable_high] of the " +
                  std::string(swept_rotor ? "rotor" : "stator") + " speed against " + second +
                  ": the stable interval containing the operating speed, else the widest; empty "
                  "fields: no stable speed in the sweep; *_at_search_limit = 1: that end is the "
                  "edge of the sweep, not a threshold";
    nlohmann::json table = nlohmann::json::array();
    for (const double v : values)
    {
      SealDynamicsInput varied = input;
      varied.set(second, v, hold_beta);
      try
      {
        varied.validate();
      }
      catch (const std::runtime_error &e)
      {
        throw std::runtime_error("Stability: Second parameter " + second + " = " +
                                 numerics::to_prm_string(v) + ": " + e.what());
      }
      const double f = swept_rotor ? varied.operating.stator_speed : varied.operating.rotor_speed;
      const double c = swept_rotor ? varied.operating.rotor_speed : varied.operating.stator_speed;
      const AngularSealDynamics d =
          varied.build(varied.sweep_film(sweep.swept, f, sweep.from, sweep.to).model);
      const auto iv =
          d.stable_speed_intervals(sweep.swept, f, sweep.from, sweep.to, sweep.n, sweep.criterion);
      bool ok = false;
      nlohmann::json lim;
      const nlohmann::json range = pick_range(iv, c, ok, lim);
      auto bound = [&](const int k) { return ok ? csv::number(range[k].get<double>()) : ""; };
      csv_table.add_row({v, bound(0), bound(1), ok && lim[0].get<bool>(), ok && lim[1].get<bool>(),
                         static_cast<unsigned int>(iv.size())});
      table.push_back({{"value", v}, {"stable_range", range}});
      for (unsigned int i = 0; i < sweep.n; ++i)
      {
        const double w = sweep.from + (sweep.to - sweep.from) * i / (sweep.n - 1);
        const double r = swept_rotor ? w : f, s = swept_rotor ? f : w;
        map_table.add_row({v, w, d.growth_rate(r, s), d.is_stable(r, s)});
      }
    }
    csv_table.write(output_directory, name);
    map_table.write(output_directory, map_name);
    notes[map_name] = "growth rate and verdict on the grid of " + second +
                      " (one block per "
                      "Second parameter value) times the swept " +
                      std::string(swept_rotor ? "rotor" : "stator") +
                      " speed: the stability map; stable = 1: every mode decays";
    summary["second_parameter"] = second;
    summary["second_parameter_sweep"] = table;
    files.push_back(name);
    files.push_back(map_name);
  }

  summary["plots"] = nlohmann::json::array();
  if (want_plot)
  {
    struct Plot
    {
      std::string script, png;
      std::vector<std::string> arguments;
    };
    const std::string dir = output_directory + "/";
    std::vector<Plot> plots = {{"plot_campbell.py",
                                "stability_campbell.png",
                                {dir + "stability_campbell.csv", dir + "stability_growth_rate.csv",
                                 dir + "stability_campbell.png"}}};
    if (second != "none")
      // the operating point on the map: the parameter's prm value and the swept ring's speed
      plots.push_back({"plot_stability_map.py",
                       "stability_map.png",
                       {dir + "stability_map.csv", dir + "stability_sweep.csv",
                        dir + "stability_map.png", numerics::to_prm_string(input.get(second)),
                        numerics::to_prm_string(current), swept_rotor ? "rotor" : "stator"}});
    for (const Plot &p : plots)
    {
      const PlotResult plot = run_plot_script(p.script, p.arguments, dir + p.png, python);
      if (plot.made)
      {
        files.push_back(p.png);
        summary["plots"].push_back(p.png);
      }
      else
      {
        summary["plot_notes"][p.png] = plot.note;
        report_skipped_plot("sealfe stability", plot);
      }
    }
  }
  summary["files"] = files;
  summary["csv_notes"] = notes;
  return summary;
}
} // namespace stability
} // namespace sealfe
