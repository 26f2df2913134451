// The assembly on the built-in annulus takes the geometry of each cell from its radial row
// (PolarCellValues: every cell of a row is the row's first cell turned about the axis by a
// multiple of 2 pi / N_theta). That is an identity of the mesh (vertices on circles at the angles
// 2 pi j / N_theta, polar manifold), so the turned values must equal FEValues on every cell, and
// the solve assembled with them the solve assembled with FEValues, to round-off. Tolerances:
// the vertices and the mapping's support points carry round-off u r (u = 1.1e-16, r <= ro); the
// mapping differentiates them across a cell, so its Jacobian, JxW and the shape gradients carry
// u ro / h_r relative (h_r the smallest radial cell width), times the weights of the derivatives
// of the degree-k Lagrange polynomials and the inverse Jacobian of cells up to ~45 times longer
// than wide: observed up to ~100 u ro / h_r (k = 3), bounded here by 1000 u ro / h_r. The loads
// of a direct (KLU) solve move with the matrix entries by at most the condition number (~1e5 on
// these meshes) times their round-off.
#include "../cavitating_wavy_seal.h"
#include "../graded_annulus.h"
#include <sealfe/film/annulus_mesh.h>
#include <sealfe/film/film_summary.h>
#include <sealfe/film/polar_cell_values.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q_cache.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

using namespace sealfe;
using namespace dealii;

namespace
{
/// The loads of one cavitation model on the built-in 8 x 128 annulus (degree 2), assembled from
/// the rows' values (`turned`) and with FEValues (`plain`), and the smallest and largest radial
/// cell width of that mesh [m] and its number of dofs.
struct BothPaths
{
  FilmLoads turned, plain;
  double h_r = 0, h_r_max = 0, dofs = 0;
};

BothPaths loads_on_both_paths(const Cavitation model, const FilmThickness &film,
                              const OperatingConditions &conditions)
{
  ReynoldsSolver turned(MPI_COMM_WORLD), plain(MPI_COMM_WORLD);
  for (ReynoldsSolver *s : {&turned, &plain})
  {
    s->cavitation.model = model;
    s->mesh().radial_cells = 8;
    s->mesh().circumferential_cells = 128;
    s->estimate_error = false;
  }
  plain.polar_rows = false;
  BothPaths result{turned.run(film, conditions), plain.run(film, conditions)};
  const std::vector<double> radii =
      turned.mesh().radial_nodes(8, film.inner_radius, film.outer_radius);
  result.dofs = turned.n_dofs();
  result.h_r = film.outer_radius;
  for (unsigned int k = 0; k + 1 < radii.size(); ++k)
  {
    result.h_r = std::min(result.h_r, radii[k + 1] - radii[k]);
    result.h_r_max = std::max(result.h_r_max, radii[k + 1] - radii[k]);
  }
  return result;
}
} // namespace

