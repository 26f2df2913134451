#include <sealfe/dynamics/response_study.h>
#include <sealfe/dynamics/seal_dynamics_input.h>
#include <sealfe/io/csv.h>
#include <sealfe/io/python_plot.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
namespace response
{
void declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  SealDynamicsInput::declare_parameters(prm);
  prm.enter_subsection("Forced response");
  prm.declare_entry("Swept speed", "Rotor speed", Selection("Rotor speed|Stator speed"),
                    "Which ring's speed is swept; the other keeps its Operating conditions value.");
  declare_speed_sweep(prm, "10", "5000", "500", "Number of speeds (equally spaced).");
  prm.declare_entry("Plot", "true", Bool(),
                    "Write response.png (relative tilt against speed with the contact limit) "
                    "with scripts/plot_response.py, if python3 with matplotlib is found.");
  prm.declare_entry("Python", "", Anything(),
                    "Python interpreter for the plot; empty: the first of /usr/bin/python3 and "
                    "python3 that imports matplotlib.");
  prm.declare_entry("Plot script", "", Anything(),
                    "Path of plot_response.py; empty: scripts/plot_response.py of the source "
                    "tree sealfe was built from.");
  prm.leave_subsection();
}

namespace
{
/// Contiguous runs of grid speeds where flag holds, as [first, last] pairs.
nlohmann::json runs(const std::vector<double> &speeds, const std::vector<bool> &flag)
{
  nlohmann::json out = nlohmann::json::array();
  for (unsigned int i = 0; i < speeds.size(); ++i)
    if (flag[i] && (i == 0 || !flag[i - 1]))
    {
      unsigned int j = i;
      while (j + 1 < speeds.size() && flag[j + 1])
        ++j;
      out.push_back({speeds[i], speeds[j]});
    }
  return out;
}
} // namespace

