// OperatingRamps: the start-up / run / shut-down history of rotor speed, outer and inner pressure
// of Green 2002 Eq. 17 — each a trapezoid in time with its own t1 <= t2 <= t3.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace sealfe
{
/// One quantity of Green 2002 Eq. 17, generalised to start from a rest value:
///   f = rest                                         t < 0 or t > t3
///   f = rest + (steady - rest) t / t1                0 <= t <= t1   (a step when t1 = 0)
///   f = steady                                       t1 <= t <= t2
///   f = rest + (steady - rest) (t3 - t) / (t3 - t2)  t2 <= t <= t3  (a step when t2 = t3)
/// The paper's form is rest = 0; a pressure that the paper ramps "as a drop" (p_o - p_i from 0)
/// is rest = p_i. t3 = inf keeps the steady value after t2.
struct Ramp
{
  double rest = 0;
  double steady = 0;
  double t1 = 0, t2 = 0, t3 = 0;

  double value(double t) const;
  /// d value / dt (the slope of the piece t lies in; the right-hand slope at a corner).
  double rate(double t) const;
  /// The corners t1, t2, t3 where the slope jumps (finite ones with a jump only).
  std::vector<double> corners() const;
  /// Integral of value() from 0 to t (closed form): the shaft angle psi_r = Int omega dt.
  double integral(double t) const;
  /// Throws std::runtime_error naming `what` unless 0 <= t1 <= t2 <= t3 and values finite.
  void validate(const std::string &what) const;
};

/// Subsection "Ramps": Speed, Outer pressure, Inner pressure, each with "... rest value",
/// "... steady value", "... t1/t2/t3". Defaults: Green 2002 Table 1 (1500 rad/s and
/// p_o 100 -> 500 kPa over 3/6/9 s, p_i = 100 kPa constant).
struct OperatingRamps
{
  Ramp speed{0, 1500, 3, 6, 9};
  Ramp outer_pressure{1e5, 5e5, 3, 6, 9};
  Ramp inner_pressure{1e5, 1e5, 0, 0, 1e300};

  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);
  void validate() const;
  /// Every corner of the three ramps, sorted, without repeats: the integrator stops there so
  /// that no step straddles a jump of the slope.
  std::vector<double> corners() const;
};
} // namespace sealfe
