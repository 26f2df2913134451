#include <sealfe/film/film_force_model.h>

#include <array>
#include <cmath>
#include <stdexcept>

namespace sealfe
{
std::string to_string(const FilmLevel level)
{
  switch (level)
  {
  case FilmLevel::closed_form:
    return "closed form";
  case FilmLevel::table:
    return "table";
  case FilmLevel::finite_element:
    return "finite element";
  }
  return "unknown";
}

FilmLevel film_level_from_string(const std::string &name)
{
  for (const FilmLevel level :
       {FilmLevel::closed_form, FilmLevel::table, FilmLevel::finite_element})
    if (name == to_string(level))
      return level;
  throw std::runtime_error("unknown film model \"" + name + "\" (expected " + film_level_pattern() +
                           ")");
}

std::string film_level_pattern()
{
  return "closed form|table|finite element";
}

FilmState FilmState::from(const FilmThickness &film, const OperatingConditions &conditions)
{
  FilmState s;
  s.axial_offset = film.axial_offset;
  s.tilt_x = film.tilt_x();
  s.tilt_y = film.tilt_y();
  s.axial_velocity = film.axial_velocity;
  s.tilt_rate_x = film.tilt_rate_x;
  s.tilt_rate_y = film.tilt_rate_y;
  s.coning = film.coning;
  s.rotor_speed = conditions.rotor_speed;
  s.stator_speed = conditions.stator_speed;
  s.inner_pressure = conditions.inner_pressure;
  s.outer_pressure = conditions.outer_pressure;
  return s;
}

FilmThickness FilmState::apply(FilmThickness base) const
{
  base.axial_offset = axial_offset;
  base.set_tilt_vector(tilt_x, tilt_y);
  base.axial_velocity = axial_velocity;
  base.tilt_rate_x = tilt_rate_x;
  base.tilt_rate_y = tilt_rate_y;
  base.coning = coning;
  base.time = time; // the t of a film expression
  return base;
}

OperatingConditions FilmState::apply(OperatingConditions base) const
{
  base.rotor_speed = rotor_speed;
  base.stator_speed = stator_speed;
  base.inner_pressure = inner_pressure;
  base.outer_pressure = outer_pressure;
  return base;
}

FilmState FilmState::turned(const double angle) const
{
  FilmState s = *this;
  const auto tilt = sealfe::turned({{tilt_x, tilt_y}}, angle);
  const auto rate = sealfe::turned({{tilt_rate_x, tilt_rate_y}}, angle);
  s.tilt_x = tilt[0];
  s.tilt_y = tilt[1];
  s.tilt_rate_x = rate[0];
  s.tilt_rate_y = rate[1];
  return s;
}

double FilmState::feature_frame_angle(const FilmThickness &base) const
{
  return base.features_on_rotor() ? rotor_angle : 0.0;
}

FilmThickness FilmState::in_feature_frame(const FilmThickness &base) const
{
  return apply(base).turned_frame(feature_frame_angle(base));
}

FilmLoads FilmState::turned_back(FilmLoads loads, const FilmThickness &base) const
{
  // force, leakages, friction, extrema, moment_restoring/transverse (taken about the tilt's
  // direction, which turned with the frame) do not depend on the frame
  const double angle = feature_frame_angle(base);
  if (angle == 0)
    return loads;
  const auto m = sealfe::turned({{loads.moment_x, loads.moment_y}}, angle);
  const auto c = sealfe::turned({{loads.contact_moment_x, loads.contact_moment_y}}, angle);
  loads.moment_x = m[0];
  loads.moment_y = m[1];
  loads.contact_moment_x = c[0];
  loads.contact_moment_y = c[1];
  return loads;
}

std::array<double, 2> turned(const std::array<double, 2> &v, const double angle)
{
  const double c = std::cos(angle), s = std::sin(angle);
  return {{c * v[0] - s * v[1], s * v[0] + c * v[1]}};
}

std::array<double, 2> tilt_vector(const double magnitude, const double angle)
{
  return {{magnitude * std::sin(angle), -magnitude * std::cos(angle)}};
}

FilmCoefficients central_difference_coefficients(const FilmForceModel &film, const FilmState &state,
                                                 const double min_film, const double outer_radius)
{
  FilmCoefficients k;
  k.level = static_cast<int>(film.level());
  k.model = film.description() + ", central differences";
  k.rotor_speed = state.rotor_speed;
  k.stator_speed = state.stator_speed;
  const double dz = 1e-3 * min_film, da = dz / outer_radius;
  // rates: a squeeze velocity that moves the face by dz in 1 ms
  const double dv = dz / 1e-3, dw = da / 1e-3;
  auto forces = [&](const FilmState &s)
  {
    const FilmLoads l = film.loads(s);
    return std::array<double, 3>{{l.force_z, l.moment_x, l.moment_y}};
  };
  double FilmState::*pos[] = {&FilmState::axial_offset, &FilmState::tilt_x, &FilmState::tilt_y};
  double FilmState::*vel[] = {&FilmState::axial_velocity, &FilmState::tilt_rate_x,
                              &FilmState::tilt_rate_y};
  for (int j = 0; j < 3; ++j)
    for (int which = 0; which < 2; ++which)
    {
      double FilmState::*m = which == 0 ? pos[j] : vel[j];
      const double step = which == 0 ? (j == 0 ? dz : da) : (j == 0 ? dv : dw);
      FilmState plus = state, minus = state;
      plus.*m += step;
      minus.*m -= step;
      const auto fp = forces(plus), fm = forces(minus);
      for (int i = 0; i < 3; ++i)
        (which == 0 ? k.stiffness : k.damping)[i][j] = -(fp[i] - fm[i]) / (2 * step);
    }
  return k;
}
} // namespace sealfe
