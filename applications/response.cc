// `sealfe response`: steady-state forced response of the seal's angular modes to the rings'
// misalignments over a speed range (dynamics/response_study.h).
#include "driver.h"

#include <sealfe/coefficients/coefficient_solver.h>
#include <sealfe/dynamics/response_study.h>
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
  response::declare_parameters(prm);
  CoefficientSolver::declare_parameters(prm); // Film model = finite element
}

/// "[a, b], [c, d] rad/s" or "none".
std::string ranges_text(const nlohmann::json &ranges)
{
  if (ranges.empty())
    return "none";
  std::ostringstream s;
  s << std::setprecision(6);
  for (std::size_t i = 0; i < ranges.size(); ++i)
    s << (i ? ", " : "") << "[" << ranges[i][0].get<double>() << ", " << ranges[i][1].get<double>()
      << "]";
  s << " rad/s";
  return s.str();
}

/// The answer on stdout: the largest relative tilt against the contact limit, the speeds of
/// face contact and of instability.
void print_headline(const nlohmann::json &s)
{
  std::cout << std::setprecision(6) << "sealfe response (" << s["configuration"].get<std::string>()
            << ", film " << s["film_model"].get<std::string>() << ", "
            << s["swept_speed"].get<std::string>() << " speed " << s["speed_range"][0].get<double>()
            << " to " << s["speed_range"][1].get<double>() << " rad/s)\n"
            << "  max relative tilt      " << s["peak_relative_tilt"].get<double>() << " rad at "
            << s["speed_at_peak_relative_tilt"].get<double>() << " rad/s\n"
            << "  contact tilt           " << s["contact_tilt"].get<double>()
            << " rad (smallest margin " << s["min_contact_margin"].get<double>() << " rad)\n"
            << "  face contact           " << ranges_text(s["contact_speed_ranges"]) << "\n"
            << "  unstable (no response) " << ranges_text(s["unstable_speed_ranges"]) << "\n";
  if (!s["rotor_critical_speed"].is_null())
    std::cout << "  rotor critical speed   " << s["rotor_critical_speed"].get<double>()
              << " rad/s (rotor on its support)\n";
}

nlohmann::json run(dealii::ParameterHandler &prm, const std::string &directory, MPI_Comm)
{
  output::make_directory(directory);
  nlohmann::json summary = response::run(prm, directory);
  print_headline(summary);
  return summary;
}
} // namespace

SubCommand response_command()
{
  return {"response",         "steady-state forced response over a speed range -> CSV, PNG",
          /*face_seal=*/true, /*distributed=*/false,
          declare_parameters, run};
}
} // namespace sealfe::applications
