// ClosingForce: the force pressing the flexibly mounted ring towards its mate, Green 2002 Eq. 22 —
// hydraulic load on the balance area plus the spring preset.
#pragma once

#include <deal.II/base/parameter_handler.h>

namespace sealfe
{
/// F_cls = pi (ro^2 - ri^2) (B p_high + (1 - B) p_low) + F_spring, where B is the balance ratio
/// applied to the higher of the two sealed pressures (Eq. 22: B = B_o if p_o > p_i, B = B_i if
/// p_i > p_o; the other area ratio is 1 - B). Subsection "Closing force".
struct ClosingForce
{
  double balance_ratio = 0.75; ///< B, in (0, 1]
  double spring_force = 20;    ///< N

  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);
  /// Throws std::runtime_error unless 0 < B <= 1 and the spring force is finite and >= 0.
  void validate() const;

  /// N, for a face ri..ro and the two pressures (Pa).
  double value(double inner_radius, double outer_radius, double inner_pressure,
               double outer_pressure) const;
};
} // namespace sealfe
