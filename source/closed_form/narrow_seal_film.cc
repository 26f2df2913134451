#include <sealfe/closed_form/green_etsion.h>
#include <sealfe/closed_form/narrow_seal_film.h>

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
  const GreenEtsionCoefficients g(state.apply(geometry), state.apply(operating));
  return g.coefficients(state.rotor_speed, state.stator_speed);
}

} // namespace sealfe
