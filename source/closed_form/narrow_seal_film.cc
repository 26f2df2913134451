#include <sealfe/closed_form/green_etsion.h>
#include <sealfe/closed_form/narrow_seal_film.h>

#include <stdexcept>
#include <string>

namespace sealfe
{
NarrowSealFilm::NarrowSealFilm(const FilmThickness &geometry_,
                               const OperatingConditions &operating_,
                               const NarrowSealQuadrature &quadrature_,
                               const Cavitation cavitation_, const double cavitation_pressure_)
    : geometry(geometry_), operating(operating_), quadrature(quadrature_), cavitation(cavitation_),
      cavitation_pressure(cavitation_pressure_)
{
  GreenEtsionCoefficients check(geometry, operating); // throws on an impossible narrow seal
  // The loads (NarrowSealModel) refuse surface features too, but a study that needs only the
  // coefficients would never ask for them: refuse here, before any work.
  if (geometry.features)
    throw std::runtime_error("Film model = closed form: surface features (Geometry/Surface "
                             "features) need Film model = finite element (or a table of it)");
}

std::string NarrowSealFilm::description() const
{
  return std::string("narrow seal, ") +
         (cavitation == Cavitation::half_sommerfeld ? "half-Sommerfeld" : "full-film") +
         " loads; Green & Etsion coefficients";
}

FilmLoads NarrowSealFilm::loads(const FilmState &state) const
{
  const NarrowSealModel model(state.apply(geometry), state.apply(operating), cavitation,
                              cavitation_pressure);
  return model.loads(quadrature);
}

FilmCoefficients NarrowSealFilm::coefficients(const FilmState &state) const
{
  // Green & Etsion's coefficients are those of a coned (and tilted) flat face: they would
  // silently drop a wave or a film formula that the narrow-seal loads do integrate.
  if (geometry.wave_amplitude != 0 || geometry.expression)
    throw std::runtime_error(
        std::string("Film model = closed form: the Green & Etsion stiffness and damping are those "
                    "of a coned face, without ") +
        (geometry.expression ? "a film expression (Geometry/Film expression)"
                             : "waviness (Geometry/Wave amplitude)") +
        "; use Film model = finite element (or a table of it)");
  const GreenEtsionCoefficients g(state.apply(geometry), state.apply(operating));
  return g.coefficients(state.rotor_speed, state.stator_speed);
}

} // namespace sealfe
