#include <sealfe/coefficients/coefficient_table.h>
#include <sealfe/io/csv.h>
#include <sealfe/numerics/lagrange_interpolation.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
// ------------------------------------------------------------------------------------------------
// OperatingPoint

const std::vector<std::pair<std::string, std::string>> &OperatingPoint::columns()
{
  static const std::vector<std::pair<std::string, std::string>> c = {
      {"rotor_speed", "rad/s"}, {"stator_speed", "rad/s"}, {"clearance", "m"},
      {"coning", "rad"},        {"tilt", "rad"},           {"pressure_difference", "Pa"},
      {"viscosity", "Pa s"},    {"tilt_angle", "rad"},     {"inner_pressure", "Pa"},
      {"inner_radius", "m"},    {"outer_radius", "m"}};
  return c;
}

namespace
{
/// The OperatingPoint field of a column name (nullptr if it is not one).
template <typename Point>
auto field(Point &p, const std::string &name) -> decltype(&p.rotor_speed)
{
  if (name == "rotor_speed")
    return &p.rotor_speed;
  if (name == "stator_speed")
    return &p.stator_speed;
  if (name == "clearance")
    return &p.clearance;
  if (name == "coning")
    return &p.coning;
  if (name == "tilt")
    return &p.tilt;
  if (name == "pressure_difference")
    return &p.pressure_difference;
  if (name == "viscosity")
    return &p.viscosity;
  if (name == "tilt_angle")
    return &p.tilt_angle;
  if (name == "inner_pressure")
    return &p.inner_pressure;
  if (name == "inner_radius")
    return &p.inner_radius;
  if (name == "outer_radius")
    return &p.outer_radius;
  return nullptr;
}
} // namespace

double OperatingPoint::get(const std::string &name) const
{
  const double *f = field(*this, name);
  if (!f)
    throw std::runtime_error("OperatingPoint: no quantity named '" + name + "'");
  return *f;
}

void OperatingPoint::set(const std::string &name, const double value)
{
  double *f = field(*this, name);
  if (!f)
    throw std::runtime_error("OperatingPoint: no quantity named '" + name + "'");
  *f = value;
}

OperatingPoint OperatingPoint::of(const FilmThickness &film, const OperatingConditions &conditions)
{
  OperatingPoint p;
  p.rotor_speed = conditions.rotor_speed;
  p.stator_speed = conditions.stator_speed;
  p.clearance = film.clearance;
  p.coning = film.coning;
  p.tilt = film.tilt;
  p.pressure_difference = conditions.outer_pressure - conditions.inner_pressure;
  p.viscosity = conditions.viscosity;
  p.tilt_angle = film.tilt_angle;
  p.inner_pressure = conditions.inner_pressure;
  p.inner_radius = film.inner_radius;
  p.outer_radius = film.outer_radius;
  return p;
}

void OperatingPoint::apply(FilmThickness &film, OperatingConditions &conditions) const
{
  conditions.rotor_speed = rotor_speed;
  conditions.stator_speed = stator_speed;
  conditions.viscosity = viscosity;
  conditions.inner_pressure = inner_pressure;
  conditions.outer_pressure = inner_pressure + pressure_difference;
  film.clearance = clearance;
  film.coning = coning;
  film.tilt = tilt;
  film.tilt_angle = tilt_angle;
  film.inner_radius = inner_radius;
  film.outer_radius = outer_radius;
}

// ------------------------------------------------------------------------------------------------
// CSV layout

