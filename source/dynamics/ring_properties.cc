#include <sealfe/dynamics/ring_properties.h>

#include <sstream>
#include <stdexcept>

namespace sealfe
{
std::string to_string(const SealConfiguration c)
{
  switch (c)
  {
  case SealConfiguration::fms:
    return "FMS";
  case SealConfiguration::fmr:
    return "FMR";
  case SealConfiguration::fmrr:
    return "FMRR";
  case SealConfiguration::fms_flexible_rotor:
    return "FMS with flexible rotor";
  }
  return "";
}

SealConfiguration configuration_from_string(const std::string &name)
{
  for (const auto c : {SealConfiguration::fms, SealConfiguration::fmr, SealConfiguration::fmrr,
                       SealConfiguration::fms_flexible_rotor})
    if (to_string(c) == name)
      return c;
  throw std::runtime_error("Seal dynamics: Configuration '" + name +
                           "' is not one of FMS, FMR, FMRR, FMS with flexible rotor");
}

void declare_ring_parameters(dealii::ParameterHandler &prm, const std::string &name,
                             const RingProperties &d, const std::string &what)
{
  using dealii::Patterns::Double;
  // Physical bounds (doc/guarantees.md): far beyond any seal ring or shaft (misalignments in rad,
  // at most 1), where the dynamics would overflow or lose every digit.
  const double max_inertia = 1e4;    // kg m^2: a 1 t disk of 4 m radius
  const double max_stiffness = 1e12; // N m/rad: a steel shaft is below 1e9
  const double max_damping = 1e12;   // N m s/rad
  auto str = [](const double v)
  {
    std::ostringstream s;
    s << v;
    return s.str();
  };
  prm.enter_subsection(name);
  prm.declare_entry("Transverse inertia", str(d.transverse_inertia), Double(0, max_inertia),
                    "Transverse mass moment of inertia I_t (kg m^2) of the " + what +
                        " about a diameter through its centre.");
  prm.declare_entry("Polar inertia", str(d.polar_inertia), Double(0, max_inertia),
                    "Polar mass moment of inertia I_p (kg m^2): gyroscopic moment I_p omega "
                    "times the tilt rate. I_t/I_p < 1/2 is a short disk, > 2 a long rotor.");
  prm.declare_entry("Support stiffness", str(d.support_stiffness), Double(0, max_stiffness),
                    "Angular stiffness (N m/rad) of the support (O-ring/springs, or the shaft "
                    "for a flexible rotor).");
  prm.declare_entry("Support damping", str(d.support_damping), Double(0, max_damping),
                    "Direct angular damping (N m s/rad) of the support.");
  prm.declare_entry("Rotating damping", str(d.rotating_damping), Double(0, max_damping),
                    "Part of the damping that turns with the ring (N m s/rad): adds the "
                    "circulatory stiffness speed x this. Equal to Support damping for a support "
                    "spinning with its shaft (Wileman & Green); D_omega_r of Varney & Green.");
  prm.declare_entry("Support misalignment", str(d.support_misalignment), Double(-1, 1),
                    "Static misalignment (rad) of the support: the tilt it holds the ring at "
                    "(turns with the ring if it spins). Stator: gamma_si; rotor: chi_s "
                    "(run-out). For a rigidly mounted ring, the ring's own tilt.");
  prm.declare_entry("Dynamic misalignment", str(d.dynamic_misalignment), Double(-1, 1),
                    "Angle chi (rad) between the principal axes and the spin axis of a "
                    "flexibly mounted spinning ring: forces (I_t - I_p) chi omega^2.");
  prm.leave_subsection();
}

RingProperties parse_ring_parameters(dealii::ParameterHandler &prm, const std::string &name)
{
  RingProperties r;
  prm.enter_subsection(name);
  r.transverse_inertia = prm.get_double("Transverse inertia");
  r.polar_inertia = prm.get_double("Polar inertia");
  r.support_stiffness = prm.get_double("Support stiffness");
  r.support_damping = prm.get_double("Support damping");
  r.rotating_damping = prm.get_double("Rotating damping");
  r.support_misalignment = prm.get_double("Support misalignment");
  r.dynamic_misalignment = prm.get_double("Dynamic misalignment");
  prm.leave_subsection();
  return r;
}

} // namespace sealfe
