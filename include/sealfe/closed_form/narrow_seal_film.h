// NarrowSealFilm: the level-0 film seen by the ring dynamics — loads from the narrow-seal
// closed-form pressure (NarrowSealModel, squeeze terms included, half-Sommerfeld), stiffness and
// damping from Green & Etsion's closed forms (GreenEtsionCoefficients).
#pragma once

#include <sealfe/closed_form/narrow_seal.h>
#include <sealfe/film/film_force_model.h>

namespace sealfe
{
/// Level 0 of FilmForceModel for one seal: the geometry (radii, C0, waviness) and operating point
/// (viscosity, reference pressure) given here, position, velocities, coning, speeds and pressures
/// from the FilmState.
class NarrowSealFilm : public FilmForceModel
{
public:
  /// Throws std::runtime_error (one line) if the untilted seal makes no narrow-seal film (the
  /// checks of GreenEtsionCoefficients).
  NarrowSealFilm(const FilmThickness &geometry, const OperatingConditions &operating,
                 const NarrowSealQuadrature &quadrature = {},
                 Cavitation cavitation = Cavitation::half_sommerfeld,
                 double cavitation_pressure = 0);

  FilmLevel level() const override { return FilmLevel::closed_form; }
  std::string description() const override;
  /// NarrowSealModel loads (half-Sommerfeld at p_cav by default, or full film) of the film at
  /// `state`.
  FilmLoads loads(const FilmState &state) const override;
  /// GreenEtsionCoefficients about the untilted face at the state's coning, pressures and
  /// speeds (the state's position, tilt and velocities do not enter: the closed forms are the
  /// linearisation about the axisymmetric equilibrium at clearance C0).
  FilmCoefficients coefficients(const FilmState &state) const override;

private:
  FilmThickness geometry;
  OperatingConditions operating;
  NarrowSealQuadrature quadrature;
  Cavitation cavitation;
  double cavitation_pressure;
};

} // namespace sealfe
