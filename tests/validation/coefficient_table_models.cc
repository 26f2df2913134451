// The coefficient table reader and interpolator (level 1, coefficient_table.h) on tables whose
// exact values are known: Green & Etsion's closed-form coefficients (level 0) tabulated over
// clearance and rotor speed. The interpolation error at points off the grid must fall at the
// interpolant's order (2 multilinear, 4 cubic) as the grid is refined; grid values and functions
// the interpolant reproduces must come back to round-off; a failed point must not spoil the rest;
// malformed tables and queries outside the table are refused with a clear message.
#include <sealfe/closed_form/green_etsion.h>
#include <sealfe/coefficients/coefficient_table.h>

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <set>
#include <string>
#include <vector>

using namespace sealfe;

namespace
{
std::string number(const double v)
{
  char buffer[64];
  return std::string(buffer, std::to_chars(buffer, buffer + 64, v).ptr);
}

/// The exact coefficients of a point: Green & Etsion's closed form.
FilmCoefficients exact(const OperatingPoint &p)
{
  FilmThickness film;
  OperatingConditions conditions;
  p.apply(film, conditions);
  return GreenEtsionCoefficients(film, conditions).coefficients(p.rotor_speed, p.stator_speed);
}

/// One CSV row with the closed-form coefficients of p (status ok) or a failure.
std::string row(const unsigned int index, const std::string &role, const OperatingPoint &p,
                const bool failed = false)
{
  std::string line = std::to_string(index) + "," + role;
  for (const auto &[name, unit] : OperatingPoint::columns())
    line += "," + number(p.get(name));
  const auto columns = coefficient_table_format::output_columns(false);
  if (failed)
  {
    for (unsigned int c = 0; c < columns.size(); ++c)
      line += ",nan";
    return line + ",failed: the film touches down at r = 0.0355 m; theta = 1.2 rad";
  }
  const FilmCoefficients k = exact(p);
  // Loads: a smooth stand-in (the force of the closed-form axial stiffness over C0), moments 0.
  const std::vector<double> loads = {k.stiffness[0][0] * p.clearance,
                                     0,
                                     0,
                                     0,
                                     0,
                                     -1e-9,
                                     1e-9,
                                     1e-4 * p.rotor_speed,
                                     p.clearance,
                                     4e5,
                                     0,
                                     0};
  for (const double v : loads)
    line += "," + number(v);
  for (const auto *m : {&k.stiffness, &k.damping})
    for (const auto &r : *m)
      for (const double v : r)
        line += "," + number(v);
  return line + ",1234,ok";
}

OperatingPoint base_point()
{
  FilmThickness film;
  OperatingConditions conditions;
  return OperatingPoint::of(film, conditions);
}

std::vector<double> linspace(const double a, const double b, const unsigned int n)
{
  std::vector<double> v;
  for (unsigned int i = 0; i < n; ++i)
    v.push_back(a + (b - a) * i / (n - 1));
  return v;
}

/// CSV text of the grid clearance x rotor speed (and `checks` as held-out rows); `failed` marks
/// grid indices whose solve failed; `skip` drops a grid row.
std::string table_text(const std::vector<double> &clearances, const std::vector<double> &speeds,
                       const std::vector<OperatingPoint> &checks = {},
                       const std::set<unsigned int> &failed = {}, const int skip = -1)
{
  std::string text = coefficient_table_format::header(false) + "\n";
  unsigned int i = 0;
  for (const double c : clearances)
    for (const double w : speeds)
    {
      OperatingPoint p = base_point();
      p.clearance = c;
      p.rotor_speed = w;
      if (static_cast<int>(i) != skip)
        text += row(i, "grid", p, failed.count(i) > 0) + "\n";
      ++i;
    }
  for (const auto &p : checks)
    text += row(i++, "check", p) + "\n";
  return text;
}

/// Off-grid query points (fixed while the grid is refined).
std::vector<OperatingPoint> queries()
{
  std::vector<OperatingPoint> q;
  for (const auto &[c, w] : std::vector<std::pair<double, double>>{
           {0.93e-6, 1234.5}, {1.37e-6, 2777.7}, {1.11e-6, 333.3}, {1.52e-6, 3901.0}})
  {
    OperatingPoint p = base_point();
    p.clearance = c;
    p.rotor_speed = w;
    q.push_back(p);
  }
  return q;
}

/// Max over a dense set of off-grid points (an estimate of the sup norm, whose convergence is
/// not disturbed by where single points fall inside their cells).
double max_error(const CoefficientTable &table, bool damping)
{
  double e = 0;
  for (unsigned int i = 0; i < 400; ++i)
  {
    OperatingPoint p = base_point();
    p.clearance = 0.8e-6 + 0.8e-6 * (i + 0.5) / 400;
    p.rotor_speed = 4000 * std::fmod(0.618034 * i, 1.0);
    const auto err = CoefficientTable::compare(table.coefficients(p), exact(p), p.outer_radius);
    e = std::max(e, damping ? err.damping : err.stiffness);
  }
  return e;
}

template <typename F>
std::string thrown_message(F &&f)
{
  try
  {
    f();
  }
  catch (std::runtime_error &e)
  {
    return e.what();
  }
  return "(nothing thrown)";
}
} // namespace