TEST(PolarCellValues, EqualFEValuesOnEveryCellOfEveryLevel)
{
  const double ri = test::GradedAnnulus::ri, ro = test::GradedAnnulus::ro;
  for (const unsigned int degree : {1u, 2u, 3u})
  {
    test::GradedAnnulus annulus(MPI_COMM_WORLD);
    auto &tria = annulus.tria;
    const FE_Q<2> fe(degree);
    MappingQCache<2> mapping(degree);
    mapping.initialize(MappingQ<2>(degree), tria);
    const QGauss<2> quadrature(degree + 2);
    FEValues<2> fe_values(mapping, fe, quadrature,
                          update_values | update_gradients | update_quadrature_points |
                              update_JxW_values);
    PolarCellValues polar(mapping, fe, quadrature);
    const unsigned int n = fe.n_dofs_per_cell();
    double h_r = ro;
    for (const auto &cell : tria.active_cell_iterators())
      h_r = std::min(h_r, cell->vertex(1).norm() - cell->vertex(0).norm());
    const double tol = 1000 * 1.1e-16 * ro / h_r;
    double worst_r = 0, worst_angle = 0;
    bool in_range = true;
    double worst_x = 0, worst_jxw = 0, worst_grad = 0, worst_gram = 0, worst_value = 0;
    unsigned int cells = 0;
    for (unsigned int l = 0; l < tria.n_global_levels(); ++l)
      for (const auto &cell : tria.cell_iterators_on_level(l))
      {
        ++cells;
        ASSERT_TRUE(polar.reinit(cell)) << "degree " << degree << ", level " << l;
        fe_values.reinit(cell);
        double grad_scale = 0, jxw_scale = 0;
        for (const unsigned int q : fe_values.quadrature_point_indices())
        {
          jxw_scale = std::max(jxw_scale, fe_values.JxW(q));
          for (unsigned int i = 0; i < n; ++i)
            grad_scale = std::max(grad_scale, fe_values.shape_grad(i, q).norm());
        }
        const double gram_scale = grad_scale * grad_scale * jxw_scale;
        for (const unsigned int q : fe_values.quadrature_point_indices())
        {
          worst_x = std::max(
              worst_x, fe_values.quadrature_point(q).distance(polar.quadrature_point(q)) / ro);
          // radius and angle of the point from the row's (norm, atan2 of FEValues' point); the
          // angle compared modulo 2 pi (at +-pi round-off may pick the other end of the range)
          const Point<2> &x = fe_values.quadrature_point(q);
          worst_r = std::max(worst_r, std::abs(x.norm() - polar.radius(q)) / ro);
          worst_angle = std::max(
              worst_angle,
              std::abs(std::remainder(std::atan2(x[1], x[0]) - polar.angle(q), 2 * numbers::PI)));
          in_range = in_range && polar.angle(q) > -numbers::PI && polar.angle(q) <= numbers::PI;
          worst_jxw = std::max(worst_jxw, std::abs(fe_values.JxW(q) - polar.JxW(q)) / jxw_scale);
          for (unsigned int i = 0; i < n; ++i)
          {
            worst_value = std::max(worst_value,
                                   std::abs(fe_values.shape_value(i, q) - polar.shape_value(i, q)));
            worst_grad =
                std::max(worst_grad,
                         (fe_values.shape_grad(i, q) - polar.shape_grad(i, q)).norm() / grad_scale);
            for (unsigned int j = 0; j < n; ++j)
              worst_gram =
                  std::max(worst_gram, std::abs(fe_values.shape_grad(i, q) *
                                                    fe_values.shape_grad(j, q) * fe_values.JxW(q) -
                                                polar.gram(q)[i * n + j]) /
                                           gram_scale);
          }
        }
      }
    // every cell but the first of each row given by turning
    EXPECT_EQ(polar.n_turned() + polar.n_rows(), cells) << "degree " << degree;
    EXPECT_LT(worst_x, 1e-13) << "degree " << degree;
    // a point error e moves the radius by <= e and the angle by <= e / r (r >= ri)
    EXPECT_LT(worst_r, 1e-13) << "degree " << degree;
    EXPECT_LT(worst_angle, 1e-13 * ro / ri) << "degree " << degree;
    EXPECT_TRUE(in_range) << "degree " << degree;
    EXPECT_LT(worst_jxw, tol) << "degree " << degree;
    EXPECT_EQ(worst_value, 0.0) << "degree " << degree; // FE_Q: the same numbers on every cell
    EXPECT_LT(worst_grad, tol) << "degree " << degree;
    EXPECT_LT(worst_gram, tol) << "degree " << degree;
    std::cout << "degree " << degree << ": ro / h_r = " << ro / h_r << ", JxW " << worst_jxw
              << ", gradients " << worst_grad << ", products " << worst_gram << " (bound " << tol
              << ")\n";
  }
}

