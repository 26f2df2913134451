#include <sealfe/coefficients/table_film.h>

#include <algorithm>

#include <stdexcept>

namespace sealfe
{
TableFilm::TableFilm(std::shared_ptr<const CoefficientTable> table, const FilmThickness &geometry_,
                     const OperatingConditions &operating_, std::string table_name)
    : table_(std::move(table)), geometry(geometry_), operating(operating_),
      name(std::move(table_name))
{
  // Fail now if the seal is not the table's: every quantity the table did not sweep must be the
  // table's; the swept ones are set to their first node, since the transient moves the
  // clearance (C0 + z), coning, tilt, speed and pressure away from the seal's nominal values.
  OperatingPoint p = OperatingPoint::of(geometry, operating);
  for (unsigned int a = 0; a < table_->axes().size(); ++a)
    p.set(table_->axes()[a], table_->axis_values(a).front());
  table_->coefficients(p);
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
  // turn a tilt onto the table's direction (rotational invariance of an axisymmetric face: not
  // with waviness, a film formula or surface features, whose loads the table holds at their
  // own angle; a tilt in another direction is then outside the table)
  if (geometry.features_on_rotor() && state.rotor_angle != 0)
    throw std::runtime_error("Table film: the table holds the loads of the rotor's surface "
                             "features at one rotor angle (Phase), not at a turned rotor");
  const auto &axes = table_->axes();
  const bool angle_swept = std::find(axes.begin(), axes.end(), "tilt_angle") != axes.end();
  const double turn =
      (!angle_swept && !geometry.has_angular_pattern() && (state.tilt_x != 0 || state.tilt_y != 0))
          ? table_->constant_point().tilt_angle - state.apply(geometry).tilt_angle
          : 0.0;
  const FilmState s = state.turned(turn);
  // The film is C0 + z + ...: an axial offset z is a clearance C0 + z for the table.
  FilmThickness film = s.apply(geometry);
  film.clearance += film.axial_offset;
  film.axial_offset = 0;
  OperatingPoint point = OperatingPoint::of(film, s.apply(operating));
  if (turn != 0.0)
    point.tilt_angle = table_->constant_point().tilt_angle; // turned onto it, up to round-off
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
  const double v[3] = {s.axial_velocity, s.tilt_rate_x, s.tilt_rate_y};
  if (v[0] != 0 || v[1] != 0 || v[2] != 0)
  {
    const FilmCoefficients k = table_->coefficients(point);
    double *load[3] = {&l.force_z, &l.moment_x, &l.moment_y};
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        *load[i] -= k.damping[i][j] * v[j];
  }
  const auto moment = turned({{l.moment_x, l.moment_y}}, -turn);
  l.moment_x = moment[0];
  l.moment_y = moment[1];
  return l;
}

FilmCoefficients TableFilm::coefficients(const FilmState &state) const
{
  return table_->coefficients(state.apply(geometry), state.apply(operating));
}

} // namespace sealfe