TEST(CoefficientTable, InterpolationErrorFallsAtTheInterpolantsOrder)
{
  for (const auto method :
       {CoefficientTable::Interpolation::linear, CoefficientTable::Interpolation::cubic})
  {
    const double order = method == CoefficientTable::Interpolation::linear ? 2 : 4;
    std::vector<double> ek, ed;
    const std::vector<unsigned int> nodes = {5, 9, 17, 33};
    for (const unsigned int n : nodes)
    {
      const auto table = CoefficientTable::from_text(
          table_text(linspace(0.8e-6, 1.6e-6, n), linspace(0, 4000, 5)), "synthetic", method);
      ek.push_back(max_error(table, false));
      ed.push_back(max_error(table, true));
    }
    for (unsigned int i = 1; i < nodes.size(); ++i)
    {
      const double rk = std::log2(ek[i - 1] / ek[i]), rd = std::log2(ed[i - 1] / ed[i]);
      std::cout << (order == 2 ? "multilinear" : "cubic") << " " << nodes[i]
                << " clearances: error K " << ek[i] << " D " << ed[i] << ", observed order K " << rk
                << " D " << rd << "\n";
      if (i == nodes.size() - 1)
      {
        EXPECT_NEAR(rk, order, 0.1 * order);
        EXPECT_NEAR(rd, order, 0.1 * order);
      }
    }
  }
}

TEST(CoefficientTable, HeldOutRowsReportTheInterpolationError)
{
  const auto q = queries();
  const auto table = CoefficientTable::from_text(
      table_text(linspace(0.8e-6, 1.6e-6, 9), linspace(0, 4000, 5), q), "synthetic");
  EXPECT_EQ(table.n_grid_points(), 45u);
  EXPECT_EQ(table.n_check_points(), q.size());
  ASSERT_EQ(table.axes().size(), 2u);
  EXPECT_EQ(table.axes()[0], "rotor_speed");
  EXPECT_EQ(table.axes()[1], "clearance");
  const auto errors = table.held_out_errors();
  ASSERT_EQ(errors.size(), q.size());
  for (unsigned int i = 0; i < q.size(); ++i)
  {
    const auto direct =
        CoefficientTable::compare(table.coefficients(q[i]), exact(q[i]), q[i].outer_radius);
    EXPECT_DOUBLE_EQ(errors[i].stiffness, direct.stiffness);
    EXPECT_DOUBLE_EQ(errors[i].damping, direct.damping);
    EXPECT_GT(errors[i].stiffness, 0);
    EXPECT_LT(errors[i].stiffness, 1e-3);
    // Entries that vanish (axial-tilt coupling) are measured against their matrix: zero error.
    EXPECT_EQ(errors[i].columns.at("K_z_tx"), 0.0);
    EXPECT_LT(errors[i].columns.at("K_tx_tx"), 1e-3);
  }
}