TEST(PolarCellValues, SolveEqualsTheFEValuesAssembly)
{
  // A tilted, wavy face pair with squeeze (axial and tilt rates): every term of the assembly
  // (K, Couette flux, squeeze, the loads' weights) varies around the annulus.
  for (const unsigned int degree : {1u, 2u, 3u})
  {
    FilmSettings s;
    s.geometry.tilt = 0.5 * s.geometry.clearance / s.geometry.outer_radius;
    s.geometry.tilt_angle = 0.3;
    s.geometry.wave_amplitude = 0.2e-6;
    s.geometry.wave_number = 3;
    s.geometry.axial_velocity = 1e-4;
    s.geometry.tilt_rate_x = 2e-3;
    s.polynomial_degree = degree;
    s.mesh.radial_cells = 8;
    s.mesh.circumferential_cells = 64;
    s.estimate_error = false;
    s.linear_solver = FilmSettings::LinearSolver::direct;
    ReynoldsSolver turned(s, MPI_COMM_WORLD), plain(s, MPI_COMM_WORLD);
    plain.polar_rows = false;
    const FilmLoads a = turned.run(), b = plain.run();
    ASSERT_TRUE(turned.loads_from_assembled_sums());
    const double F = std::abs(a.force_z), ro = s.geometry.outer_radius;
    const double Q = std::abs(a.leakage_outer), T = std::abs(a.friction_torque);
    // The turned gradients differ from FEValues' by up to ~100 u r_o/h_r (3e-12 relative on
    // this mesh, first test), so do the matrix entries; the loads were observed within 2.4e-13.
    // 1e-10 is an empirical margin above that, not a derived bound.
    const double tol = 1e-10;
    EXPECT_NEAR(a.force_z, b.force_z, tol * F) << "degree " << degree;
    EXPECT_NEAR(a.moment_x, b.moment_x, tol * F * ro) << "degree " << degree;
    EXPECT_NEAR(a.moment_y, b.moment_y, tol * F * ro) << "degree " << degree;
    EXPECT_NEAR(a.leakage_inner, b.leakage_inner, tol * Q) << "degree " << degree;
    EXPECT_NEAR(a.leakage_outer, b.leakage_outer, tol * Q) << "degree " << degree;
    EXPECT_NEAR(a.friction_torque, b.friction_torque, tol * T) << "degree " << degree;
    std::cout << "degree " << degree << ": force_z " << (a.force_z - b.force_z) / F << ", moment_x "
              << (a.moment_x - b.moment_x) / (F * ro) << ", leakage "
              << (a.leakage_outer - b.leakage_outer) / Q << " relative\n";
  }
}