namespace coefficient_table_format
{
namespace
{
const char *dof_name[3] = {"z", "tx", "ty"};

std::string coefficient_unit(const bool stiffness, const unsigned int i, const unsigned int j)
{
  std::string u = i == 0 ? "N" : "N m";
  if (!stiffness)
    u += " s";
  return u + (j == 0 ? "/m" : "/rad");
}
} // namespace

std::string coefficient_name(const bool stiffness, const unsigned int i, const unsigned int j)
{
  return std::string(stiffness ? "K_" : "D_") + dof_name[i] + "_" + dof_name[j];
}

std::vector<std::pair<std::string, std::string>> output_columns(const bool with_errors)
{
  std::vector<std::pair<std::string, std::string>> c = {{"force_z", "N"},
                                                        {"moment_x", "N m"},
                                                        {"moment_y", "N m"},
                                                        {"moment_restoring", "N m"},
                                                        {"moment_transverse", "N m"},
                                                        {"leakage_inner", "m^3/s"},
                                                        {"leakage_outer", "m^3/s"},
                                                        {"friction_torque", "N m"},
                                                        {"min_film", "m"},
                                                        {"max_pressure", "Pa"},
                                                        {"min_pressure", "Pa"},
                                                        {"cavitated_fraction", csv::dimensionless}};
  for (const bool stiffness : {true, false})
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        c.emplace_back(coefficient_name(stiffness, i, j), coefficient_unit(stiffness, i, j));
  if (with_errors)
    for (const bool stiffness : {true, false})
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          c.emplace_back("err_" + coefficient_name(stiffness, i, j),
                         coefficient_unit(stiffness, i, j));
  c.emplace_back("dofs", csv::dimensionless);
  return c;
}

std::string header(const bool with_errors)
{
  std::vector<csv::Column> c = {{"index", csv::dimensionless}, {"role", ""}};
  for (const auto &[name, unit] : OperatingPoint::columns())
    c.push_back({name, unit});
  for (const auto &[name, unit] : output_columns(with_errors))
    c.push_back({name, unit});
  c.push_back({"status", ""});
  return csv::header(c);
}

std::string sanitize(const std::string &message)
{
  return csv::text_field(message);
}
} // namespace coefficient_table_format

// ------------------------------------------------------------------------------------------------
// Reading

namespace
{
std::vector<std::string> split(const std::string &line)
{
  std::vector<std::string> fields;
  std::string f;
  std::istringstream s(line);
  while (std::getline(s, f, ','))
    fields.push_back(f);
  if (!line.empty() && line.back() == ',')
    fields.emplace_back();
  return fields;
}

std::string trim(const std::string &s)
{
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos)
    return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

/// "name [unit]" -> "name"
std::string column_name(const std::string &field)
{
  const std::string f = trim(field);
  const auto bracket = f.find(" [");
  return bracket == std::string::npos ? f : trim(f.substr(0, bracket));
}

bool same_value(const double a, const double b)
{
  return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b));
}

std::string describe(const OperatingPoint &p, const std::vector<std::string> &names)
{
  std::ostringstream s;
  s.precision(6);
  for (unsigned int i = 0; i < names.size(); ++i)
    s << (i ? ", " : "") << names[i] << " = " << p.get(names[i]);
  return s.str();
}
} // namespace

CoefficientTable::CoefficientTable(const std::string &csv_file, const Interpolation interpolation)
    : method(interpolation)
{
  std::ifstream in(csv_file);
  if (!in)
    throw std::runtime_error("coefficient table '" + csv_file + "' is missing or unreadable");
  std::stringstream text;
  text << in.rdbuf();
  parse(text.str(), csv_file);
  build_grid();
}

CoefficientTable CoefficientTable::from_text(const std::string &csv_text, const std::string &name,
                                             const Interpolation interpolation)
{
  CoefficientTable t;
  t.method = interpolation;
  t.parse(csv_text, name);
  t.build_grid();
  return t;
}

