// ReynoldsSolver::local_film on the coned, tilted face pair (no waviness, expression or surface
// features) evaluates h, dh/dtheta and dh/dt in Cartesian form, without a sine, cosine or atan2
// per point (reynolds_solver.cc). They must equal FilmThickness's polar formulas
//
//   h = C0 + z + beta (r - ri) + gamma r cos(theta - psi),  dh/dtheta = -gamma r sin(theta - psi),
//   dh/dt = z_dot + tilt_x_dot r sin(theta) - tilt_y_dot r cos(theta)
//
// to the round-off of either evaluation: a few units u = 2^-53 of the largest term's size.
#include <sealfe/film/annulus_mesh.h>
#include <sealfe/film/film_settings.h>
#include <sealfe/film/polar_cell_values.h>
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/film/surface_features.h>

#include <deal.II/base/numbers.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q_cache.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

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

namespace
{
FilmSettings parsed(const std::string &text)
{
  dealii::ParameterHandler prm;
  FilmSettings::declare_parameters(prm);
  prm.parse_input_from_string(text);
  FilmSettings s;
  s.parse_parameters(prm);
  return s;
}
} // namespace

// The assembly on the built-in annulus calls the 5-argument local_film at every quadrature point
// with r and theta from PolarCellValues (the row's |x_q| and atan2, the angle turned by the
// cell's) and cos, sin of the tilt angle once per assembly; the coned, tilted film takes its
// Cartesian forms, every other film (waviness, film expression, surface features) the polar
// FilmThickness formulas at that (r, theta). Cell by cell over a mesh, the film, its squeeze
// and the divergence of the Couette flux must equal the one-point formulas at the point's own
// r = |x|, theta = atan2(x) to round-off, and so must the one-point local_film(x) of the loads
// and the field output (its own |x|, atan2, cos and sin: the same bound holds). Bound: r and theta
// of PolarCellValues differ from those by at most ~8 u r and ~8 u pi (atan2 and the norm ~1 ulp
// each, the rotation of the row's point and its cos, sin from the vertices a few u, the sum of the
// two angles and the wrap by 2 pi one rounding each), which moves a term by its derivative times
// that; each evaluation rounds ~5 times (16 u of the sizes, as above). With H the sum of the film's
// term sizes, H_t and H_tt bounds of |dh/dtheta| and |d2h/dtheta2|, R the squeeze's size and R_t
// its theta slope:
//   |dh| <= 32 u (H + pi H_t), |d(dh/dtheta)| <= 32 u (H_t + pi H_tt) + D,
//   |d squeeze| <= 32 u (R + pi R_t) + |w_F| |d(dh/dtheta)|,  |d div c| <= |w_mean| |d(dh/dtheta)|,
// 32 u a factor 2-4 over the sum. D: a film expression's dh/dtheta is a centred difference with
// step 6e-6 rad (film_expression.cc), whose round-off (~16 u a / step per evaluation, a the
// formula's size) does not vary smoothly with theta: D = 32 u a / 6e-6. Surface features are
// piecewise constant with the mesh's cell edges on their steps (Align with features), so no
// quadrature point is within round-off of a step.
TEST(LocalFilm, PolarCellValuesPathEqualsFilmThicknessFormulasOnEveryCell)
{
  using namespace dealii;
  const double u = 0.5 * std::numeric_limits<double>::epsilon();
  const std::string tilted =
      " set Tilt = 1.2e-5\n set Tilt angle = 1.9\n set Axial offset = 1e-7\n";
  const std::string squeeze = "subsection Squeeze motion\n set Axial velocity = 1e-4\n"
                              " set Tilt rate x = 2e-3\n set Tilt rate y = -3e-3\nend\n";
  const std::string wavy = " set Wave amplitude = 0.2e-6\n set Wave number = 3\n";
  const double expression_size = 0.2e-6;
  struct Case
  {
    std::string name, geometry;
  };
  const std::vector<Case> cases = {
      {"coned, tilted", tilted},
      {"wavy", tilted + wavy},
      {"film expression", tilted + " set Film expression = a*cos(2*theta)*r/0.0408\n"
                                   " set Film expression constants = a=0.2e-6\n"},
      {"surface features (rotor)",
       tilted + wavy +
           " subsection Surface features\n  set Face = rotor\n  subsection Rayleigh pads\n"
           "   set Number = 12\n   set Step depth = 1e-6\n   set Step fraction = 0.718\n"
           "   set Feeding groove angle = 0.05\n   set Feeding groove depth = 1e-5\n"
           "   set Feeding groove side = both\n  end\n end\n"}};
  for (const Case &c : cases)
  {
    const FilmSettings s =
        parsed("subsection Geometry\n" + c.geometry + "end\n" + squeeze +
               "subsection Discretization\n set Radial cells = 4\n"
               " set Circumferential cells = 96\n set Polynomial degree = 2\nend\n");
    const FilmThickness &g = s.geometry;
    ASSERT_EQ(g.is_coned_tilted(), c.name == "coned, tilted");
    ReynoldsSolver solver(s, MPI_COMM_WORLD);
    const double ri = g.inner_radius, ro = g.outer_radius, pi = numbers::PI;
    const double A = std::abs(g.wave_amplitude), n = g.wave_number, gamma = std::abs(g.tilt);
    const double a = g.expression ? expression_size : 0.0;
    const double step = g.features ? 1e-5 : 0.0; // the deepest recess (the groove)
    const double H = g.clearance + std::abs(g.axial_offset) + std::abs(g.coning) * (ro - ri) +
                     gamma * ro + A + a + step;
    const double H_t = gamma * ro + A * n + 2 * a, H_tt = gamma * ro + A * n * n + 4 * a;
    const double R_t = (std::abs(g.tilt_rate_x) + std::abs(g.tilt_rate_y)) * ro,
                 R = std::abs(g.axial_velocity) + R_t;
    const double w_F = g.feature_frame_speed(s.conditions.rotor_speed, s.conditions.stator_speed);
    const double w_mean = s.conditions.mean_speed() - w_F;
    const double slope_bound = 32 * u * (H_t + pi * H_tt) + 32 * u * a / 6e-6;
    const double h_bound = 32 * u * (H + pi * H_t),
                 squeeze_bound = 32 * u * (R + pi * R_t) + std::abs(w_F) * slope_bound,
                 div_bound = std::abs(w_mean) * slope_bound;

    // the mesh, mapping and quadrature of ReynoldsSolver::setup_system and assemble_system
    AnnulusMesh m = s.mesh;
    m.grading_clearance = g.clearance;
    m.grading_coning = g.coning;
    m.alignment = g.features ? g.features->mesh_alignment() : AnnulusMesh::Alignment();
    parallel::distributed::Triangulation<2> tria(
        MPI_COMM_WORLD, Triangulation<2>::limit_level_difference_at_vertices,
        parallel::distributed::Triangulation<2>::construct_multigrid_hierarchy);
    m.create(tria, ri, ro, 0);
    const unsigned int degree = s.polynomial_degree;
    const FE_Q<2> fe(degree);
    MappingQCache<2> mapping(s.mapping_degree());
    mapping.initialize(MappingQ<2>(s.mapping_degree()), tria);
    PolarCellValues polar(mapping, fe, QGauss<2>(degree + 2));
    const double cos_tilt = std::cos(g.tilt_angle), sin_tilt = std::sin(g.tilt_angle);
    double worst_h = 0, worst_squeeze = 0, worst_div = 0, worst_one_point = 0;
    unsigned int cells = 0, points = 0;
    for (const auto &cell : tria.active_cell_iterators())
    {
      if (!polar.reinit(cell))
        continue; // the assembly takes FEValues there (the test above covers that form)
      ++cells;
      for (const unsigned int q : polar.quadrature_point_indices())
      {
        const Point<2> &x = polar.quadrature_point(q);
        const ReynoldsSolver::LocalFilm f =
            solver.local_film(x, polar.radius(q), polar.angle(q), cos_tilt, sin_tilt);
        const double r_x = x.norm(), theta_x = std::atan2(x[1], x[0]);
        const double slope = g.d_dtheta(r_x, theta_x);
        worst_h = std::max(worst_h, std::abs(f.h - g.value(r_x, theta_x)) / h_bound);
        worst_squeeze =
            std::max(worst_squeeze,
                     std::abs(f.squeeze - (g.d_dt(r_x, theta_x) + w_F * slope)) / squeeze_bound);
        worst_div = std::max(worst_div, std::abs(f.c_div - w_mean * slope) / div_bound);
        // the one-point local_film(x) (loads, output): |x|, atan2 and cos, sin of its own
        const ReynoldsSolver::LocalFilm f1 = solver.local_film(x);
        worst_one_point = std::max({worst_one_point, std::abs(f.h - f1.h) / h_bound,
                                    std::abs(f.squeeze - f1.squeeze) / squeeze_bound,
                                    std::abs(f.c_div - f1.c_div) / div_bound});
        ++points;
      }
    }
    std::cout << c.name << ": " << cells << " of " << tria.n_active_cells() << " cells, " << points
              << " points; worst error / bound: h " << worst_h << ", squeeze " << worst_squeeze
              << ", div c " << worst_div << "; against local_film(x) " << worst_one_point << "\n";
    // every cell of a row is a turned copy of its first (also the aligned mesh's rows)
    EXPECT_EQ(cells, tria.n_active_cells()) << c.name;
    EXPECT_LE(worst_h, 1.0) << c.name;
    EXPECT_LE(worst_squeeze, 1.0) << c.name;
    EXPECT_LE(worst_div, 1.0) << c.name;
    EXPECT_LE(worst_one_point, 1.0) << c.name;
  }
}
