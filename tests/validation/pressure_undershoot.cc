// The interpolation undershoot of the mass-conserving (JFO) pressure at the cavity edge
// (FilmLoads::min_pressure_nodal, pressure_undershoot, pressure_undershoot_force;
// doc/cavitation.md):
//  - the nodes, which the complementarity solve controls, stay at p_cav within its tolerance;
//  - degree 1: the bilinear interpolant on each cell is a convex combination of its vertex values,
//    so it cannot go below its nodes: no undershoot (to round-off);
//  - degree 2: the interpolant may dip below p_cav between nodes; the undershoot is the nodal
//    minimum minus the interpolated one, the dip force the integral of min(p_h - p_cav, 0);
//  - the dip shrinks under refinement.
#include <sealfe/film/film_summary.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/quadrature_lib.h>

#include "../cavitating_wavy_seal.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace sealfe;

using sealfe::testing::low_pressure;
using sealfe::testing::wavy_film;

namespace
{
FilmLoads solve(ReynoldsSolver &s, const Cavitation model, const unsigned int degree,
                const unsigned int nr, const unsigned int nt)
{
  s.cavitation.model = model;
  s.polynomial_degree = degree;
  s.mesh().radial_cells = nr;
  s.mesh().circumferential_cells = nt;
  s.estimate_error = false;
  return s.run(wavy_film(), low_pressure());
}

/// Lowest nodal pressure the JFO stop criterion admits: the Fischer-Burmeister residual of the
/// scaled unknown a = (p - p_cav)/P is below Tolerance, so a >= -Tolerance, with P the full-film
/// pressure excursion max |p - p_cav| (reynolds_solver.cc), bounded here by the full film's range.
double nodal_floor(const ReynoldsSolver &jfo, const unsigned int degree, const unsigned int nr,
                   const unsigned int nt)
{
  ReynoldsSolver full(MPI_COMM_WORLD);
  const FilmLoads f = solve(full, Cavitation::none, degree, nr, nt);
  const double p_cav = jfo.cavitation.pressure;
  const double P = std::max(std::abs(f.max_pressure - p_cav), std::abs(f.min_pressure - p_cav));
  return p_cav - jfo.cavitation.tolerance * P;
}
} // namespace

TEST(PressureUndershoot, LinearElementsCannotUndershootTheirNodes)
{
  ReynoldsSolver s(MPI_COMM_WORLD);
  const FilmLoads l = solve(s, Cavitation::jfo, 1, 8, 128);
  ASSERT_GT(l.cavitated_fraction, 0.2); // the film does cavitate
  EXPECT_GE(l.min_pressure_nodal, nodal_floor(s, 1, 8, 128));
  // A convex combination of nodal values, evaluated in floating point: at most a few roundings
  // of the largest nodal value below the smallest.
  const double round_off = 8 * std::numeric_limits<double>::epsilon() * l.max_pressure;
  EXPECT_NEAR(l.min_pressure, l.min_pressure_nodal, round_off);
  EXPECT_LE(l.pressure_undershoot, round_off);
  // The dip is at most the nodal shortfall below p_cav (and round-off) times the area.
  EXPECT_LE(-l.pressure_undershoot_force,
            (std::max(s.cavitation.pressure - l.min_pressure_nodal, 0.) + round_off) * l.area);
  EXPECT_TRUE(pressure_undershoot_warning(l, s.cavitation.pressure).empty());
}

