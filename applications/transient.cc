// `sealfe transient`: start-up / run / shut-down of a flexibly mounted stator seal with asperity
// contact and thermal coning (Green 2002 Eq. 26; dynamics/stator_transient.h,
// dynamics/transient_study.h).
#include "driver.h"

#include <sealfe/dynamics/transient_study.h>

namespace sealfe::applications
{
namespace
{
nlohmann::json run(dealii::ParameterHandler &prm, const std::string &directory, MPI_Comm)
{
  return transient::run(prm, directory); // writes transient.csv, prints the headline
}
} // namespace

SubCommand transient_command()
{
  return {"transient",
          "start-up/run/shut-down transient (Green 2002) -> CSV, PNG",
          /*face_seal=*/true,
          /*distributed=*/false,
          transient::declare_parameters,
          run};
}
} // namespace sealfe::applications
