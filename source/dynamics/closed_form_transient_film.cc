#include <sealfe/dynamics/closed_form_transient_film.h>

#include <cmath>

namespace sealfe
{
ClosedFormTransientFilm::ClosedFormTransientFilm(const FilmThickness &geometry,
                                                 const OperatingConditions &conditions,
                                                 const Cavitation cavitation,
                                                 const NarrowSealQuadrature &quadrature,
                                                 const double cavitation_pressure)
    : geometry_(geometry), conditions_(conditions), cavitation_(cavitation),
      cavitation_pressure_(cavitation_pressure), quadrature_(quadrature)
{
}

std::string ClosedFormTransientFilm::description() const
{
  return std::string("narrow seal (level 0), ") +
         (cavitation_ == Cavitation::half_sommerfeld ? "half-Sommerfeld" : "full film") + ", " +
         std::to_string(quadrature_.radial_points) + " x " +
         std::to_string(quadrature_.angular_points) + " quadrature";
}

FilmLoads ClosedFormTransientFilm::loads(const FilmState &state) const
{
  ++evaluations_;
  const NarrowSealModel model(state.apply(geometry_), state.apply(conditions_), cavitation_,
                              cavitation_pressure_);
  return model.loads(quadrature_);
}

FilmCoefficients ClosedFormTransientFilm::coefficients(const FilmState &state) const
{
  return central_difference_coefficients(*this, state, state.apply(geometry_).minimum().value,
                                         geometry_.outer_radius);
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