TEST(CoefficientTable, ReproducesGridValuesAndLinearDependence)
{
  const auto table = CoefficientTable::from_text(
      table_text(linspace(0.8e-6, 1.6e-6, 5), linspace(0, 4000, 5)), "synthetic");
  for (const double c : {0.8e-6, 1.2e-6, 1.6e-6})
    for (const double w : {0.0, 1000.0, 2345.6, 4000.0})
    {
      OperatingPoint p = base_point();
      p.clearance = c;
      p.rotor_speed = w;
      // On a clearance node the coefficients are linear in the speed (c = omega/2 d11), which
      // both interpolants reproduce.
      const auto k = table.coefficients(p), e = exact(p);
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
        {
          const double scale = std::max(std::abs(e.stiffness[1][2]), std::abs(e.stiffness[1][1]));
          EXPECT_NEAR(k.stiffness[i][j], e.stiffness[i][j],
                      1e-12 * std::max(std::abs(e.stiffness[i][j]), i == 0 ? 0.0 : scale));
          EXPECT_NEAR(k.damping[i][j], e.damping[i][j], 1e-12 * std::abs(e.damping[i][j]));
        }
      EXPECT_EQ(k.level, 1);
      EXPECT_NEAR(table.value("K_z_z", p), e.stiffness[0][0], 1e-12 * e.stiffness[0][0]);
    }
}

