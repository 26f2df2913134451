// ClosedFormTransientFilm: a level-0 FilmForceModel for the transient — the narrow-seal pressure
// (NarrowSealModel: hydrostatic coned part, wedge and squeeze, half-Sommerfeld) of Green 2002
// Eq. 23, loads by quadrature; coefficients by central differences of the loads.
#pragma once

#include <sealfe/closed_form/narrow_seal.h>
#include <sealfe/film/film_force_model.h>

namespace sealfe
{
/// Stand-in for the level-0 film of the dynamics branch (closed_form/narrow_seal_film.h) with the
/// same physics, kept under its own name so that both can coexist until they are merged.
class ClosedFormTransientFilm : public FilmForceModel
{
public:
  ClosedFormTransientFilm(const FilmThickness &geometry, const OperatingConditions &conditions,
                          Cavitation cavitation, const NarrowSealQuadrature &quadrature,
                          double cavitation_pressure = 0);
  FilmLevel level() const override { return FilmLevel::closed_form; }
  std::string description() const override;
  /// Throws std::runtime_error where the film touches down (h <= 0 somewhere).
  FilmLoads loads(const FilmState &state) const override;
  FilmCoefficients coefficients(const FilmState &state) const override;
  unsigned long evaluations() const { return evaluations_; }

private:
  FilmThickness geometry_;
  OperatingConditions conditions_;
  Cavitation cavitation_;
  double cavitation_pressure_;
  NarrowSealQuadrature quadrature_;
  mutable unsigned long evaluations_ = 0;
};

/// Stiffness and damping of any FilmForceModel by central differences of its loads about
/// `state` (steps: dz = 1e-3 of the min film, tilt dz / ro, rates: steps / 1 s... see .cc).
FilmCoefficients central_difference_coefficients(const FilmForceModel &film, const FilmState &state,
                                                 double min_film, double outer_radius);
} // namespace sealfe
