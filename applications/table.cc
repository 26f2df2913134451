// `sealfe table`: finite-element coefficients and loads over a grid of operating points, shared
// across the MPI ranks, written as a CSV coefficient table (coefficients/table_sweep.h).
#include "driver.h"

#include <sealfe/coefficients/table_sweep.h>

namespace sealfe::applications
{
SubCommand table_command()
{
  // The sweep (its plan, the points' distribution over the ranks, the CSV and the progress lines
  // on stderr) is table::run.
  return {"table",
          "coefficients and loads over a grid of operating points -> CSV",
          /*face_seal=*/true,
          /*distributed=*/true,
          table::declare_parameters,
          table::run};
}
} // namespace sealfe::applications