// JFO (mass-conserving cavitation) on the built-in annulus: the cell matrices A, G, F take the
// rows' values (JFOSolver::compute_cell_matrices) and so does the leakage residual of the cells on
// the circles, void-fraction terms included (LoadIntegrator::polar_assembly). Two claims:
//  - The leakages balance to round-off. With the residual built from the values the system was
//    assembled with, Q_in + Q_out + squeeze is (by sum_i phi_i = 1) the sum of the solved
//    system's residuals at the N dofs off the circles, each zero but for the round-off of its
//    sums (the final Newton system on a fixed cavitated set, solved directly). A residual sums
//    ~4 cells x 16 points of fluxes through a cell, each at most q = Q_h h_r,max / (ro - ri)
//    (Q_h: the flow scale Q_s of film_summary.h with the thickest film instead of C0; the flux
//    through one cell is its share of the flux through a radial line): its round-off is a
//    random walk of ~64 roundings, ~10 u q. The N residuals' round-off adds up as a random walk
//    too (Higham & Mary 2019, probabilistic rounding error analysis): within lambda sqrt(N) 10 u
//    q with lambda = 3 (the worst-case N 10 u q would not tell a wrong geometry from a right
//    one). Measured 0.2-0.8 sqrt(N) u Q_h (both paths). With the loads' residual on FEValues where
//    the system has the rows' values (the assembly moved without the loads), the two geometries'
//    round-off
//    (~100 u ro / h_r of every term) entered every boundary dof instead: 1.9e-13 Q_s on the
//    wavy seal (15 sqrt(N) u Q_h, 4x its bound of 3.75) and 2.2e-13 Q_s on the tilted one (4.4,
//    within its bound of 10.4: its graded cells' wider flux q leaves room). The cavity of neither
//    seal puts a macroscopic void into the cells on the circles (the supply keeps the film full
//    there); the void terms of their residual still matter at the 1e-10 level: left out, the
//    imbalance was 2.4e-10 and 2.2e-9 Q_s.
//  - The loads equal those of the FEValues path (polar_rows = false) to the geometry's round-off.
//    The two systems are one Galerkin problem whose point data (JxW, mapped gradients) differ
//    by at most delta = 1000 u ro / h_r relative (first test), i.e. the same discrete problem with
//    K (two gradients and JxW: 3 delta), the Couette flux (2 delta) and the squeeze term (delta)
//    perturbed pointwise; on the same cavitated set the problem is linear and elliptic in p, and
//    its solution, hence force and moments (integrals of p), moves by the same relative order:
//    bounded by 10 delta of the force (moments: of force times ro). A different cavitated set
//    would move them by a node's share of the load, far above that.
// Two seals: the cavitating wavy seal (tests/cavitating_wavy_seal.h) and the benchmark's tilted
// Varney & Green seal (benchmarks/reynolds_speed/case.prm; graded mesh, ro / h_r = 241).
TEST(PolarCellValues, JfoLeakagesBalanceToRoundOffAndLoadsEqualTheFEValuesPath)
{
  const double u = 0.5 * std::numeric_limits<double>::epsilon();
  for (const bool tilted_seal : {false, true})
  {
    FilmThickness film = sealfe::testing::wavy_film();
    OperatingConditions conditions = sealfe::testing::low_pressure();
    if (tilted_seal)
    {
      film = FilmThickness();
      film.tilt = 0.5 * film.clearance / film.outer_radius;
      conditions = OperatingConditions();
    }
    const BothPaths paths = loads_on_both_paths(Cavitation::jfo, film, conditions);
    const FilmLoads &a = paths.turned, &b = paths.plain;
    ASSERT_GT(a.cavitated_fraction, 0.05); // the case does cavitate

    const double ri = film.inner_radius, ro = film.outer_radius;
    const double h_r = paths.h_r, h_r_max = paths.h_r_max;
    const double Q_s = mass_balance_flow_scale(film, conditions, a);
    const double Q_h = Q_s * film.maximum().value / film.clearance;
    const double q = Q_h * h_r_max / (ro - ri);
    const double N = paths.dofs, bound = 3 * std::sqrt(N) * 10 * u * q;
    for (const FilmLoads *l : {&a, &b})
    {
      const double imbalance = std::abs(l->leakage_inner + l->leakage_outer + l->squeeze_flow);
      std::cout << (l == &a ? "rows" : "FEValues")
                << (tilted_seal ? ", tilted seal" : ", wavy seal") << ": leakage "
                << l->leakage_outer << " m^3/s, imbalance " << imbalance / Q_s
                << " Q_s = " << imbalance / (std::sqrt(N) * u * Q_h) << " sqrt(N) u Q_h (bound "
                << bound / (std::sqrt(N) * u * Q_h) << "), cavitated " << l->cavitated_fraction
                << "\n";
      EXPECT_LT(imbalance, bound) << (l == &a ? "rows" : "FEValues") << tilted_seal;
    }

    const double delta = 1000 * u * ro / h_r, tol = 10 * delta;
    const double F = std::abs(a.force_z);
    std::cout << "  force_z " << (a.force_z - b.force_z) / F << ", moment_x "
              << (a.moment_x - b.moment_x) / (F * ro) << ", moment_y "
              << (a.moment_y - b.moment_y) / (F * ro) << ", leakage_outer "
              << (a.leakage_outer - b.leakage_outer) / Q_s << " relative (bound " << tol
              << ", ro / h_r = " << ro / h_r << ")\n";
    EXPECT_NEAR(a.force_z, b.force_z, tol * F) << tilted_seal;
    EXPECT_NEAR(a.moment_x, b.moment_x, tol * F * ro) << tilted_seal;
    EXPECT_NEAR(a.moment_y, b.moment_y, tol * F * ro) << tilted_seal;
    EXPECT_NEAR(a.leakage_outer, b.leakage_outer, tol * Q_s) << tilted_seal;
    // the same cavitated set: its area moves by the JxW's round-off only (integrate takes the
    // rows' JxW too), where a node more or less moves it by about a cell's share (1/512 here)
    EXPECT_NEAR(a.cavitated_fraction, b.cavitated_fraction, tol) << tilted_seal;
  }
}