void CoefficientTable::parse(const std::string &text, const std::string &name)
{
  source = name;
  auto fail = [&](const unsigned int line, const std::string &what)
  {
    throw std::runtime_error("coefficient table '" + name + "' line " + std::to_string(line) +
                             ": " + what);
  };
  std::istringstream in(text);
  std::string line;
  unsigned int line_number = 0;
  unsigned int role_column = 0, status_column = 0;
  bool have_header = false;
  while (std::getline(in, line))
  {
    ++line_number;
    if (trim(line).empty())
      continue;
    const std::vector<std::string> fields = split(line);
    if (!have_header)
    {
      for (unsigned int c = 0; c < fields.size(); ++c)
      {
        const std::string n = column_name(fields[c]);
        if (column_index.count(n))
          fail(line_number, "column '" + n + "' appears twice");
        column_index[n] = c;
        column_names.push_back(n);
      }
      for (const char *required : {"role", "status"})
        if (!column_index.count(required))
          fail(line_number, std::string("the header has no '") + required +
                                "' column (not a table written by sealfe table)");
      for (const auto &[n, unit] : OperatingPoint::columns())
        if (!column_index.count(n))
          fail(line_number, "the header has no '" + n + "' column");
      role_column = column_index["role"];
      status_column = column_index["status"];
      have_header = true;
      continue;
    }
    if (fields.size() != column_names.size())
      fail(line_number, "has " + std::to_string(fields.size()) + " fields, the header " +
                            std::to_string(column_names.size()));
    Row row;
    row.line = line_number;
    row.values.assign(fields.size(), std::numeric_limits<double>::quiet_NaN());
    row.status = trim(fields[status_column]);
    row.ok = row.status == "ok";
    if (!row.ok && row.status.rfind("failed", 0) != 0)
      fail(line_number, "status must be 'ok' or 'failed: ...' (got '" + row.status + "')");
    for (unsigned int c = 0; c < fields.size(); ++c)
    {
      if (c == role_column || c == status_column)
        continue;
      const std::string f = trim(fields[c]);
      char *end = nullptr;
      const double v = std::strtod(f.c_str(), &end);
      if (f.empty() || end != f.c_str() + f.size())
        fail(line_number, "column '" + column_names[c] + "' is not a number ('" + f + "')");
      row.values[c] = v;
    }
    for (const auto &[n, unit] : OperatingPoint::columns())
      if (!std::isfinite(row.values[column_index[n]]))
        fail(line_number, "operating quantity '" + n + "' is not a finite number");
    const std::string role = trim(fields[role_column]);
    if (role == "grid")
    {
      if (!row.ok)
        ++failed;
      grid_rows.push_back(std::move(row));
    }
    else if (role == "check")
      check_rows.push_back(std::move(row));
    else
      fail(line_number, "role must be 'grid' or 'check' (got '" + role + "')");
  }
  if (!have_header)
    throw std::runtime_error("coefficient table '" + name + "' is empty");
  if (grid_rows.empty())
    throw std::runtime_error("coefficient table '" + name + "' has no grid rows");
}

