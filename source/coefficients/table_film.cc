#include <sealfe/coefficients/table_film.h>

#include <stdexcept>

namespace sealfe
{
TableFilm::TableFilm(std::shared_ptr<const CoefficientTable> table, const FilmThickness &geometry_,
                     const OperatingConditions &operating_, std::string table_name)
    : table_(std::move(table)), geometry(geometry_), operating(operating_),
      name(std::move(table_name))
{
  // film_model() checks that the seal is the table's (at the table's first speed nodes).
  table_->film_model(geometry, operating);
}

std::string TableFilm::description() const
{
  return "coefficient table " + name + " (" +
         (table_->interpolation() == CoefficientTable::Interpolation::linear ? "multilinear"
                                                                             : "cubic") +
         " interpolation)";
}

FilmLoads TableFilm::loads(const FilmState &state) const
{
  if (state.axial_velocity != 0.0 || state.tilt_rate_x != 0.0 || state.tilt_rate_y != 0.0)
    throw std::runtime_error("Table film: the table " + name +
                             " has no loads for a state with axial or tilt velocity (it holds "
                             "steady states only)");
  // The film is C0 + z + ...: an axial offset z is a clearance C0 + z for the table.
  FilmThickness film = state.apply(geometry);
  film.clearance += film.axial_offset;
  film.axial_offset = 0;
  const OperatingPoint point = OperatingPoint::of(film, state.apply(operating));
  FilmLoads l;
  const std::pair<const char *, double *> columns[] = {
      {"force_z", &l.force_z},
      {"moment_x", &l.moment_x},
      {"moment_y", &l.moment_y},
      {"moment_restoring", &l.moment_restoring},
      {"moment_transverse", &l.moment_transverse},
      {"leakage_inner", &l.leakage_inner},
      {"leakage_outer", &l.leakage_outer},
      {"friction_torque", &l.friction_torque},
      {"min_film", &l.min_film},
      {"max_pressure", &l.max_pressure},
      {"min_pressure", &l.min_pressure},
      {"cavitated_fraction", &l.cavitated_fraction}};
  for (const auto &[column, value] : columns)
  {
    if (!table_->has_column(column))
      throw std::runtime_error("Table film: the table " + name +
                               " has no loads for this state (no " + column + " column)");
    *value = table_->value(column, point);
  }
  return l;
}

FilmCoefficients TableFilm::coefficients(const FilmState &state) const
{
  return table_->coefficients(state.apply(geometry), state.apply(operating));
}

} // namespace sealfe
