// The film of the ring dynamics at the level the parameter file chooses (doc/reynolds.md, Levels):
// the FilmForceModel of that level for one seal, and the film coefficients at any pair of ring
// speeds drawn from it (computed once per pair).
#pragma once

#include <sealfe/coefficients/coefficient_table.h>
#include <sealfe/dynamics/angular_dynamics.h>
#include <sealfe/film/film_force_model.h>

#include <functional>
#include <memory>

namespace sealfe
{
/// The level-2 coefficient producer the application supplies today (a CoefficientSolver on
/// MPI_COMM_SELF): the coefficients of a film and operating point.
/// TODO(FiniteElementFilm): remove once coefficients/finite_element_film.h lands; level 2 is then
/// built in make_film_force_model from FilmSettings + MPI_Comm (see FilmLevelSources).
using FilmCoefficientProvider = std::function<FilmCoefficients(
    const FilmThickness &film, const OperatingConditions &conditions)>;

/// What a level needs beyond the seal: level 1 the table (read beforehand), level 2 the
/// finite-element film.
/// TODO(FiniteElementFilm): replace `finite_element` by `FilmSettings finite_element;` and
/// `MPI_Comm comm = MPI_COMM_SELF;` and build `std::make_shared<FiniteElementFilm>(finite_element,
/// comm)` in make_film_force_model (the only place that knows the hook).
struct FilmLevelSources
{
  std::shared_ptr<const CoefficientTable> table;
  std::string table_name; ///< the table's file, for descriptions
  FilmCoefficientProvider finite_element;
};

/// The FilmForceModel of `level` for the seal `geometry`, `operating`: NarrowSealFilm (level 0),
/// TableFilm (level 1, needs sources.table), the finite-element film (level 2, needs
/// sources.finite_element). Throws std::runtime_error (one line) when the level cannot be built.
std::shared_ptr<const FilmForceModel> make_film_force_model(FilmLevel level,
                                                            const FilmThickness &geometry,
                                                            const OperatingConditions &operating,
                                                            const FilmLevelSources &sources);

/// The film coefficients of `model` at any pair of ring speeds, the rest of the state being
/// `base` (the seal's equilibrium): model->coefficients with the speeds written into `base`,
/// computed once per speed pair (copies of the returned function share the results).
FilmModel coefficients_at_speeds(std::shared_ptr<const FilmForceModel> model,
                                 const FilmState &base);

} // namespace sealfe
