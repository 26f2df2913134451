// Round-off of a film solve at extreme bearing numbers: an a-priori estimate of the relative
// error double precision leaves in the pressure, and the limits at which a result is flagged or
// refused (doc/guarantees.md).
#pragma once

#include <sealfe/film/film_loads.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/operating_conditions.h>

#include <nlohmann/json.hpp>

namespace sealfe
{
/// The shear (Couette) and squeeze terms of the discrete Reynolds equation are sums of
/// contributions of the size of the viscous pressure scale
///   p_visc = 6 mu (|w_r| + |w_s|) ro (ro - ri) / h_min^2 + 12 mu v (ro - ri)^2 / h_min^3,
/// (v: the axial velocity plus the tilt rates times ro) that cancel down to the pressure the film
/// carries; double precision keeps about eps * p_visc of them. Relative to the pressure range
/// (the supply pressure scale max(|po - pi|, |pi - p_ref|, |po - p_ref|), or max p - min p of the
/// solution for a film without supply pressure) this is
///   relative_error = eps * p_visc / p_range.
/// Measured on the default seal (viscosity raised): the force error is about 1/60 of it and the
/// mass-balance residual about 1/8, so it is a conservative estimate.
struct RoundOffEstimate
{
  double viscous_pressure = 0; ///< Pa
  double supply_pressure = 0;  ///< Pa, the boundary pressures' scale (0: a purely viscous film)
  double pressure_range = 0;   ///< Pa
  double relative_error = 0;   ///< eps * viscous_pressure / pressure_range

  /// Above this the result is reported with a warning (digits lost to round-off).
  static constexpr double warn_above = 1e-6;
  /// Above this the result is refused (fewer than about two digits are left), if there is a
  /// supply pressure; a purely viscous film (no boundary pressure) is only warned.
  static constexpr double refuse_above = 1e-1;

  nlohmann::json to_json() const;

  /// Absolute round-off of a load whose scale (the load the pressure range would carry) is
  /// `scale`: relative_error * scale. A computed load below it (a moment of 1e-14 N m on an
  /// axisymmetric seal) is round-off, not a result.
  double absolute_bound(double scale) const { return relative_error * scale; }
};

/// The absolute round-off bounds of the loads (summary.json round_off/absolute_bound): force
/// pressure_range * pi (ro^2 - ri^2) (N), moments that times ro (N m), leakages relative_error
/// times the mass-balance flow scale `flow_scale` (m^3/s).
nlohmann::json round_off_bounds_of_loads(const RoundOffEstimate &estimate,
                                         const FilmThickness &film, double flow_scale);

RoundOffEstimate estimate_round_off(const FilmThickness &film,
                                    const OperatingConditions &conditions, const FilmLoads &loads);

/// Throws std::runtime_error with the reason if the estimate is above refuse_above.
void refuse_round_off_collapse(const RoundOffEstimate &estimate);
} // namespace sealfe
