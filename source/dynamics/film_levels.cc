#include <sealfe/closed_form/narrow_seal_film.h>
#include <sealfe/coefficients/finite_element_film.h>
#include <sealfe/coefficients/table_film.h>
#include <sealfe/dynamics/film_levels.h>
#include <sealfe/dynamics/shared_cache.h>

#include <stdexcept>

namespace sealfe
{
std::shared_ptr<const FilmForceModel> make_film_force_model(const FilmLevel level,
                                                            const FilmThickness &geometry,
                                                            const OperatingConditions &operating,
                                                            const FilmLevelSources &sources)
{
  switch (level)
  {
  case FilmLevel::closed_form:
    return std::make_shared<NarrowSealFilm>(geometry, operating);
  case FilmLevel::table:
    if (!sources.table)
      throw std::runtime_error("Seal dynamics: Film model = table needs a Table file (the CSV "
                               "written by sealfe table)");
    return std::make_shared<TableFilm>(sources.table, geometry, operating, sources.table_name);
  case FilmLevel::finite_element:
  {
    FilmSettings settings = sources.film_solver;
    settings.geometry = geometry;
    settings.conditions = operating;
    return std::make_shared<FiniteElementFilm>(settings, sources.comm, sources.coefficient_method);
  }
  }
  throw std::runtime_error("Seal dynamics: unknown film level");
}

FilmModel coefficients_at_speeds(std::shared_ptr<const FilmForceModel> model, const FilmState &base)
{
  SharedCache<std::pair<double, double>, FilmCoefficients> cache;
  return
      [model = std::move(model), base, cache](const double rotor_speed, const double stator_speed)
  {
    return cache.get({rotor_speed, stator_speed},
                     [&]
                     {
                       FilmState s = base;
                       s.rotor_speed = rotor_speed;
                       s.stator_speed = stator_speed;
                       return model->coefficients(s);
                     });
  };
}

} // namespace sealfe