// The reynolds (Swift-Stieber) system on the built-in annulus is assembled with the rows' values
// too (ReynoldsCavitationSolver::assemble), and so is its leakage residual: the loads equal those
// of the FEValues path to the geometry's round-off, by the argument of the test above (the same
// discrete problem with its point data perturbed by at most delta = 1000 u ro / h_r relative, on
// the same cavitated set linear in p): within 10 delta. (Swift-Stieber does not conserve mass at
// reformation, so its leakages do not balance: no claim on that.)
TEST(PolarCellValues, ReynoldsCavitationLoadsEqualTheFEValuesPath)
{
  const double u = 0.5 * std::numeric_limits<double>::epsilon();
  FilmThickness film; // Varney & Green's seal, tilted as in benchmarks/reynolds_speed/case.prm
  film.tilt = 0.5 * film.clearance / film.outer_radius;
  const OperatingConditions conditions;
  const BothPaths paths = loads_on_both_paths(Cavitation::reynolds, film, conditions);
  const FilmLoads &a = paths.turned, &b = paths.plain;
  ASSERT_GT(a.cavitated_fraction, 0.01); // the case does cavitate
  const double ro = film.outer_radius, h_r = paths.h_r;
  const double tol = 10 * 1000 * u * ro / h_r;
  const double F = std::abs(a.force_z), Q_s = mass_balance_flow_scale(film, conditions, a);
  std::cout << "force_z " << (a.force_z - b.force_z) / F << ", moment_x "
            << (a.moment_x - b.moment_x) / (F * ro) << ", leakage_inner "
            << (a.leakage_inner - b.leakage_inner) / Q_s << ", leakage_outer "
            << (a.leakage_outer - b.leakage_outer) / Q_s << " relative (bound " << tol
            << "), cavitated " << a.cavitated_fraction << "\n";
  EXPECT_NEAR(a.force_z, b.force_z, tol * F);
  EXPECT_NEAR(a.moment_x, b.moment_x, tol * F * ro);
  EXPECT_NEAR(a.moment_y, b.moment_y, tol * F * ro);
  EXPECT_NEAR(a.leakage_inner, b.leakage_inner, tol * Q_s);
  EXPECT_NEAR(a.leakage_outer, b.leakage_outer, tol * Q_s);
  EXPECT_NEAR(a.cavitated_fraction, b.cavitated_fraction, tol); // the same set (test above)
}

