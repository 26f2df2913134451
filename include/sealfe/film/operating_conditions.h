// OperatingConditions: boundary pressures, viscosity and ring speeds of a seal operating point.
#pragma once

#include <deal.II/base/parameter_handler.h>

namespace sealfe
{
/// Reads subsection "Operating conditions". Rotor speed omega1 and stator speed omega2 are the
/// angular speeds (rad/s, positive in +theta) of the two faces; the film shape is fixed in the
/// frame of the solve, so the Couette velocity is (omega1 + omega2)/2 * r e_theta.
struct OperatingConditions
{
  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);
  /// Throws std::runtime_error on non-positive viscosity or non-finite values.
  void validate() const;

  double mean_speed() const { return 0.5 * (rotor_speed + stator_speed); }

  double inner_pressure = 0;     // Pa
  double outer_pressure = 4e5;   // Pa
  double viscosity = 1.2e-3;     // Pa s
  double rotor_speed = 1000;     // rad/s
  double stator_speed = 0;       // rad/s
  double reference_pressure = 0; // Pa, p_ref subtracted in the loads
};

} // namespace sealfe
