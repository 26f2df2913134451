// The film of the ring dynamics at the level the parameter file chooses (doc/reynolds.md, Levels):
// the FilmForceModel of that level for one seal, and the film coefficients at any pair of ring
// speeds drawn from it (computed once per pair).
#pragma once

#include <sealfe/coefficients/coefficient_solver.h>
#include <sealfe/coefficients/coefficient_table.h>
#include <sealfe/dynamics/angular_dynamics.h>
#include <sealfe/film/film_force_model.h>
#include <sealfe/film/film_settings.h>

#include <deal.II/base/mpi.h>

#include <memory>

namespace sealfe
{
/// What a level needs beyond the seal: level 1 the table (read beforehand), level 2 the
/// finite-element solver's settings (its geometry and operating conditions are replaced by the
/// seal's) and the communicator of its solves.
struct FilmLevelSources
{
  std::shared_ptr<const CoefficientTable> table;
  std::string table_name; ///< the table's file, for descriptions
  FilmSettings film_solver;
  CoefficientSettings coefficient_method;
  MPI_Comm comm = MPI_COMM_SELF;
};

/// The FilmForceModel of `level` for the seal `geometry`, `operating`: NarrowSealFilm (level 0),
/// TableFilm (level 1, needs sources.table), FiniteElementFilm (level 2, on sources.film_solver
/// and sources.comm). Throws std::runtime_error (one line) when the level cannot be built.
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