TEST(CoefficientTable, TwoRotatingRingsAreAnsweredAtTheirMeanSpeed)
{
  // An FMS table (stator at rest) answers an FMRR query through the mean speed: K and D depend
  // on the ring speeds only through (omega1 + omega2)/2 (Wileman & Green: D11 = (omega1 + omega2)/2
  // d11).
  const auto table = CoefficientTable::from_text(
      table_text(linspace(0.8e-6, 1.6e-6, 5), linspace(-4000, 4000, 9)), "synthetic");
  OperatingPoint p = base_point();
  p.clearance = 1.2e-6;
  p.rotor_speed = -2000;
  p.stator_speed = 3000;
  const FilmCoefficients k = table.coefficients(p), e = exact(p);
  EXPECT_EQ(k.rotor_speed, -2000);
  EXPECT_EQ(k.stator_speed, 3000);
  EXPECT_NEAR(k.tilt_cross_stiffness(), e.tilt_cross_stiffness(),
              1e-12 * std::abs(e.tilt_cross_stiffness()));
  EXPECT_NEAR(k.tilt_cross_stiffness(), 500 * e.tilt_direct_damping(),
              1e-12 * std::abs(e.tilt_cross_stiffness()));
  // As a seal_dynamics FilmModel.
  FilmThickness film;
  OperatingConditions conditions;
  p.apply(film, conditions);
  const auto model = table.film_model(film, conditions);
  const FilmCoefficients m = model(-1000, 2500);
  EXPECT_EQ(m.level, 1);
  EXPECT_NEAR(m.tilt_cross_stiffness(), 750 * e.tilt_direct_damping(),
              1e-12 * std::abs(m.tilt_cross_stiffness()));
  // Outside the table's mean-speed range: the message says how the query was mapped.
  const std::string message = thrown_message([&] { model(-3000, -3000); });
  EXPECT_NE(message.find("rotor_speed = -6000 is outside the table's range [-4000, 4000]"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("stator speed -3000 rad/s, answered at the same mean speed"),
            std::string::npos)
      << message;
}

TEST(CoefficientTable, QueriesOutsideTheTableAreRefused)
{
  const auto table = CoefficientTable::from_text(
      table_text(linspace(0.8e-6, 1.6e-6, 5), linspace(0, 4000, 5)), "synthetic");
  OperatingPoint p = base_point();
  p.clearance = 2e-6;
  std::string m = thrown_message([&] { table.coefficients(p); });
  EXPECT_NE(m.find("clearance = 2e-06 is outside the table's range"), std::string::npos) << m;
  p = base_point();
  p.coning = 2e-3;
  m = thrown_message([&] { table.coefficients(p); });
  EXPECT_NE(m.find("coning = 0.002 rad, but the table was computed at coning = 0.001 rad only"),
            std::string::npos)
      << m;
  // A film model for another seal fails when it is made, not in the middle of a sweep.
  FilmThickness film;
  OperatingConditions conditions;
  conditions.viscosity = 2e-3;
  m = thrown_message([&] { table.film_model(film, conditions); });
  EXPECT_NE(m.find("viscosity"), std::string::npos) << m;
}

TEST(CoefficientTable, AFailedPointKeepsTheRest)
{
  // Grid index 12 = clearance node 2 (1.2e-6), speed node 2 (2000) failed.
  const auto table = CoefficientTable::from_text(
      table_text(linspace(0.8e-6, 1.6e-6, 5), linspace(0, 4000, 5), queries(), {12}), "t.csv",
      CoefficientTable::Interpolation::linear);
  EXPECT_EQ(table.n_failed_points(), 1u);
  OperatingPoint far = base_point();
  far.clearance = 0.9e-6;
  far.rotor_speed = 500;
  const auto intact =
      CoefficientTable::from_text(table_text(linspace(0.8e-6, 1.6e-6, 5), linspace(0, 4000, 5)),
                                  "intact.csv", CoefficientTable::Interpolation::linear);
  EXPECT_EQ(table.coefficients(far).stiffness, intact.coefficients(far).stiffness);
  EXPECT_EQ(table.coefficients(far).damping, intact.coefficients(far).damping);
  OperatingPoint near = base_point();
  near.clearance = 1.3e-6;
  near.rotor_speed = 2500;
  const std::string m = thrown_message([&] { table.coefficients(near); });
  EXPECT_NE(m.find("needs the point on line 14"), std::string::npos) << m;
  EXPECT_NE(m.find("film touches down"), std::string::npos) << m;
  // Held-out rows next to the failed point are skipped, the others reported.
  EXPECT_EQ(table.held_out_errors().size(), 3u);
}

TEST(CoefficientTable, MalformedTablesAreRefusedWithTheLine)
{
  const auto good = table_text(linspace(0.8e-6, 1.6e-6, 3), linspace(0, 4000, 3));
  auto message = [](const std::string &text)
  { return thrown_message([&] { CoefficientTable::from_text(text, "t.csv"); }); };
  EXPECT_NE(message(table_text(linspace(0.8e-6, 1.6e-6, 3), linspace(0, 4000, 3), {}, {}, 4))
                .find("is not a full grid: no row for rotor_speed = 2000, clearance = 1.2e-06"),
            std::string::npos);
  {
    std::string text = good;
    const auto second = text.find('\n') + 1;
    const auto end = text.find('\n', second) + 1;
    text += text.substr(second, end - second); // the first data row again
    EXPECT_NE(message(text).find("the same grid point as line 2"), std::string::npos)
        << message(text);
  }
  {
    std::string text = good;
    const auto pos = text.find(",grid,");
    text.replace(pos, 6, ",grod,");
    EXPECT_NE(message(text).find("line 2: role must be 'grid' or 'check'"), std::string::npos);
  }
  {
    std::string text = good;
    const auto pos = text.rfind(",1234,ok");
    text.replace(pos, 8, ",12x4,ok");
    EXPECT_NE(message(text).find("line 10: column 'dofs' is not a number ('12x4')"),
              std::string::npos)
        << message(text);
  }
  {
    std::string text = good;
    const auto pos = text.find("viscosity [Pa s]");
    text.replace(pos, 9, "viscosite");
    EXPECT_NE(message(text).find("line 1: the header has no 'viscosity' column"), std::string::npos)
        << message(text);
  }
  EXPECT_NE(message("").find("is empty"), std::string::npos);
  EXPECT_NE(thrown_message([] { CoefficientTable("/nonexistent/table.csv"); })
                .find("'/nonexistent/table.csv' is missing or unreadable"),
            std::string::npos);
}

TEST(CoefficientTable, ReadsAFileWrittenToDisk)
{
  const auto path = std::filesystem::temp_directory_path() / "sealfe_coefficient_table_test.csv";
  {
    std::ofstream out(path);
    out << table_text(linspace(0.8e-6, 1.6e-6, 5), linspace(0, 4000, 5), queries());
  }
  const CoefficientTable table(path.string());
  EXPECT_EQ(table.n_grid_points(), 25u);
  EXPECT_EQ(table.held_out_errors().size(), 4u);
  std::filesystem::remove(path);
}