// A cell that is not its row's first cell turned (one vertex moved) must be refused, or, if the
// move changed its row key, be the first cell of a row of its own (FEValues on itself); no cell
// may get the turned values of a row it does not belong to. The key holds the radii of vertices
// 0 and 1 and the angle between vertices 0 and 2 (units 2^-36). A vertex moved by 1e-14 m along
// its circle (above the 64 u r = 6e-16 m of the vertex check, far below the 2^-36 (1.5e-11) of
// the key's angle, 2.5e-13 here) leaves the keys of the four cells around it unchanged: all four
// are refused (none is a row's first cell). Moved by 1e-6 m, the cells whose vertex 0 or 2 it
// is get new keys (new rows of their own); those whose vertex 1 or 3 it is keep theirs and are
// refused. Either way nothing else is refused, and every cell reinit takes has FEValues' points
// and gradients (the tolerance of the test above).
TEST(PolarCellValues, RefusesACellThatIsNoRotation)
{
  const double ri = 0.0355, ro = 0.0408;
  const unsigned int degree = 2;
  for (const double move : {1e-14, 1e-6})
  {
    AnnulusMesh m;
    m.radial_cells = 4;
    m.circumferential_cells = 32;
    parallel::distributed::Triangulation<2> tria(MPI_COMM_WORLD);
    m.create(tria, ri, ro, 0);
    // vertex 3 of a cell halfway round (not a row's first cell), moved along its circle
    auto moved_cell = tria.begin_active();
    for (const auto &cell : tria.active_cell_iterators())
      if (cell->center()[0] < -0.9 * cell->center().norm() && cell->vertex(0).norm() > ri * 1.01)
      {
        moved_cell = cell;
        break;
      }
    Point<2> &x3 = moved_cell->vertex(3);
    const double alpha = move / x3.norm(); // turned on its circle: the radius keeps its key
    const Point<2> moved_vertex(std::cos(alpha) * x3[0] - std::sin(alpha) * x3[1],
                                std::sin(alpha) * x3[0] + std::cos(alpha) * x3[1]);
    x3 = moved_vertex;

    const FE_Q<2> fe(degree);
    const MappingQ<2> mapping(degree);
    const QGauss<2> quadrature(degree + 2);
    FEValues<2> fe_values(mapping, fe, quadrature, update_gradients | update_quadrature_points);
    PolarCellValues polar(mapping, fe, quadrature);
    const unsigned int n = fe.n_dofs_per_cell();
    const double h_r = (ro - ri) / m.radial_cells, tol = 1000 * 1.1e-16 * ro / h_r;
    unsigned int refused = 0, refused_elsewhere = 0, taken = 0;
    double worst_x = 0, worst_grad = 0;
    for (const auto &cell : tria.active_cell_iterators())
    {
      bool touches = false;
      for (unsigned int k = 0; k < 4; ++k)
        touches = touches || cell->vertex(k).distance(moved_vertex) == 0;
      if (!polar.reinit(cell))
      {
        ++refused;
        refused_elsewhere += touches ? 0 : 1;
        continue;
      }
      ++taken;
      fe_values.reinit(cell);
      double grad_scale = 0;
      for (const unsigned int q : fe_values.quadrature_point_indices())
        for (unsigned int i = 0; i < n; ++i)
          grad_scale = std::max(grad_scale, fe_values.shape_grad(i, q).norm());
      for (const unsigned int q : fe_values.quadrature_point_indices())
      {
        worst_x = std::max(worst_x,
                           fe_values.quadrature_point(q).distance(polar.quadrature_point(q)) / ro);
        for (unsigned int i = 0; i < n; ++i)
          worst_grad =
              std::max(worst_grad,
                       (fe_values.shape_grad(i, q) - polar.shape_grad(i, q)).norm() / grad_scale);
      }
    }
    std::cout << "vertex moved " << move << " m: " << taken << " taken, " << refused
              << " refused; points " << worst_x << ", gradients " << worst_grad << "\n";
    EXPECT_EQ(taken + refused, tria.n_active_cells());
    EXPECT_EQ(refused_elsewhere, 0u) << move;
    EXPECT_EQ(refused, move < 1e-11 ? 4u : 2u) << move;
    EXPECT_LT(worst_x, 1e-13) << move;
    EXPECT_LT(worst_grad, tol) << move;
  }
}
