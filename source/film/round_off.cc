#include <sealfe/film/round_off.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
RoundOffEstimate estimate_round_off(const FilmThickness &film,
                                    const OperatingConditions &conditions, const FilmLoads &loads)
{
  const double ri = film.inner_radius, ro = film.outer_radius, width = ro - ri;
  // the thinnest film carries the largest viscous terms (the clearance if the faces touch)
  const double h = loads.min_film > 0 ? loads.min_film : film.clearance;
  const double mu = conditions.viscosity;
  const double speed = std::abs(conditions.rotor_speed) + std::abs(conditions.stator_speed);
  const double squeeze_velocity = std::abs(film.axial_velocity) +
                                  (std::abs(film.tilt_rate_x) + std::abs(film.tilt_rate_y)) * ro;
  RoundOffEstimate e;
  e.viscous_pressure = 6 * mu * speed * ro * width / (h * h) +
                       12 * mu * squeeze_velocity * width * width / (h * h * h);
  e.supply_pressure =
      std::max({std::abs(conditions.outer_pressure - conditions.inner_pressure),
                std::abs(conditions.inner_pressure - conditions.reference_pressure),
                std::abs(conditions.outer_pressure - conditions.reference_pressure)});
  // Not max p - min p when there is a supply pressure: at collapse that range is itself round-off
  // and would hide it (the estimate would saturate near 0.1).
  e.pressure_range = e.supply_pressure > 0 ? e.supply_pressure
                                           : std::max(loads.max_pressure - loads.min_pressure,
                                                      std::numeric_limits<double>::min());
  e.relative_error = std::numeric_limits<double>::epsilon() * e.viscous_pressure / e.pressure_range;
  return e;
}

nlohmann::json RoundOffEstimate::to_json() const
{
  nlohmann::json j = {{"relative_error", relative_error},
                      {"viscous_pressure", viscous_pressure},
                      {"pressure_range", pressure_range},
                      {"definition",
                       "eps * viscous pressure scale / pressure range: the relative "
                       "pressure error double precision can leave (doc/guarantees.md)"}};
  if (relative_error > warn_above)
  {
    std::ostringstream s;
    s.precision(2);
    s << "round-off: the viscous terms are " << viscous_pressure / pressure_range
      << " times the pressure range, so about " << relative_error
      << " of the pressure is round-off (warned above " << warn_above << ")";
    j["warning"] = s.str();
  }
  return j;
}

nlohmann::json round_off_bounds_of_loads(const RoundOffEstimate &estimate,
                                         const FilmThickness &film, const double flow_scale)
{
  const double ri = film.inner_radius, ro = film.outer_radius;
  const double force_scale = estimate.pressure_range * M_PI * (ro * ro - ri * ri);
  const double force = estimate.absolute_bound(force_scale);
  const double moment = estimate.absolute_bound(force_scale * ro);
  const double leakage = estimate.absolute_bound(flow_scale);
  return {{"force_z", force},
          {"moment_x", moment},
          {"moment_y", moment},
          {"leakage_inner", leakage},
          {"leakage_outer", leakage}};
}

void refuse_round_off_collapse(const RoundOffEstimate &e)
{
  // Without a supply pressure the pressure range is the film's own (possibly all round-off, as
  // for a shear-only axisymmetric film whose true pressure is 0): warned, not refused.
  if (!(e.relative_error > RoundOffEstimate::refuse_above) || !(e.supply_pressure > 0))
    return;
  std::ostringstream s;
  s.precision(3);
  s << "round-off collapse: the viscous (shear and squeeze) terms of the film equation, "
    << e.viscous_pressure << " Pa, are " << e.viscous_pressure / e.pressure_range
    << " times the pressure range of the film, " << e.pressure_range
    << " Pa, so double precision leaves a relative error of about " << e.relative_error
    << " in the pressure (limit " << RoundOffEstimate::refuse_above
    << "): lower the viscosity or speeds, or raise the film thickness or pressures";
  throw std::runtime_error(s.str());
}
} // namespace sealfe