nlohmann::json run(dealii::ParameterHandler &prm, const std::string &output_directory)
{
  SealDynamicsInput input;
  input.parse_parameters(prm);
  input.validate();
  prm.enter_subsection("Forced response");
  const bool swept_rotor = prm.get("Swept speed") == "Rotor speed";
  const double from = prm.get_double("Speed from"), to = prm.get_double("Speed to");
  const unsigned int n = prm.get_integer("Speed points");
  const bool want_plot = prm.get_bool("Plot");
  const std::string python = prm.get("Python"), script = prm.get("Plot script");
  prm.leave_subsection();
  if (!std::isfinite(from) || !std::isfinite(to) || !(to > from))
  {
    std::ostringstream s;
    s << "Forced response: Speed to (" << to << " rad/s) must be greater than Speed from (" << from
      << " rad/s)";
    throw std::runtime_error(s.str());
  }

  const double fixed = swept_rotor ? input.operating.stator_speed : input.operating.rotor_speed;
  // Level 2: the FE coefficients at a few speeds of the sweep, interpolated in between.
  const SweepFilm film = input.sweep_film(swept_rotor ? AngularSealDynamics::SweptRing::rotor
                                                      : AngularSealDynamics::SweptRing::stator,
                                          fixed, from, to);
  const AngularSealDynamics dynamics = input.build(film.model);
  const double limit = input.contact_tilt();
  const double C0 = input.geometry.clearance, ro = input.geometry.outer_radius;

  const std::string csv_name = "response.csv";
  const std::string rad = "rad", speed = "rad/s", none = csv::dimensionless;
  csv::Writer table({{"swept_speed", speed},
                     {"rotor_speed", speed},
                     {"stator_speed", speed},
                     {"stator_tilt", rad},
                     {"rotor_tilt", rad},
                     {"relative_tilt", rad},
                     {"relative_tilt_synchronous", rad},
                     {"relative_tilt_phase", "deg"},
                     {"relative_tilt_static", rad},
                     {"normalized_relative_tilt", none},
                     {"contact_tilt", rad},
                     {"contact_margin", rad},
                     {"stable", none}});
  std::vector<double> speeds;
  std::vector<bool> contact, unstable;
  double peak = -1, speed_at_peak = 0, min_margin = INFINITY;
  for (unsigned int i = 0; i < n; ++i)
  {
    const double w = from + (to - from) * i / (n - 1);
    const double wr = swept_rotor ? w : fixed, ws = swept_rotor ? fixed : w;
    const ForcedResponse r = dynamics.forced_response(wr, ws);
    const double rel = ForcedResponse::max_magnitude(r.relative_tilt);
    const HarmonicTilt sync = ForcedResponse::at_frequency(r.relative_tilt, std::abs(wr));
    const HarmonicTilt stat = ForcedResponse::at_frequency(r.relative_tilt, 0.0);
    const double sync_amp = (wr != 0.0) ? std::abs(sync.forward) + std::abs(sync.backward) : 0;
    // a rotor spinning in -theta whirls backward: its phase is that of the backward part
    const std::complex<double> sync_vec = (wr >= 0) ? sync.forward : sync.backward;
    const double phase = (wr != 0.0 && sync_amp > 0) ? std::arg(sync_vec) * 180 / M_PI : 0.0;
    const bool stable = dynamics.is_stable(wr, ws);
    table.add_row({w, wr, ws, ForcedResponse::max_magnitude(r.stator_tilt),
                   ForcedResponse::max_magnitude(r.rotor_tilt), rel, sync_amp, phase,
                   std::abs(stat.forward), rel * ro / C0, limit, limit - rel, stable});
    speeds.push_back(w);
    contact.push_back(rel > limit);
    unstable.push_back(!stable);
    if (rel > peak)
    {
      peak = rel;
      speed_at_peak = w;
    }
    min_margin = std::min(min_margin, limit - rel);
  }
  table.write(output_directory, csv_name);

  nlohmann::json summary;
  summary["csv_notes"] = {
      {csv_name,
       "steady-state response to the misalignments: tilts are the largest magnitude over time; "
       "relative_tilt_phase is the phase of the synchronous relative tilt against the rotor "
       "angle; normalized_relative_tilt = relative_tilt ro / C0; contact_margin = contact_tilt - "
       "relative_tilt (negative: face contact); stable = 0: the response is not reached (an "
       "unstable mode grows)"}};
  summary["configuration"] = to_string(input.configuration);
  const FilmCoefficients fc =
      dynamics.film_coefficients(input.operating.rotor_speed, input.operating.stator_speed);
  summary["film_model"] = fc.model;
  summary["film_model_level"] = static_cast<int>(input.film_level);
  summary["film_coefficients"] = fc.to_json();
  summary["film_speed_dependence"] = film.description;
  if (film.interpolation)
    // the interpolation error around the speed of the largest relative tilt
    summary["film_speed_dependence"]["interpolation_check"] =
        film.interpolation->check_report({speed_at_peak}, input.geometry.outer_radius);
  summary["swept_speed"] = swept_rotor ? "rotor" : "stator";
  summary["speed_range"] = {from, to};
  summary["contact_tilt"] = limit;
  summary["peak_relative_tilt"] = peak;
  summary["speed_at_peak_relative_tilt"] = speed_at_peak;
  summary["min_contact_margin"] = min_margin;
  summary["contact"] = min_margin < 0;
  summary["contact_speed_ranges"] = runs(speeds, contact);
  summary["unstable_speed_ranges"] = runs(speeds, unstable);
  // forward synchronous critical speed of the rotor ring on its own support (Varney & Green (2017):
  // the shaft): sqrt(k_s / (I_t - I_p)); none for a thin rotor (I_t <= I_p)
  const RingProperties &rotor = input.rotor;
  summary["rotor_critical_speed"] =
      (dynamics.rotor_is_flexible() && rotor.transverse_inertia > rotor.polar_inertia)
          ? nlohmann::json(std::sqrt(rotor.support_stiffness /
                                     (rotor.transverse_inertia - rotor.polar_inertia)))
          : nlohmann::json(nullptr);
  nlohmann::json files = {csv_name};
  summary["plot"] = nullptr;
  if (want_plot)
  {
    const PlotResult plot =
        run_plot_script("plot_response.py",
                        {output_directory + "/response.csv", output_directory + "/response.png"},
                        output_directory + "/response.png", python, script);
    if (plot.made)
    {
      files.push_back("response.png");
      summary["plot"] = "response.png";
    }
    else
    {
      summary["plot_note"] = plot.note;
      report_skipped_plot("sealfe response", plot);
    }
  }
  summary["files"] = files;
  return summary;
}
} // namespace response
} // namespace sealfe