void CoefficientTable::build_grid()
{
  // Distinct values of every operating quantity among the grid rows.
  for (const auto &[name, unit] : OperatingPoint::columns())
  {
    const unsigned int c = column_index.at(name);
    std::vector<double> v;
    for (const Row &r : grid_rows)
      v.push_back(r.values[c]);
    std::sort(v.begin(), v.end());
    std::vector<double> distinct;
    for (const double x : v)
      if (distinct.empty() || !same_value(distinct.back(), x))
        distinct.push_back(x);
    if (distinct.size() > 1)
    {
      axis_names.push_back(name);
      axis_nodes.push_back(distinct);
    }
    else
      constants.set(name, distinct[0]);
  }
  // Every grid row is one node of the tensor product, and every node has one row.
  std::size_t n_nodes = 1;
  for (const auto &nodes : axis_nodes)
    n_nodes *= nodes.size();
  const unsigned int unset = std::numeric_limits<unsigned int>::max();
  node_to_row.assign(n_nodes, unset);
  for (unsigned int r = 0; r < grid_rows.size(); ++r)
  {
    std::size_t index = 0, stride = 1;
    for (unsigned int a = 0; a < axis_names.size(); ++a)
    {
      const double x = grid_rows[r].values[column_index.at(axis_names[a])];
      const auto &nodes = axis_nodes[a];
      const auto it = std::find_if(nodes.begin(), nodes.end(),
                                   [x](const double v) { return same_value(v, x); });
      index += stride * (it - nodes.begin());
      stride *= nodes.size();
    }
    if (node_to_row[index] != unset)
      throw std::runtime_error(
          "coefficient table '" + source + "' line " + std::to_string(grid_rows[r].line) +
          ": the same grid point as line " + std::to_string(grid_rows[node_to_row[index]].line));
    node_to_row[index] = r;
  }
  for (std::size_t index = 0; index < n_nodes; ++index)
    if (node_to_row[index] == unset)
    {
      OperatingPoint p = constants;
      std::size_t rest = index;
      for (unsigned int a = 0; a < axis_names.size(); ++a)
      {
        p.set(axis_names[a], axis_nodes[a][rest % axis_nodes[a].size()]);
        rest /= axis_nodes[a].size();
      }
      throw std::runtime_error("coefficient table '" + source +
                               "' is not a full grid: no row for " + describe(p, axis_names));
    }
  // Scales for relative errors. Entries that vanish by symmetry (the axial-tilt coupling of an
  // axisymmetric film, its moments) are measured against the matrix or load they belong to,
  // not against their own round-off: K and D entries against the largest entry of the
  // dimensionally uniform matrix diag(1, 1/ro, 1/ro) K diag(1, 1/ro, 1/ro) converted back to
  // the entry's units, moments against max(|moments|, |F_z| ro), leakages against both.
  for (unsigned int c = 0; c < column_names.size(); ++c)
  {
    double s = 0;
    for (const Row &r : grid_rows)
      if (r.ok && std::isfinite(r.values[c]))
        s = std::max(s, std::abs(r.values[c]));
    column_scale[column_names[c]] = s;
  }
  auto raise = [this](const std::string &name, const double v)
  {
    if (column_scale.count(name))
      column_scale[name] = std::max(column_scale[name], v);
  };
  auto get = [this](const Row &r, const std::string &name)
  { return column_index.count(name) ? std::abs(r.values[column_index.at(name)]) : 0.0; };
  for (const Row &r : grid_rows)
  {
    if (!r.ok)
      continue;
    const double ro = r.values[column_index.at("outer_radius")];
    const double w[3] = {1, 1 / ro, 1 / ro};
    for (const bool stiffness : {true, false})
    {
      double uniform = 0;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          uniform = std::max(uniform,
                             get(r, coefficient_table_format::coefficient_name(stiffness, i, j)) *
                                 w[i] * w[j]);
      if (!std::isfinite(uniform))
        continue;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
        {
          const std::string n = coefficient_table_format::coefficient_name(stiffness, i, j);
          raise(n, uniform / (w[i] * w[j]));
          raise("err_" + n, uniform / (w[i] * w[j]));
        }
    }
    double moment = get(r, "force_z") * ro;
    for (const char *m : {"moment_x", "moment_y", "moment_restoring", "moment_transverse"})
      moment = std::max(moment, get(r, m));
    for (const char *m : {"moment_x", "moment_y", "moment_restoring", "moment_transverse"})
      raise(m, moment);
    const double leakage = std::max(get(r, "leakage_inner"), get(r, "leakage_outer"));
    raise("leakage_inner", leakage);
    raise("leakage_outer", leakage);
  }
}

unsigned int CoefficientTable::grid_row(const std::vector<unsigned int> &node) const
{
  std::size_t index = 0, stride = 1;
  for (unsigned int a = 0; a < node.size(); ++a)
  {
    index += stride * node[a];
    stride *= axis_nodes[a].size();
  }
  return node_to_row[index];
}

std::vector<double> CoefficientTable::locate(const OperatingPoint &point) const
{
  std::ostringstream s;
  s.precision(8);
  s << "coefficient table '" << source << "': ";
  std::vector<double> x;
  for (unsigned int a = 0; a < axis_names.size(); ++a)
  {
    const double v = point.get(axis_names[a]);
    const auto &nodes = axis_nodes[a];
    const double slack = 1e-9 * (nodes.back() - nodes.front());
    if (!(v >= nodes.front() - slack && v <= nodes.back() + slack))
    {
      s << axis_names[a] << " = " << v << " is outside the table's range [" << nodes.front() << ", "
        << nodes.back() << "]";
      throw std::runtime_error(s.str());
    }
    x.push_back(std::clamp(v, nodes.front(), nodes.back()));
  }
  for (const auto &[name, unit] : OperatingPoint::columns())
  {
    if (std::find(axis_names.begin(), axis_names.end(), name) != axis_names.end())
      continue;
    // Without tilt the tilt angle does not matter.
    if (name == "tilt_angle" && constants.tilt == 0 && point.tilt == 0)
      continue;
    const double v = point.get(name), c = constants.get(name);
    if (!(std::abs(v - c) <= 1e-9 * std::max(std::abs(v), std::abs(c))))
    {
      s << name << " = " << v << " " << unit << ", but the table was computed at " << name << " = "
        << c << " " << unit << " only (not swept)";
      throw std::runtime_error(s.str());
    }
  }
  return x;
}

