// The linearised Reynolds solve (one extra solve with the same factorisation) against central
// finite differences of the nonlinear solve: the loads are smooth in z, the tilts and their
// rates, so the two agree to the O(step^2) truncation of the differences (1e-6 relative here).
#include <sealfe/film/reynolds_solver.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace sealfe;

namespace
{
FilmThickness operating_film()
{
  FilmThickness f;
  f.set_tilt_vector(0.3 * f.clearance / f.outer_radius, 0.2 * f.clearance / f.outer_radius);
  return f;
}

FilmLoads solve(const FilmThickness &f, const OperatingConditions &c)
{
  ReynoldsSolver s(MPI_COMM_WORLD);
  s.mesh().circumferential_cells = 64;
  s.mesh().radial_cells = 6;
  return s.run(f, c);
}

void expect_close(const FilmLoads &lin, const FilmLoads &fd, const double force_scale,
                  const double moment_scale, const double flow_scale)
{
  EXPECT_NEAR(lin.force_z, fd.force_z, 1e-6 * force_scale);
  EXPECT_NEAR(lin.moment_x, fd.moment_x, 1e-6 * moment_scale);
  EXPECT_NEAR(lin.moment_y, fd.moment_y, 1e-6 * moment_scale);
  EXPECT_NEAR(lin.leakage_inner, fd.leakage_inner, 1e-6 * flow_scale);
  EXPECT_NEAR(lin.leakage_outer, fd.leakage_outer, 1e-6 * flow_scale);
  EXPECT_NEAR(lin.friction_torque, fd.friction_torque, 1e-6 * moment_scale);
}

FilmLoads difference(const FilmLoads &a, const FilmLoads &b, const double step)
{
  FilmLoads d;
  d.force_z = (a.force_z - b.force_z) / (2 * step);
  d.moment_x = (a.moment_x - b.moment_x) / (2 * step);
  d.moment_y = (a.moment_y - b.moment_y) / (2 * step);
  d.leakage_inner = (a.leakage_inner - b.leakage_inner) / (2 * step);
  d.leakage_outer = (a.leakage_outer - b.leakage_outer) / (2 * step);
  d.friction_torque = (a.friction_torque - b.friction_torque) / (2 * step);
  return d;
}
} // namespace

TEST(ReynoldsLinearization, MatchesCentralDifferencesInFullFilm)
{
  const FilmThickness film = operating_film();
  const OperatingConditions conditions;
  ReynoldsSolver solver(MPI_COMM_WORLD);
  solver.mesh().circumferential_cells = 64;
  solver.mesh().radial_cells = 6;
  const FilmLoads base = solver.run(film, conditions);
  const double F = std::abs(base.force_z), M = F * film.outer_radius,
               Q = std::abs(base.leakage_outer);

  // z: dh/dz = 1; step 1e-3 C0.
  {
    const double step = 1e-3 * film.clearance;
    FilmThickness a = film, b = film;
    a.axial_offset += step;
    b.axial_offset -= step;
    const FilmLoads fd = difference(solve(a, conditions), solve(b, conditions), step);
    const FilmLoads lin = solver.linearized_loads({[](double, double) { return 1.0; }, {}});
    expect_close(lin, fd, F / film.clearance, M / film.clearance, Q / film.clearance);
  }
  // tilt_x: dh/dtilt_x = y = r sin(theta); step 1e-3 C0/ro.
  {
    const double step = 1e-3 * film.clearance / film.outer_radius;
    FilmThickness a = film, b = film;
    a.set_tilt_vector(film.tilt_x() + step, film.tilt_y());
    b.set_tilt_vector(film.tilt_x() - step, film.tilt_y());
    const FilmLoads fd = difference(solve(a, conditions), solve(b, conditions), step);
    const FilmLoads lin =
        solver.linearized_loads({[](double r, double t) { return r * std::sin(t); }, {}});
    const double unit = film.clearance / film.outer_radius;
    expect_close(lin, fd, F / unit, M / unit, Q / unit);
  }
  // tilt rate y: d(dh/dt)/d(tilt_y_dot) = -x; the loads are linear in the rates, so any step.
  {
    const double step = 1.0;
    FilmThickness a = film, b = film;
    a.tilt_rate_y = step;
    b.tilt_rate_y = -step;
    const FilmLoads fd = difference(solve(a, conditions), solve(b, conditions), step);
    const FilmLoads lin =
        solver.linearized_loads({{}, [](double r, double t) { return -r * std::cos(t); }});
    const double scale = std::max(std::abs(fd.moment_y), std::abs(fd.moment_x));
    EXPECT_NEAR(lin.moment_x, fd.moment_x, 1e-9 * scale);
    EXPECT_NEAR(lin.moment_y, fd.moment_y, 1e-9 * scale);
    EXPECT_NEAR(lin.force_z, fd.force_z, 1e-9 * scale / film.outer_radius);
  }
}
