// `sealfe annular`: stiffness, leakage and optimum of an annular (radial-clearance) seal
// (annular/annular_seal.h).
#include "driver.h"

#include <sealfe/annular/annular_seal.h>
#include <sealfe/io/output.h>

namespace sealfe::applications
{
namespace
{
nlohmann::json run(dealii::ParameterHandler &prm, const std::string &directory, MPI_Comm)
{
  output::make_directory(directory);
  return annular::run(prm, directory);
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