TEST(PressureUndershoot, QuadraticElementsDipBetweenTheirNodes)
{
  ReynoldsSolver s(MPI_COMM_WORLD);
  const FilmLoads l = solve(s, Cavitation::jfo, 2, 8, 128);
  const double p_cav = s.cavitation.pressure;
  std::cout << "degree 2, 8 x 128: interpolated min " << l.min_pressure << " Pa, nodal min "
            << l.min_pressure_nodal << " Pa, undershoot " << l.pressure_undershoot << " Pa ("
            << 100 * l.pressure_undershoot / (l.max_pressure - p_cav) << " % of the peak), dip "
            << l.pressure_undershoot_force << " N of " << l.force_z << " N\n";
  // The nodes obey the cavitation condition; the interpolant between them does not.
  EXPECT_GE(l.min_pressure_nodal, nodal_floor(s, 2, 8, 128));
  EXPECT_LT(l.min_pressure, p_cav);
  EXPECT_GT(l.pressure_undershoot, 0.);
  EXPECT_DOUBLE_EQ(l.pressure_undershoot, std::min(p_cav, l.min_pressure_nodal) - l.min_pressure);
  // The dip force is int min(p_h - p_cav, 0) dA: against an independent composite rule of
  // 32 x 32 copies of a 6-point Gauss rule per cell. The reported one uses 8 x 8 copies of the
  // 4-point rule on the cells at the cavity edge; its error comes from the sub-cells the kink of
  // min(., 0) cuts, O(1/8^2) = 1.6 % of the dip at most (the reference's is 16 times smaller).
  const double direct =
      s.pressure_integral([p_cav](const double p) { return std::min(p - p_cav, 0.); },
                          dealii::QIterated<2>(dealii::QGauss<1>(6), 32));
  std::cout << "dip force " << l.pressure_undershoot_force << " N, direct quadrature " << direct
            << " N\n";
  EXPECT_LT(l.pressure_undershoot_force, 0.);
  EXPECT_NEAR(l.pressure_undershoot_force, direct, 1.6e-2 * std::abs(direct));
  // and it is bounded by the undershoot times the area.
  EXPECT_LE(-l.pressure_undershoot_force, l.pressure_undershoot * l.area);
}

TEST(PressureUndershoot, ShrinksUnderRefinement)
{
  // The interpolant's overshoot at a kink of the solution (the pressure gradient jumps at
  // rupture) falls with the cell size: the undershoot and the dip decrease with each halving.
  double previous_undershoot = std::numeric_limits<double>::infinity();
  double previous_dip = previous_undershoot;
  for (const unsigned int k : {1u, 2u, 4u})
  {
    ReynoldsSolver s(MPI_COMM_WORLD);
    const FilmLoads l = solve(s, Cavitation::jfo, 2, 4 * k, 64 * k);
    const double relative = l.pressure_undershoot / (l.max_pressure - s.cavitation.pressure);
    std::cout << 4 * k << " x " << 64 * k << ": undershoot " << 100 * relative << " % of peak, dip "
              << l.pressure_undershoot_force << " N\n";
    EXPECT_LT(relative, previous_undershoot);
    EXPECT_LT(std::abs(l.pressure_undershoot_force), previous_dip);
    previous_undershoot = relative;
    previous_dip = std::abs(l.pressure_undershoot_force);
  }
}

TEST(PressureUndershoot, ReportedInTheSummaryWithAWarningAboveOnePercent)
{
  ReynoldsSolver s(MPI_COMM_WORLD);
  const FilmLoads l = solve(s, Cavitation::jfo, 2, 4, 64);
  ::testing::internal::CaptureStderr();
  const nlohmann::json j = finite_element_solve_summary(s.settings, s, l, MPI_COMM_WORLD);
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(j["min_pressure_nodal"].get<double>(), l.min_pressure_nodal);
  EXPECT_EQ(j["pressure_undershoot"].get<double>(), l.pressure_undershoot);
  EXPECT_EQ(j["pressure_undershoot_force"].get<double>(), l.pressure_undershoot_force);
  const bool above = l.pressure_undershoot > 0.01 * (l.max_pressure - s.cavitation.pressure);
  EXPECT_EQ(j.contains("pressure_undershoot_warning"), above);
  EXPECT_EQ(err.find("pressure dips") != std::string::npos, above) << err;

  // The threshold itself: 1 % of the peak above p_cav.
  FilmLoads f;
  f.max_pressure = 1e6;
  f.pressure_undershoot = 0.011e6;
  f.pressure_undershoot_force = -3;
  EXPECT_FALSE(pressure_undershoot_warning(f, 0.).empty());
  f.pressure_undershoot = 0.009e6;
  EXPECT_TRUE(pressure_undershoot_warning(f, 0.).empty());
  EXPECT_TRUE(pressure_undershoot_warning(f, -1e5).empty()); // 0.9e4 / 1.1e6

  // Models that do not hold the nodes at p_cav report no undershoot.
  ReynoldsSolver n(MPI_COMM_WORLD);
  const FilmLoads none = solve(n, Cavitation::none, 2, 4, 64);
  EXPECT_LT(none.min_pressure, 0.); // the full film goes far below p_cav = 0 ...
  EXPECT_EQ(none.pressure_undershoot, 0.);
  EXPECT_EQ(none.pressure_undershoot_force, 0.);
  EXPECT_LE(none.min_pressure, none.min_pressure_nodal);
}
