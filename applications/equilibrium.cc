// `sealfe equilibrium`: the axial operating point of a flexibly mounted stator under its closing
// force — film force + asperity contact + support = closing force (Green 2002 Eq. 22;
// dynamics/equilibrium.h, dynamics/transient_study.h).
#include "driver.h"

#include <sealfe/dynamics/transient_study.h>
#include <sealfe/io/output.h>

namespace sealfe::applications
{
namespace
{
nlohmann::json run(dealii::ParameterHandler &prm, const std::string &directory, MPI_Comm)
{
  nlohmann::json summary = equilibrium::run(prm, directory); // prints the headline
  output::make_directory(directory);
  return summary;
}
} // namespace

SubCommand equilibrium_command()
{
  return {"equilibrium",
          "axial operating point under the closing force -> summary.json",
          /*face_seal=*/true,
          /*distributed=*/false,
          equilibrium::declare_parameters,
          run};
}
} // namespace sealfe::applications
