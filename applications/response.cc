// `sealfe response`: steady-state forced response of the seal's angular modes to the rings'
// misalignments over a speed range (dynamics/response_study.h).
#include "driver.h"

#include <sealfe/coefficients/coefficient_solver.h>
#include <sealfe/dynamics/response_study.h>
#include <sealfe/io/output.h>

#include <iostream>

namespace sealfe::applications
{
namespace
{
void declare_parameters(dealii::ParameterHandler &prm)
{
  response::declare_parameters(prm);
  CoefficientSolver::declare_parameters(prm); // Film model = finite element
}

nlohmann::json run(dealii::ParameterHandler &prm, const std::string &directory, MPI_Comm)
{
  output::make_directory(directory);
  nlohmann::json summary = response::run(prm, directory);
  std::cout << "sealfe response (" << summary["film_model"].get<std::string>()
            << "): peak relative tilt " << summary["peak_relative_tilt"].get<double>() << " rad at "
            << summary["speed_at_peak_relative_tilt"].get<double>() << " rad/s, "
            << (summary["contact"].get<bool>() ? "contact" : "no contact") << "\n";
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
