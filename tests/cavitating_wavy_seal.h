// Test support: the cavitating seal several film tests share, the default seal made flat, wavy
// (three waves of 0.5 C0) and slightly tilted, at a low sealed pressure, so that the film
// ruptures behind each wave and reforms ahead of the next one.
#pragma once

#include <sealfe/film/film_thickness.h>
#include <sealfe/film/operating_conditions.h>

namespace sealfe::testing
{
/// Flat faces with `waves` waves of amplitude `amplitude_over_c0` C0 and a tilt of 0.2 C0/ro.
inline FilmThickness wavy_film(const double amplitude_over_c0 = 0.5, const double waves = 3)
{
  FilmThickness f;
  f.coning = 0;
  f.wave_amplitude = amplitude_over_c0 * f.clearance;
  f.wave_number = waves;
  f.tilt = 0.2 * f.clearance / f.outer_radius;
  return f;
}

/// The default conditions at pi = 20 kPa, po = 50 kPa.
inline OperatingConditions low_pressure()
{
  OperatingConditions c;
  c.inner_pressure = 2e4;
  c.outer_pressure = 5e4;
  return c;
}
} // namespace sealfe::testing
