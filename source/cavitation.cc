#include <sealfe/cavitation.h>

namespace sealfe
{
void CavitationSettings::declare_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Cavitation");
  prm.declare_entry("Model", "none", dealii::Patterns::Selection("none|half-sommerfeld"),
                    "none: full film (p may fall below the cavitation pressure). "
                    "half-sommerfeld: full-film solve, then p < p_cav is set to p_cav in the "
                    "loads (the closed forms' assumption; not mass conserving).");
  prm.declare_entry("Cavitation pressure", "0", dealii::Patterns::Double(),
                    "p_cav (Pa), absolute or gauge like the boundary pressures.");
  prm.leave_subsection();
}

void CavitationSettings::parse_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Cavitation");
  model = prm.get("Model") == "half-sommerfeld" ? Cavitation::half_sommerfeld : Cavitation::none;
  pressure = prm.get_double("Cavitation pressure");
  prm.leave_subsection();
}
} // namespace sealfe
