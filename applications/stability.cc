// `sealfe stability`: linear stability of the angular modes of a face seal — eigenvalues,
// Routh-Hurwitz verdict and the stable range of one ring's speed (dynamics/stability_study.h).
#include "driver.h"

#include <sealfe/coefficients/coefficient_solver.h>
#include <sealfe/dynamics/stability_study.h>
#include <sealfe/io/output.h>

#include <iomanip>
#include <iostream>
#include <sstream>

namespace sealfe::applications
{
namespace
{
void declare_parameters(dealii::ParameterHandler &prm)
{
  stability::declare_parameters(prm);
  CoefficientSolver::declare_parameters(prm); // Film model = finite element
}

/// "[a, b] rad/s", an end found at the edge of the sweep marked as such (not a threshold).
std::string range_text(const nlohmann::json &range, const nlohmann::json &at_limit)
{
  std::ostringstream s;
  s << std::setprecision(6) << "[" << range[0].get<double>() << ", " << range[1].get<double>()
    << "] rad/s";
  if (at_limit.is_array() && (at_limit[0].get<bool>() || at_limit[1].get<bool>()))
    s << " ("
      << (at_limit[0].get<bool>() && at_limit[1].get<bool>() ? "both ends"
          : at_limit[0].get<bool>()                          ? "lower end"
                                                             : "upper end")
      << " at the edge of the sweep, not a threshold)";
  return s.str();
}

/// The answer on stdout: the verdict, the stable speed range and its thresholds, the least
/// damped mode.
void print_headline(const nlohmann::json &s)
{
  const std::string ring = s["swept_speed"];
  std::cout << std::setprecision(6) << "sealfe stability (" << s["configuration"].get<std::string>()
            << ", film " << s["film_model"].get<std::string>() << ")\n"
            << "  operating point        " << (s["stable"].get<bool>() ? "stable" : "unstable")
            << " (rotor " << s["rotor_speed"].get<double>() << ", stator "
            << s["stator_speed"].get<double>() << " rad/s)\n"
            << "  stable " << ring << " speed" << std::string(ring == "rotor" ? 5 : 4, ' ');
  if (s["stable_range"].is_null())
    std::cout << "none in the sweep [" << s["sweep"][0].get<double>() << ", "
              << s["sweep"][1].get<double>() << "] rad/s\n";
  else
    std::cout << range_text(s["stable_range"], s["stable_range_at_search_limit"]) << "\n";
  if (s["stable_intervals"].size() > 1)
  {
    std::cout << "  stable intervals       ";
    for (std::size_t i = 0; i < s["stable_intervals"].size(); ++i)
      std::cout << (i ? ", " : "") << "[" << s["stable_intervals"][i][0].get<double>() << ", "
                << s["stable_intervals"][i][1].get<double>() << "]";
    std::cout << " rad/s\n";
  }
  if (s["undamped_thresholds"].is_array())
  {
    std::cout << "  undamped thresholds    ";
    for (std::size_t i = 0; i < s["undamped_thresholds"].size(); ++i)
      std::cout << (i ? ", " : "") << s["undamped_thresholds"][i].get<double>();
    std::cout << " rad/s (no support damping, Wileman & Green Eq. 17)\n";
  }
  // least damped mode: the smallest damping ratio -Re(lambda)/|lambda|
  const auto &zeta = s["damping_ratios"];
  std::size_t least = 0;
  for (std::size_t i = 1; i < zeta.size(); ++i)
    if (zeta[i].get<double>() < zeta[least].get<double>())
      least = i;
  if (!zeta.empty())
    std::cout << "  least damped mode      damping ratio " << zeta[least].get<double>()
              << ", whirl " << s["eigenvalues"][least][1].get<double>() << " rad/s, Re(lambda) "
              << s["eigenvalues"][least][0].get<double>() << " 1/s\n";
  std::cout << "  growth rate            " << s["growth_rate"].get<double>()
            << " 1/s (largest Re(lambda); stable < 0)\n";
  if (s.contains("second_parameter"))
    std::cout << "  stable range against   " << s["second_parameter"].get<std::string>() << ": "
              << s["second_parameter_sweep"].size() << " values in stability_sweep.csv\n";
  if (s.contains("plots") && !s["plots"].empty())
  {
    std::cout << "  plots                  ";
    for (std::size_t i = 0; i < s["plots"].size(); ++i)
      std::cout << (i ? ", " : "") << s["plots"][i].get<std::string>();
    std::cout << "\n";
  }
}

nlohmann::json run(dealii::ParameterHandler &prm, const std::string &directory, MPI_Comm)
{
  output::make_directory(directory);
  nlohmann::json summary = stability::run(prm, directory);
  print_headline(summary);
  return summary;
}
} // namespace

SubCommand stability_command()
{
  return {
      "stability",        "linear stability, eigenvalues and threshold speeds -> summary.json, CSV",
      /*face_seal=*/true, /*distributed=*/false,
      declare_parameters, run};
}
} // namespace sealfe::applications
