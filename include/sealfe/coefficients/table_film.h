// TableFilm: the level-1 film seen by the ring dynamics — stiffness, damping and (where the table
// has them) loads interpolated in a CoefficientTable of finite-element results.
#pragma once

#include <sealfe/coefficients/coefficient_table.h>
#include <sealfe/film/film_force_model.h>

#include <memory>

namespace sealfe
{
/// Level 1 of FilmForceModel for one seal: the table, read beforehand, and the seal's geometry
/// and operating point (everything the table did not sweep must equal the table's values).
class TableFilm : public FilmForceModel
{
public:
  /// Throws std::runtime_error (one line) if the seal is not the table's (a quantity the table
  /// did not sweep differs), checked at the table's first speed nodes.
  TableFilm(std::shared_ptr<const CoefficientTable> table, const FilmThickness &geometry,
            const OperatingConditions &operating, std::string table_name);

  FilmLevel level() const override { return FilmLevel::table; }
  std::string description() const override;
  /// The table's load columns at the state (axial offset as a change of clearance; tilt as tilt
  /// and tilt angle). A tilt in another direction than the table's (tilt angle not swept, no
  /// waviness) is turned onto the table's direction and the moments turned back: an axisymmetric
  /// face is invariant under rotation. Squeeze rates add -D v with the table's damping at the
  /// state: exact for a full film (the Reynolds pressure is linear in the squeeze rates at fixed
  /// h), a linearisation in the rates where the film cavitates. Throws std::runtime_error (one
  /// line) when the table has no loads for the state (outside it, or load columns missing).
  FilmLoads loads(const FilmState &state) const override;
  /// CoefficientTable::coefficients at the state (the state's tilt, coning, speeds, pressures).
  FilmCoefficients coefficients(const FilmState &state) const override;

  const CoefficientTable &table() const { return *table_; }

private:
  std::shared_ptr<const CoefficientTable> table_;
  FilmThickness geometry;
  OperatingConditions operating;
  std::string name;
};

} // namespace sealfe
