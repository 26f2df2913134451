#include <sealfe/closed_form/narrow_seal_film.h>
#include <sealfe/coefficients/table_film.h>
#include <sealfe/dynamics/film_levels.h>
#include <sealfe/dynamics/shared_cache.h>

#include <stdexcept>

namespace sealfe
{
namespace
{
/// Level 2 through the application's coefficient producer: coefficients only.
/// TODO(FiniteElementFilm): delete this class; FiniteElementFilm replaces it.
class ProducedFiniteElementFilm : public FilmForceModel
{
public:
  ProducedFiniteElementFilm(FilmCoefficientProvider producer, const FilmThickness &geometry,
                            const OperatingConditions &operating)
      : producer(std::move(producer)), geometry(geometry), operating(operating)
  {
  }
  FilmLevel level() const override { return FilmLevel::finite_element; }
  std::string description() const override { return "finite element (application's solver)"; }
  FilmLoads loads(const FilmState &) const override
  {
    throw std::runtime_error("Seal dynamics: the finite-element film of the coefficient hook "
                             "gives no loads");
  }
  FilmCoefficients coefficients(const FilmState &state) const override
  {
    FilmCoefficients k = producer(state.apply(geometry), state.apply(operating));
    k.level = 2;
    k.rotor_speed = state.rotor_speed;
    k.stator_speed = state.stator_speed;
    return k;
  }

private:
  FilmCoefficientProvider producer;
  FilmThickness geometry;
  OperatingConditions operating;
};
} // namespace

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
    // TODO(FiniteElementFilm): return std::make_shared<FiniteElementFilm>(sources.finite_element,
    // sources.comm) with the geometry and operating point.
    if (!sources.finite_element)
      throw std::runtime_error("Seal dynamics: Film model = finite element needs the "
                               "finite-element solver, which the sealfe application supplies "
                               "(SealDynamicsInput::finite_element is empty)");
    return std::make_shared<ProducedFiniteElementFilm>(sources.finite_element, geometry, operating);
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
