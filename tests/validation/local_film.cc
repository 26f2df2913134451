// ReynoldsSolver::local_film on the coned, tilted face pair (no waviness, expression or surface
// features) evaluates h, dh/dtheta and dh/dt in Cartesian form, without a sine, cosine or atan2
// per point (reynolds_solver.cc). They must equal FilmThickness's polar formulas
//
//   h = C0 + z + beta (r - ri) + gamma r cos(theta - psi),  dh/dtheta = -gamma r sin(theta - psi),
//   dh/dt = z_dot + tilt_x_dot r sin(theta) - tilt_y_dot r cos(theta)
//
// to the round-off of either evaluation: a few units u = 2^-53 of the largest term's size.
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/numbers.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace sealfe;

TEST(LocalFilm, ConedTiltedFilmEqualsFilmThicknessFormulas)
{
  const double u = 0.5 * std::numeric_limits<double>::epsilon();
  // psi in each quadrant and at the ends of atan2's range (film.tilt_angle is atan2's)
  for (const double psi : {0.0, 0.3, 1.9, 3.1, -3.1, -0.7})
  {
    FilmSettings s;
    s.geometry.tilt = 0.5 * s.geometry.clearance / s.geometry.outer_radius;
    s.geometry.tilt_angle = psi;
    s.geometry.axial_offset = 0.1e-6;
    s.geometry.axial_velocity = 1e-4;
    s.geometry.tilt_rate_x = 2e-3;
    s.geometry.tilt_rate_y = -3e-3;
    s.polynomial_degree = 1;
    s.mesh.radial_cells = 2;
    s.mesh.circumferential_cells = 16;
    s.estimate_error = false;
    s.linear_solver = FilmSettings::LinearSolver::direct;
    ASSERT_EQ(s.geometry.wave_amplitude, 0.0);
    ASSERT_FALSE(s.geometry.has_added_terms());
    ReynoldsSolver solver(s, MPI_COMM_WORLD);
    solver.run(); // sets the solver's film and conditions from s
    const FilmThickness &g = s.geometry;
    const double ri = g.inner_radius, ro = g.outer_radius;
    const double w_mean = s.conditions.mean_speed();
    // the sizes the round-off is relative to
    const double h_size = g.clearance + std::abs(g.axial_offset) + std::abs(g.coning) * (ro - ri) +
                          std::abs(g.tilt) * ro;
    const double rate_size =
        std::abs(g.axial_velocity) + (std::abs(g.tilt_rate_x) + std::abs(g.tilt_rate_y)) * ro;
    double worst_h = 0, worst_rate = 0, worst_slope = 0;
    for (unsigned int i = 0; i <= 10; ++i)
      for (unsigned int j = 0; j < 64; ++j)
      {
        const double r = ri + (ro - ri) * i / 10.0;
        const double theta = -dealii::numbers::PI + 2 * dealii::numbers::PI * (j + 0.5) / 64;
        const dealii::Point<2> x(r * std::cos(theta), r * std::sin(theta));
        const ReynoldsSolver::LocalFilm f = solver.local_film(x);
        // x is given in Cartesian coordinates: compare with the formulas at the x's own r, theta
        const double r_x = x.norm(), theta_x = std::atan2(x[1], x[0]);
        worst_h = std::max(worst_h, std::abs(f.h - g.value(r_x, theta_x)) / h_size);
        worst_rate = std::max(worst_rate, std::abs(f.squeeze - g.d_dt(r_x, theta_x)) / rate_size);
        // smooth faces without features: div of the Couette flux = w_mean dh/dtheta
        worst_slope = std::max(worst_slope, std::abs(f.c_div - w_mean * g.d_dtheta(r_x, theta_x)) /
                                                (std::abs(w_mean) * std::abs(g.tilt) * ro));
      }
    std::cout << "psi " << psi << ": h " << worst_h / u << " u, dh/dt " << worst_rate / u
              << " u, dh/dtheta " << worst_slope / u << " u\n";
    // each side: ~5 roundings of terms of size <= h_size, plus cos/sin of libm (<= 1 ulp) times
    // gamma r and the error of r, theta of the point (a few u): 16 u a generous sum
    EXPECT_LE(worst_h, 16 * u) << "psi " << psi;
    EXPECT_LE(worst_rate, 16 * u) << "psi " << psi;
    EXPECT_LE(worst_slope, 16 * u) << "psi " << psi;
  }
}
