// `sealfe annular`: stiffness, leakage and optimum of an annular (radial-clearance) seal
// (annular/annular_seal.h).
#include "driver.h"

#include <sealfe/annular/annular_seal.h>
#include <sealfe/io/output.h>

#include <iomanip>
#include <iostream>

namespace sealfe::applications
{
namespace
{
/// The answer on stdout: stiffness and leakage, against the straight seal of the same smallest
/// clearance, and the geometry (Fleming's model has no damping).
void print_headline(const nlohmann::json &s)
{
  const bool stepped = !s["step_ratio"].is_null();
  std::cout << std::setprecision(6) << "sealfe annular (" << s["geometry_type"].get<std::string>()
            << " seal, Lambda = f L / C2 = " << s["lambda"].get<double>() << ")\n"
            << "  stiffness              " << s["stiffness"].get<double>() << " N/m (Kbar "
            << s["stiffness_dimensionless"].get<double>() << ", "
            << s["stiffness_ratio_to_straight"].get<double>() << " x the straight seal)\n"
            << "  leakage                " << s["leakage"].get<double>() << " kg/s, "
            << s["leakage_volumetric"].get<double>() << " m^3/s (Mbar "
            << s["leakage_dimensionless"].get<double>() << ", "
            << s["leakage_ratio_to_straight"].get<double>() << " x the straight seal)\n"
            << "  clearance ratio H      " << s["clearance_ratio"].get<double>();
  if (stepped)
    std::cout << ", step position gamma " << s["step_ratio"].get<double>();
  if (!s["optimisation"].is_null())
    std::cout << " (optimised for " << s["optimisation"]["objective"].get<std::string>() << ")";
  std::cout << "\n  Reynolds number        " << s["reynolds_number"].get<double>() << "\n"
            << "  damping                not modelled (Fleming 1977: direct stiffness only)\n";
}

nlohmann::json run(dealii::ParameterHandler &prm, const std::string &directory, MPI_Comm)
{
  output::make_directory(directory);
  nlohmann::json summary = annular::run(prm, directory);
  print_headline(summary);
  return summary;
}
} // namespace

SubCommand annular_command()
{
  return {"annular",
          "annular (radial-clearance) seal stiffness, leakage, optimum -> JSON, CSV",
          /*face_seal=*/false,
          /*distributed=*/false,
          annular::declare_parameters,
          run};
}
} // namespace sealfe::applications
