// The finite-element Reynolds solution against the narrow-seal closed forms (Etsion 1977):
// for a tilted flat face in full film (pure hydrodynamics, pi = po = 0) the FE transverse moment
// departs from Etsion's full-film closed form (Eq. 58, corrected) only through the narrow-seal
// approximations (curvature, circumferential pressure flow), which are O((1 - ri/ro)^2).
// Half-Sommerfeld: the same for force, restoring and transverse moment (Eqs. 29, 43, 56).
#include <sealfe/closed_form/narrow_seal.h>
#include <sealfe/film/reynolds_solver.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace sealfe;

namespace
{
struct Departure
{
  double force, restoring, transverse;
};

/// Relative departures of the FE loads from Etsion's closed forms for a flat seal tilted to eps.
Departure departure(const double Ri, const double eps, const Cavitation cavitation)
{
  FilmThickness film;
  film.coning = 0;
  film.outer_radius = 0.0408;
  film.inner_radius = Ri * film.outer_radius;
  film.tilt = eps * film.clearance / film.outer_radius;
  film.tilt_angle = 0.4;
  OperatingConditions conditions;
  conditions.inner_pressure = conditions.outer_pressure = 0;

  ReynoldsSolver solver(MPI_COMM_WORLD);
  solver.polynomial_degree = 3;
  solver.cavitation.model = cavitation;
  // The pressure is (ro - r)(r - ri)/h^2-like across the dam: a few cubic cells resolve it to
  // round-off relative to the (1 - Ri)^2 departures measured here; theta needs more cells.
  solver.mesh().radial_cells = 4;
  solver.mesh().circumferential_cells = cavitation == Cavitation::none ? 256 : 512;
  const FilmLoads fe = solver.run(film, conditions);

  const etsion::TiltLoads closed = etsion::loads(film, conditions, cavitation);
  Departure d;
  d.transverse = fe.moment_transverse / closed.moment_transverse - 1;
  d.restoring = cavitation == Cavitation::none
                    ? fe.moment_restoring / std::abs(closed.moment_transverse)
                    : fe.moment_restoring / closed.moment_restoring - 1;
  d.force = cavitation == Cavitation::none
                ? fe.force_z * film.outer_radius / std::abs(closed.moment_transverse)
                : fe.force_z / closed.force_z - 1;
  return d;
}
} // namespace

TEST(ReynoldsNarrowSeal, FullFilmTransverseMomentDepartureShrinksLikeWidthSquared)
{
  const double eps = 0.5;
  std::vector<double> widths = {0.1, 0.05, 0.02, 0.01}, dep;
  for (const double w : widths)
  {
    const Departure d = departure(1 - w, eps, Cavitation::none);
    dep.push_back(std::abs(d.transverse));
    std::cout << "1-Ri " << w << " transverse departure " << d.transverse << " force/moment "
              << d.force << " restoring/moment " << d.restoring << "\n";
    // Antisymmetric full-film pressure: no hydrodynamic force or restoring moment (to the
    // discretisation error of the FE solve).
    EXPECT_LT(std::abs(d.force), 1e-6);
    EXPECT_LT(std::abs(d.restoring), 1e-6);
  }
  for (unsigned int i = 1; i < widths.size(); ++i)
  {
    const double slope = std::log(dep[i - 1] / dep[i]) / std::log(widths[i - 1] / widths[i]);
    std::cout << "observed rate between 1-Ri = " << widths[i - 1] << " and " << widths[i] << ": "
              << slope << "\n";
    EXPECT_NEAR(slope, 2.0, 0.15);
  }
  // Size at ri/ro = 0.99: a (1 - Ri)^2 departure with a constant below 1 (measured: 0.025).
  EXPECT_LT(dep.back(), widths.back() * widths.back());
}

TEST(ReynoldsNarrowSeal, HalfSommerfeldLoadsMatchEtsionCavitatingClosedForms)
{
  for (const double eps : {0.3, 0.6})
  {
    std::vector<Departure> d;
    for (const double w : {0.04, 0.02, 0.01})
      d.push_back(departure(1 - w, eps, Cavitation::half_sommerfeld));
    for (unsigned int i = 0; i < d.size(); ++i)
      std::cout << "eps " << eps << " force " << d[i].force << " restoring " << d[i].restoring
                << " transverse " << d[i].transverse << "\n";
    const double rate_force = std::log2(std::abs(d[0].force / d[1].force));
    const double rate_transverse = std::log2(std::abs(d[0].transverse / d[1].transverse));
    std::cout << "rates: force " << rate_force << " transverse " << rate_transverse << "\n";
    EXPECT_NEAR(rate_force, 2.0, 0.3);
    EXPECT_NEAR(rate_transverse, 2.0, 0.3);
    // At ri/ro = 0.99 every load is within 1e-4 of the closed form.
    EXPECT_LT(std::abs(d[2].force), 1e-4);
    EXPECT_LT(std::abs(d[2].restoring), 1e-4);
    EXPECT_LT(std::abs(d[2].transverse), 1e-4);
  }
}