void CoefficientTable::axis_weights(const unsigned int axis, const double x,
                                    std::vector<unsigned int> &nodes,
                                    std::vector<double> &weights) const
{
  // Multilinear: the 2 nodes of the interval; cubic: Lagrange on the 4 nodes around it (fewer
  // nodes on the axis lower the degree).
  const LagrangeStencil s =
      lagrange_stencil(axis_nodes[axis], x, method == Interpolation::linear ? 2 : 4);
  nodes.clear();
  for (unsigned int m = 0; m < s.weights.size(); ++m)
    nodes.push_back(s.first + m);
  weights = s.weights;
}

double CoefficientTable::interpolate(const unsigned int column, const std::vector<double> &x) const
{
  const unsigned int d = axis_names.size();
  if (d == 0)
  {
    const Row &r = grid_rows[0];
    if (!r.ok)
      throw std::runtime_error("coefficient table '" + source + "': its only point (line " +
                               std::to_string(r.line) + ") failed: " + r.status);
    return r.values[column];
  }
  std::vector<std::vector<unsigned int>> nodes(d);
  std::vector<std::vector<double>> weights(d);
  for (unsigned int a = 0; a < d; ++a)
    axis_weights(a, x[a], nodes[a], weights[a]);
  // Sum over the tensor product of the per-axis stencils.
  std::vector<unsigned int> counter(d, 0), node(d);
  double sum = 0;
  while (true)
  {
    double w = 1;
    for (unsigned int a = 0; a < d; ++a)
    {
      node[a] = nodes[a][counter[a]];
      w *= weights[a][counter[a]];
    }
    if (w != 0)
    {
      const Row &r = grid_rows[grid_row(node)];
      if (!r.ok || !std::isfinite(r.values[column]))
      {
        OperatingPoint p = constants;
        for (unsigned int a = 0; a < d; ++a)
          p.set(axis_names[a], axis_nodes[a][node[a]]);
        throw std::runtime_error("coefficient table '" + source +
                                 "': the interpolation needs the point on line " +
                                 std::to_string(r.line) + " (" + describe(p, axis_names) +
                                 "), which has no value: " + r.status);
      }
      sum += w * r.values[column];
    }
    unsigned int a = 0;
    for (; a < d; ++a)
      if (++counter[a] < nodes[a].size())
        break;
      else
        counter[a] = 0;
    if (a == d)
      break;
  }
  return sum;
}

double CoefficientTable::value(const std::string &column, const OperatingPoint &point) const
{
  const auto it = column_index.find(column);
  if (it == column_index.end())
    throw std::runtime_error("coefficient table '" + source + "' has no column '" + column + "'");
  return interpolate(it->second, locate(point));
}

FilmCoefficients CoefficientTable::coefficients(const OperatingPoint &query) const
{
  OperatingPoint p = query;
  const bool stator_swept =
      std::find(axis_names.begin(), axis_names.end(), "stator_speed") != axis_names.end();
  const bool mapped = !stator_swept && p.stator_speed != constants.stator_speed;
  if (mapped)
  {
    // Same mean speed (omega1 + omega2)/2 at the table's stator speed.
    p.rotor_speed = query.rotor_speed + query.stator_speed - constants.stator_speed;
    p.stator_speed = constants.stator_speed;
  }
  std::vector<double> x;
  try
  {
    x = locate(p);
  }
  catch (std::runtime_error &e)
  {
    if (!mapped)
      throw;
    std::ostringstream s;
    s << e.what() << " (asked for rotor speed " << query.rotor_speed << " and stator speed "
      << query.stator_speed << " rad/s, answered at the same mean speed with the table's stator "
      << "speed " << constants.stator_speed << " rad/s)";
    throw std::runtime_error(s.str());
  }
  FilmCoefficients k;
  k.level = 1;
  k.model = "coefficient table '" + source + "' (" +
            (method == Interpolation::linear ? "multilinear" : "cubic") + " interpolation)";
  k.rotor_speed = query.rotor_speed;
  k.stator_speed = query.stator_speed;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
    {
      k.stiffness[i][j] =
          interpolate(column_index.at(coefficient_table_format::coefficient_name(true, i, j)), x);
      k.damping[i][j] =
          interpolate(column_index.at(coefficient_table_format::coefficient_name(false, i, j)), x);
    }
  return k;
}

