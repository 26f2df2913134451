// Rayleigh's infinitely wide step slider (Rayleigh 1918): pressure of a film h1 over the inlet
// length B1 followed by h2 < h1 over B2, ends at ambient pressure, and his optimum step.
#pragma once

#include <cmath>

namespace sealfe::closed_form
{
/// One-dimensional step slider: the stepped surface stands still, the other slides at U from
/// the inlet (x = 0) to the outlet (x = B1 + B2); p = 0 at both ends, gauge.
struct RayleighStep
{
  double h1, h2, B1, B2, viscosity, speed;

  /// Pressure at the step: continuity of U h/2 - h^3 p'/(12 mu) across it,
  /// p_max = 6 mu U (h1 - h2) / (h1^3 / B1 + h2^3 / B2).
  double max_pressure() const
  {
    return 6 * viscosity * speed * (h1 - h2) / (h1 * h1 * h1 / B1 + h2 * h2 * h2 / B2);
  }
  /// Pressure at x (piecewise linear).
  double pressure(const double x) const
  {
    const double p = max_pressure();
    return x <= B1 ? p * x / B1 : p * (B1 + B2 - x) / B2;
  }
  /// Load per unit width, p_max (B1 + B2) / 2.
  double load_per_width() const { return 0.5 * max_pressure() * (B1 + B2); }

  /// Rayleigh's optimum for the load at fixed h2 and B1 + B2: h1 / h2 = 1 + sqrt(3)/2 = 1.866
  /// and B1 / (B1 + B2) = H^1.5 / (1 + H^1.5) = 0.718 (maximise (H - 1) / (H^3/f + 1/(1 - f))
  /// over f, then over H: 2 u^3 - 3 u - 1 = 0 with u = sqrt(H)).
  static double optimum_film_ratio() { return 1 + std::sqrt(3.0) / 2; }
  static double optimum_step_fraction()
  {
    const double h15 = std::pow(optimum_film_ratio(), 1.5);
    return h15 / (1 + h15);
  }
};

} // namespace sealfe::closed_form
