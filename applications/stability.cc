// `sealfe stability`: linear stability of the angular modes of a face seal — eigenvalues,
// Routh-Hurwitz verdict and the stable range of one ring's speed (dynamics/stability_study.h).
#include "driver.h"

#include <sealfe/coefficients/coefficient_solver.h>
#include <sealfe/dynamics/stability_study.h>
#include <sealfe/io/output.h>

#include <iostream>

namespace sealfe::applications
{
namespace
{
void declare_parameters(dealii::ParameterHandler &prm)
{
  stability::declare_parameters(prm);
  CoefficientSolver::declare_parameters(prm); // Film model = finite element
}

nlohmann::json run(dealii::ParameterHandler &prm, const std::string &directory, MPI_Comm)
{
  output::make_directory(directory);
  nlohmann::json summary = stability::run(prm, directory);
  std::cout << "sealfe stability (" << summary["film_model"].get<std::string>()
            << "): " << (summary["stable"].get<bool>() ? "stable" : "unstable")
            << " at the operating point, stable " << summary["swept_speed"].get<std::string>()
            << " speed range " << summary["stable_range"].dump() << " rad/s\n";
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