FilmCoefficients CoefficientTable::coefficients(const FilmThickness &film,
                                                const OperatingConditions &conditions) const
{
  return coefficients(OperatingPoint::of(film, conditions));
}

std::function<FilmCoefficients(double, double)>
CoefficientTable::film_model(const FilmThickness &film, const OperatingConditions &conditions) const
{
  auto table = std::make_shared<const CoefficientTable>(*this);
  const OperatingPoint base = OperatingPoint::of(film, conditions);
  // Fail now, not in the middle of a stability sweep, if the seal is not the table's.
  {
    OperatingPoint p = base;
    for (unsigned int a = 0; a < axis_names.size(); ++a)
      if (axis_names[a] == "rotor_speed" || axis_names[a] == "stator_speed")
        p.set(axis_names[a], axis_nodes[a].front());
    if (std::find(axis_names.begin(), axis_names.end(), "rotor_speed") != axis_names.end() &&
        std::find(axis_names.begin(), axis_names.end(), "stator_speed") == axis_names.end())
      p.stator_speed = constants.stator_speed;
    table->coefficients(p);
  }
  return [table, base](const double rotor_speed, const double stator_speed)
  {
    OperatingPoint p = base;
    p.rotor_speed = rotor_speed;
    p.stator_speed = stator_speed;
    return table->coefficients(p);
  };
}

CoefficientTable::Error CoefficientTable::compare(const FilmCoefficients &interpolated,
                                                  const FilmCoefficients &reference,
                                                  const double outer_radius)
{
  const double w[3] = {1, 1 / outer_radius, 1 / outer_radius};
  auto relative = [&](const FilmCoefficients::Matrix3 &a, const FilmCoefficients::Matrix3 &b)
  {
    double diff = 0, scale = 0;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
      {
        diff = std::max(diff, std::abs(a[i][j] - b[i][j]) * w[i] * w[j]);
        scale = std::max(scale, std::abs(b[i][j]) * w[i] * w[j]);
      }
    return scale > 0 ? diff / scale : diff;
  };
  Error e;
  e.stiffness = relative(interpolated.stiffness, reference.stiffness);
  e.damping = relative(interpolated.damping, reference.damping);
  return e;
}

std::vector<CoefficientTable::Error> CoefficientTable::held_out_errors() const
{
  std::vector<Error> errors;
  for (const Row &r : check_rows)
  {
    if (!r.ok)
      continue;
    OperatingPoint p;
    for (const auto &[name, unit] : OperatingPoint::columns())
      p.set(name, r.values[column_index.at(name)]);
    FilmCoefficients reference;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
      {
        reference.stiffness[i][j] =
            r.values[column_index.at(coefficient_table_format::coefficient_name(true, i, j))];
        reference.damping[i][j] =
            r.values[column_index.at(coefficient_table_format::coefficient_name(false, i, j))];
      }
    Error e;
    try
    {
      e = compare(coefficients(p), reference, p.outer_radius);
      const std::vector<double> x = locate(p);
      for (const auto &[name, unit] : coefficient_table_format::output_columns(false))
      {
        if (name == "dofs" || !column_index.count(name))
          continue;
        const unsigned int c = column_index.at(name);
        const double scale = column_scale.at(name);
        const double diff = std::abs(interpolate(c, x) - r.values[c]);
        e.columns[name] = scale > 0 ? diff / scale : diff;
      }
    }
    catch (std::runtime_error &)
    {
      continue; // the check point needs a failed grid point: no error to report
    }
    e.point = p;
    errors.push_back(e);
  }
  return errors;
}

} // namespace sealfe
