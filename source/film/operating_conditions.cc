#include <sealfe/film/operating_conditions.h>
#include <sealfe/numerics/number_lists.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
void OperatingConditions::declare_parameters(dealii::ParameterHandler &prm)
{
  using dealii::Patterns::Double;
  const OperatingConditions defaults; // the member initialisers are the defaults
  // Physical bounds (doc/guarantees.md): beyond them no sealed fluid or ring exists and the film
  // equation overflows or loses every digit. A non-positive viscosity has its own message.
  const double lowest = Double::min_double_value;
  const double max_pressure = 1e10; // Pa: 10 GPa, far above any sealed pressure
  const double max_viscosity = 1e6; // Pa s: above pitch-like polymer melts
  const double max_speed = 1e6;     // rad/s: a 1 cm face would move at 10 km/s
  prm.enter_subsection("Operating conditions");
  prm.declare_entry("Inner pressure", numerics::to_prm_string(defaults.inner_pressure),
                    Double(-max_pressure, max_pressure), "Pressure pi (Pa) on r = ri.");
  prm.declare_entry("Outer pressure", numerics::to_prm_string(defaults.outer_pressure),
                    Double(-max_pressure, max_pressure), "Pressure po (Pa) on r = ro.");
  prm.declare_entry("Viscosity", numerics::to_prm_string(defaults.viscosity),
                    Double(lowest, max_viscosity), "Dynamic viscosity mu (Pa s).");
  prm.declare_entry("Rotor speed", numerics::to_prm_string(defaults.rotor_speed),
                    Double(-max_speed, max_speed),
                    "Angular speed (rad/s, positive in +theta) of the rotor face; the film shape "
                    "is fixed in the frame of the solve.");
  prm.declare_entry("Stator speed", numerics::to_prm_string(defaults.stator_speed),
                    Double(-max_speed, max_speed),
                    "Angular speed (rad/s) of the other face (non-zero for two rotating rings, "
                    "FMRR).");
  prm.declare_entry("Reference pressure", numerics::to_prm_string(defaults.reference_pressure),
                    Double(-max_pressure, max_pressure),
                    "p_ref (Pa) subtracted from the pressure in the force and moments.");
  prm.leave_subsection();
}

void OperatingConditions::parse_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Operating conditions");
  inner_pressure = prm.get_double("Inner pressure");
  outer_pressure = prm.get_double("Outer pressure");
  viscosity = prm.get_double("Viscosity");
  rotor_speed = prm.get_double("Rotor speed");
  stator_speed = prm.get_double("Stator speed");
  reference_pressure = prm.get_double("Reference pressure");
  prm.leave_subsection();
}

void OperatingConditions::validate() const
{
  for (double v : {inner_pressure, outer_pressure, viscosity, rotor_speed, stator_speed})
    if (!std::isfinite(v))
      throw std::runtime_error("Operating conditions: a parameter is not a finite number");
  if (!(viscosity > 0))
  {
    std::ostringstream s;
    s << "Operating conditions: Viscosity must be positive (got " << viscosity << " Pa s)";
    throw std::runtime_error(s.str());
  }
}

} // namespace sealfe
