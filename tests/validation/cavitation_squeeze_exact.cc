// A semi-analytic JFO solution in one dimension: flat faces separating axisymmetrically at
// dh/dt > 0 without rotation, with a supply pressure p_s on both circles. The film is sucked
// in; in the middle of the dam it cavitates (p = p_cav = 0). In the cavity the JFO mass balance
// s dh/dt = 0 gives s = 0; in the two full-film zones
//   (1/r) d/dr(r K dp/dr) = dh/dt,  K = h^3/(12 mu)  =>  p = a r^2 + A ln r + B, a = h_t/(4K),
// with p = p_s at the circle and p = dp/dr = 0 at the cavity boundary r_c (free boundary), so
//   a (r0^2 - r_c^2 + 2 r_c^2 ln(r_c/r0)) = p_s  for r0 = ri and r0 = ro,
// two scalar equations for the two cavity radii, solved here by bisection. The FE JFO solution
// (2D, Q2) must reproduce the force, the cavitated area and the leakage.
#include <sealfe/film/reynolds_solver.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace sealfe;

namespace
{
struct SqueezeCavity
{
  double ri, ro, a, ps;
  /// p_s/a = g(r_c) for the zone attached to the circle r0
  double g(double r0, double rc) const
  {
    return r0 * r0 - rc * rc + 2 * rc * rc * std::log(rc / r0);
  }
  /// The root of a g(r0, r_c) = p_s between r0 and `other` (a g increases away from r0 from 0).
  double cavity_radius(double r0, double other) const
  {
    double lo = 0, hi = 1; // fractions of the way from r0 to other
    for (int i = 0; i < 100; ++i)
    {
      const double mid = 0.5 * (lo + hi);
      (a * g(r0, r0 + mid * (other - r0)) > ps ? hi : lo) = mid;
    }
    return r0 + 0.5 * (lo + hi) * (other - r0);
  }
  /// int p r dr over the zone between r0 and rc
  double zone_force(double r0, double rc) const
  {
    const double A = -2 * a * rc * rc, B = -a * rc * rc - A * std::log(rc);
    auto F = [&](double r)
    { return a * std::pow(r, 4) / 4 + A * (r * r / 2 * std::log(r) - r * r / 4) + B * r * r / 2; };
    return 2 * M_PI * std::abs(F(rc) - F(r0));
  }
};
} // namespace

TEST(CavitationSqueezeExact, JfoMatchesTheSemiAnalyticCavity)
{
  FilmThickness film;
  film.coning = 0;
  film.axial_velocity = 2e-5; // m/s, opening
  OperatingConditions conditions;
  conditions.rotor_speed = 0;
  conditions.inner_pressure = conditions.outer_pressure = 1e5;
  const double K = std::pow(film.clearance, 3) / (12 * conditions.viscosity);
  SqueezeCavity exact{film.inner_radius, film.outer_radius, film.axial_velocity / (4 * K),
                      conditions.inner_pressure};
  const double rc_in = exact.cavity_radius(exact.ri, exact.ro);
  const double rc_out = exact.cavity_radius(exact.ro, exact.ri);
  ASSERT_LT(rc_in, rc_out) << "the case must cavitate";
  const double force = exact.zone_force(exact.ri, rc_in) + exact.zone_force(exact.ro, rc_out);
  const double area = M_PI * (exact.ro * exact.ro - exact.ri * exact.ri);
  const double cavitated = M_PI * (rc_out * rc_out - rc_in * rc_in) / area;
  // leakage: what the two full-film zones draw in = -h_t times their area (out of the dam < 0)
  const double inflow = film.axial_velocity * (area - M_PI * (rc_out * rc_out - rc_in * rc_in));
  std::cout << "exact: cavity " << rc_in << " .. " << rc_out << " m, force " << force
            << " N, cavitated " << cavitated << ", inflow " << inflow << " m^3/s\n";

  std::vector<double> errors;
  for (const unsigned int nr : {8u, 16u, 32u})
  {
    ReynoldsSolver solver(MPI_COMM_WORLD);
    solver.cavitation.model = Cavitation::jfo;
    solver.mesh().radial_cells = nr;
    solver.mesh().circumferential_cells = 16;
    const FilmLoads l = solver.run(film, conditions);
    errors.push_back(std::abs(l.force_z / force - 1));
    std::cout << "nr " << nr << ": force " << l.force_z << " (rel. error " << errors.back()
              << "), cavitated " << l.cavitated_fraction << ", inflow "
              << -(l.leakage_inner + l.leakage_outer) << ", Newton "
              << solver.nonlinear_iterations() << "\n";
    // The cavity edges are located to about a radial cell each: allow 1/nr of the area.
    EXPECT_NEAR(-(l.leakage_inner + l.leakage_outer) / inflow, 1.0, 1.0 / nr);
    EXPECT_NEAR(l.cavitated_fraction, cavitated, 1.0 / nr);
  }
  // the force converges to the semi-analytic one (the free boundary is C1: p ~ (r - r_c)^2)
  EXPECT_LT(errors.back(), 2e-3);
  EXPECT_LT(errors[2], errors[0]);
}
