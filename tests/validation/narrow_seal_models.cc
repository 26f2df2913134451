// Validation of the narrow-seal film model (level 0): its pressure solves the narrow Reynolds
// equation, its loads integrate to Etsion's closed forms, conservation and symmetry hold, and the
// textbook limits (parallel-plate squeeze film, slot leakage, Couette torque) come out.
#include <sealfe/closed_form/narrow_seal.h>

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <stdexcept>

using namespace sealfe;

namespace
{
// A flat face pair tilted to Etsion's parameter eps = gamma ro / C, thickest at theta = psi.
FilmThickness tilted_film(const double eps, const double Ri, const double psi = 0.7)
{
  FilmThickness f;
  f.outer_radius = 0.05;
  f.inner_radius = Ri * f.outer_radius;
  f.clearance = 2e-6;
  f.coning = 0;
  f.tilt = eps * f.clearance / f.outer_radius;
  f.tilt_angle = psi;
  return f;
}

// Etsion's seal: no sealed pressure, so only hydrodynamics. Both faces turn (mean speed 150 rad/s)
// to exercise omega_Etsion = w1 + w2.
OperatingConditions etsion_conditions()
{
  OperatingConditions oc;
  oc.inner_pressure = 0;
  oc.outer_pressure = 0;
  oc.viscosity = 1.7e-3;
  oc.rotor_speed = 200;
  oc.stator_speed = 100;
  return oc;
}

NarrowSealQuadrature etsion_measure()
{
  NarrowSealQuadrature q;
  q.curvature = Curvature::neglected;
  return q;
}

double rel(const double a, const double b)
{
  return std::abs(a - b) / std::abs(b);
}

struct Case
{
  double eps, Ri;
};
// Wide and narrow dams, from small tilt to near touch-down.
const Case cases[] = {{0.05, 0.5}, {0.3, 0.8}, {0.6, 0.95}, {0.7, 0.9}, {0.9, 0.99}, {0.95, 0.6}};
} // namespace

// Etsion's closed forms are the exact integrals of the narrow-seal pressure (Eq. 9) with curvature
// neglected, so the model's quadrature must reproduce them to the quadrature's accuracy (1e-8 is
// far above the ~1e-12 the rules reach and far below any modelling difference).
TEST(NarrowSeal, HalfSommerfeldLoadsEqualEtsionClosedForms)
{
  for (const Case &c : cases)
  {
    const FilmThickness film = tilted_film(c.eps, c.Ri);
    const OperatingConditions oc = etsion_conditions();
    const FilmLoads l = compute(film, oc, Cavitation::half_sommerfeld, etsion_measure());
    const etsion::TiltLoads e = etsion::loads(film, oc, Cavitation::half_sommerfeld);
    SCOPED_TRACE("eps = " + std::to_string(c.eps) + ", Ri = " + std::to_string(c.Ri));
    EXPECT_NEAR(e.eps, c.eps, 1e-14);
    EXPECT_LT(rel(l.force_z, e.force_z), 1e-8);
    EXPECT_LT(rel(l.moment_restoring, e.moment_restoring), 1e-8);
    EXPECT_LT(rel(l.moment_transverse, e.moment_transverse), 1e-8);
    const double m = std::hypot(e.moment_x, e.moment_y);
    EXPECT_LT(std::abs(l.moment_x - e.moment_x) / m, 1e-8);
    EXPECT_LT(std::abs(l.moment_y - e.moment_y) / m, 1e-8);
    // The positive pressure fills exactly the converging half, theta - psi in (0, pi).
    EXPECT_NEAR(l.cavitated_fraction, 0.5, 1e-12);
    EXPECT_EQ(l.min_pressure, 0.0);
  }
}

// Full film: p_d is antisymmetric about the tilt line (Etsion p. 5), so the hydrodynamic force and
// restoring moment vanish and the transverse moment doubles (Eq. 58).
TEST(NarrowSeal, FullFilmHydrodynamicsIsAntisymmetric)
{
  for (const Case &c : cases)
  {
    const FilmThickness film = tilted_film(c.eps, c.Ri);
    const OperatingConditions oc = etsion_conditions();
    const FilmLoads full = compute(film, oc, Cavitation::none, etsion_measure());
    const FilmLoads half = compute(film, oc, Cavitation::half_sommerfeld, etsion_measure());
    const etsion::TiltLoads e = etsion::loads(film, oc, Cavitation::none);
    SCOPED_TRACE("eps = " + std::to_string(c.eps) + ", Ri = " + std::to_string(c.Ri));
    EXPECT_LT(std::abs(full.force_z), 1e-10 * half.force_z);
    EXPECT_LT(std::abs(full.moment_restoring), 1e-10 * half.moment_restoring);
    EXPECT_LT(rel(full.moment_transverse, e.moment_transverse), 1e-8);
    EXPECT_LT(rel(full.moment_transverse, 2 * half.moment_transverse), 1e-8);
    // Pointwise antisymmetry: p_d(r, psi + a) = -p_d(r, psi - a).
    const NarrowSealModel model(film, oc, Cavitation::none);
    const double r = 0.3 * film.inner_radius + 0.7 * film.outer_radius;
    for (const double a : {0.3, 1.2, 2.9})
      EXPECT_NEAR(model.pressure(r, film.tilt_angle + a), -model.pressure(r, film.tilt_angle - a),
                  1e-12 * std::abs(model.pressure(r, film.tilt_angle + a)));
    EXPECT_EQ(full.cavitated_fraction, 0.0);
  }
}

// The default measure (curvature kept: dA = r dr dtheta, arms r) differs from Etsion's (r -> r_m)
// by relative O((1 - Ri)^2): the first-order terms of r - r_m integrate to zero against the nearly
// symmetric radial profile. Check that rate: halving 1 - Ri divides the differences by ~4.
TEST(NarrowSeal, CurvatureKeptConvergesToEtsionForNarrowDams)
{
  double previous[3] = {0, 0, 0};
  for (const double Ri : {0.9, 0.95, 0.975})
  {
    const FilmThickness film = tilted_film(0.5, Ri);
    const OperatingConditions oc = etsion_conditions();
    const FilmLoads kept = compute(film, oc, Cavitation::half_sommerfeld);
    const FilmLoads neglected = compute(film, oc, Cavitation::half_sommerfeld, etsion_measure());
    const double d[3] = {rel(kept.force_z, neglected.force_z),
                         rel(kept.moment_restoring, neglected.moment_restoring),
                         rel(kept.moment_transverse, neglected.moment_transverse)};
    for (int j = 0; j < 3; ++j)
    {
      EXPECT_GT(d[j], 0.0);
      if (previous[j] > 0)
      {
        EXPECT_NEAR(previous[j] / d[j], 4.0, 0.4);
      }
      previous[j] = d[j];
    }
  }
}

// Hydrostatic coned pressure (Varney & Green Eq. 12): boundary values, and h^3 dp/dr constant
// (d/dr(h^3 dp/dr) = 0) with the value 2 (po - pi) h_i^2 h_o^2 / ((ro - ri)(h_i + h_o)) of the
// narrow coned-seal flow. Checked by Richardson-extrapolated central differences: for p ~ 1/h^2
// their relative truncation error is about 0.75 (b delta / h)^4 (b = dh/dr), ~ 2e-8 here at
// delta = W/2000 where b delta / h reaches 0.013.
TEST(NarrowSeal, HydrostaticPressureSolvesNarrowReynolds)
{
  FilmThickness film;
  film.coning = 2e-3; // strongly coned and tilted: h_o/h_i varies from ~2 to ~20 around the ring
  film.tilt = 0.7 * film.clearance / film.outer_radius;
  film.tilt_angle = 1.1;
  OperatingConditions oc;
  oc.inner_pressure = 1e5;
  oc.outer_pressure = 5e5;
  oc.rotor_speed = 0;
  const NarrowSealModel model(film, oc, Cavitation::none);
  const double ri = film.inner_radius, ro = film.outer_radius, W = ro - ri;
  for (const double t : {0.0, 1.1, 2.0, 4.25})
  {
    EXPECT_DOUBLE_EQ(model.hydrostatic_pressure(ri, t), oc.inner_pressure);
    EXPECT_NEAR(model.hydrostatic_pressure(ro, t), oc.outer_pressure, 1e-9 * oc.outer_pressure);
    EXPECT_EQ(model.hydrodynamic_pressure(ri, t), 0.0);
    const double hi = film.value(ri, t), ho = film.value(ro, t);
    const double flux =
        2 * (oc.outer_pressure - oc.inner_pressure) * hi * hi * ho * ho / (W * (hi + ho));
    for (const double x : {0.1, 0.5, 0.9})
    {
      const double r = ri + x * W;
      auto d = [&](const double delta)
      {
        return (model.hydrostatic_pressure(r + delta, t) -
                model.hydrostatic_pressure(r - delta, t)) /
               (2 * delta);
      };
      const double delta = W / 2000;
      const double dpdr = (4 * d(delta / 2) - d(delta)) / 3;
      const double h = film.value(r, t);
      EXPECT_LT(rel(h * h * h * dpdr, flux), 1e-7);
      EXPECT_LT(rel(model.h3_dp_dr(r, t), flux), 1e-12);
    }
  }
}

// Hydrodynamic pressure: zero on both edges and d/dr(h^3 dp_d/dr) = S(theta) = 12 mu (wbar
// dh/dtheta
// + dh/dt) at r_m, the narrow Reynolds equation (with squeeze, both faces turning, waviness).
// Same Richardson-extrapolated differences as above.
TEST(NarrowSeal, HydrodynamicPressureSolvesNarrowReynolds)
{
  FilmThickness film;
  film.tilt = 0.5 * film.clearance / film.outer_radius;
  film.tilt_angle = -0.4;
  film.wave_amplitude = 0.2e-6;
  film.wave_number = 3;
  film.axial_velocity = 1e-4;
  film.tilt_rate_x = 2e-3;
  film.tilt_rate_y = -1e-3;
  OperatingConditions oc;
  oc.rotor_speed = 500;
  oc.stator_speed = -100;
  const NarrowSealModel model(film, oc, Cavitation::none);
  const double ri = film.inner_radius, ro = film.outer_radius, W = ro - ri;
  const double rm = 0.5 * (ri + ro);
  for (const double t : {0.2, 1.7, 3.3, 5.0})
  {
    const double S =
        12 * oc.viscosity *
        (0.5 * (oc.rotor_speed + oc.stator_speed) * film.d_dtheta(rm, t) + film.d_dt(rm, t));
    EXPECT_LT(rel(model.source(t), S), 1e-14);
    EXPECT_EQ(model.hydrodynamic_pressure(ri, t), 0.0);
    EXPECT_EQ(model.hydrodynamic_pressure(ro, t), 0.0);
    auto flux = [&](const double r, const double delta)
    {
      // h^3 dp_d/dr by central differences
      const double h = film.value(r, t);
      return h * h * h *
             (model.hydrodynamic_pressure(r + delta, t) -
              model.hydrodynamic_pressure(r - delta, t)) /
             (2 * delta);
    };
    const double delta = W / 2000;
    auto flux_rich = [&](const double r) { return (4 * flux(r, delta / 2) - flux(r, delta)) / 3; };
    // d/dr of the flux between r = ri + 0.25 W and ri + 0.75 W (the flux is linear in r exactly)
    const double slope = (flux_rich(ri + 0.75 * W) - flux_rich(ri + 0.25 * W)) / (0.5 * W);
    EXPECT_LT(rel(slope, S), 1e-7);
  }
}

// Leakage: narrow coned seal, no rotation: Q = pi r_m dp h_i^2 h_o^2 / (3 mu W (h_i + h_o))
// inward (the classical narrow coned-seal leakage), and for parallel faces the plane slot flow
// pi r_m dp h^3 / (6 mu W). Inflow = outflow.
TEST(NarrowSeal, HydrostaticLeakageConservedAndClassical)
{
  OperatingConditions oc;
  oc.rotor_speed = 0;
  for (const double beta : {0.0, 1e-3})
  {
    FilmThickness film;
    film.coning = beta;
    const FilmLoads l = compute(film, oc, Cavitation::none);
    const double ri = film.inner_radius, ro = film.outer_radius, W = ro - ri;
    const double rm = 0.5 * (ri + ro), hi = film.value(ri, 0), ho = film.value(ro, 0);
    const double dp = oc.outer_pressure - oc.inner_pressure, mu = oc.viscosity;
    const double Q = beta == 0 ? M_PI * rm * dp * std::pow(film.clearance, 3) / (6 * mu * W)
                               : M_PI * rm * dp * hi * hi * ho * ho / (3 * mu * W * (hi + ho));
    EXPECT_LT(rel(l.leakage_inner, Q), 1e-12); // out of the dam at ri
    EXPECT_LT(rel(-l.leakage_outer, Q), 1e-12);
    EXPECT_LT(std::abs(l.moment_transverse), 1e-12 * std::abs(l.force_z) * ro);
  }
  // With tilt too (no rotation), inflow = outflow, and zero transverse moment: the hydrostatic
  // pressure is symmetric about the tilt line (Etsion p. 17; doc/narrow_seal.md).
  FilmThickness film;
  film.tilt = 0.6 * film.clearance / film.outer_radius;
  film.tilt_angle = 2.0;
  const FilmLoads l = compute(film, oc, Cavitation::none);
  EXPECT_LT(std::abs(l.leakage_inner + l.leakage_outer), 1e-12 * l.leakage_inner);
  EXPECT_LT(std::abs(l.moment_transverse), 1e-12 * std::abs(l.moment_restoring));
}

// Full film: the hydrodynamic flux is odd about the tilt line, so the leakage is entirely
// hydrostatic (Etsion p. 17). With squeeze, inflow - outflow = the rate of film volume growth
// 2 pi r_m (ro - ri) dz/dt (narrow slab).
TEST(NarrowSeal, LeakageWithRotationAndSqueeze)
{
  FilmThickness film;
  film.tilt = 0.6 * film.clearance / film.outer_radius;
  film.tilt_angle = 2.0;
  OperatingConditions oc;
  oc.rotor_speed = 0;
  const FilmLoads still = compute(film, oc, Cavitation::none);
  oc.rotor_speed = 3000;
  const FilmLoads turning = compute(film, oc, Cavitation::none);
  EXPECT_LT(rel(turning.leakage_inner, still.leakage_inner), 1e-12);
  EXPECT_LT(rel(turning.leakage_outer, still.leakage_outer), 1e-12);

  film.axial_velocity = 2e-4;
  const FilmLoads squeezing = compute(film, oc, Cavitation::none);
  const double rm = 0.5 * (film.inner_radius + film.outer_radius);
  const double dVdt = 2 * M_PI * rm * (film.outer_radius - film.inner_radius) * film.axial_velocity;
  EXPECT_LT(rel(-(squeezing.leakage_inner + squeezing.leakage_outer), dVdt), 1e-12);
}

// Parallel-plate squeeze film (infinitely long slot of width W, length 2 pi r_m):
// p = -6 mu hdot (ro - r)(r - ri)/h^3, F = -2 pi r_m mu hdot W^3 / h^3, in both measures (the
// profile is symmetric about r_m).
TEST(NarrowSeal, ParallelSqueezeFilm)
{
  FilmThickness film;
  film.coning = 0;
  film.axial_velocity = -3e-4; // closing
  OperatingConditions oc;
  oc.outer_pressure = 0;
  oc.rotor_speed = 1000; // no effect: dh/dtheta = 0
  const double ri = film.inner_radius, ro = film.outer_radius, W = ro - ri;
  const double rm = 0.5 * (ri + ro), h = film.clearance, mu = oc.viscosity;
  const double zdot = film.axial_velocity;
  const NarrowSealModel model(film, oc, Cavitation::none);
  const double r = ri + 0.3 * W;
  EXPECT_LT(rel(model.pressure(r, 1.0), -6 * mu * zdot * (ro - r) * (r - ri) / (h * h * h)), 1e-12);
  const double F = -2 * M_PI * rm * mu * zdot * W * W * W / (h * h * h);
  for (const Curvature c : {Curvature::kept, Curvature::neglected})
  {
    NarrowSealQuadrature q;
    q.curvature = c;
    EXPECT_LT(rel(model.loads(q).force_z, F), 1e-12);
  }
}

// Couette torque of parallel faces, dam ri..ro, relative speed w1 - w2:
// T = mu (w1 - w2) pi (ro^4 - ri^4) / (2 h). The pressure depends only on the mean speed.
TEST(NarrowSeal, CouetteTorqueAndMeanSpeed)
{
  FilmThickness film;
  film.coning = 0;
  OperatingConditions oc;
  oc.rotor_speed = 700;
  oc.stator_speed = -300;
  const double ri = film.inner_radius, ro = film.outer_radius;
  const FilmLoads l = compute(film, oc, Cavitation::none);
  const double T =
      oc.viscosity * 1000 * M_PI * (std::pow(ro, 4) - std::pow(ri, 4)) / (2 * film.clearance);
  EXPECT_LT(rel(l.friction_torque, T), 1e-12);

  // Tilted film: (w1, w2) = (400, 0) and (200, 200) have the same mean speed, hence the same
  // pressure field; the second has no relative sliding, so only the pressure-gradient torque.
  film.tilt = 0.5 * film.clearance / film.outer_radius;
  oc.rotor_speed = 400;
  oc.stator_speed = 0;
  const FilmLoads a = compute(film, oc, Cavitation::half_sommerfeld);
  oc.rotor_speed = 200;
  oc.stator_speed = 200;
  const FilmLoads b = compute(film, oc, Cavitation::half_sommerfeld);
  EXPECT_LT(rel(a.force_z, b.force_z), 1e-14);
  EXPECT_LT(rel(a.moment_transverse, b.moment_transverse), 1e-14);
  EXPECT_GT(a.friction_torque, b.friction_torque);
}

// The pressure-gradient shear torque int (h/2) dp/dtheta dA is evaluated by parts in theta; check
// it against a brute-force midpoint rule with dp/dtheta by central differences. The midpoint rule
// converges as nr^-2 in r (the theta direction is spectral): Richardson extrapolation of nr = 100
// and 200 leaves ~2e-7 relative.
TEST(NarrowSeal, PressureGradientTorqueByParts)
{
  FilmThickness film;
  film.tilt = 0.6 * film.clearance / film.outer_radius;
  film.tilt_angle = 0.3;
  OperatingConditions oc;
  oc.rotor_speed = 300;
  oc.stator_speed = 300; // no sliding: the torque is the pressure-gradient part alone
  const NarrowSealModel model(film, oc, Cavitation::none);
  const double ri = film.inner_radius, ro = film.outer_radius;
  auto midpoint = [&](const unsigned int nr, const unsigned int nt)
  {
    double T = 0;
    for (unsigned int i = 0; i < nr; ++i)
      for (unsigned int j = 0; j < nt; ++j)
      {
        const double r = ri + (i + 0.5) * (ro - ri) / nr, t = (j + 0.5) * 2 * M_PI / nt;
        const double d = 1e-4;
        const double dpdt = (model.pressure(r, t + d) - model.pressure(r, t - d)) / (2 * d);
        T += 0.5 * film.value(r, t) * dpdt * r * (ro - ri) / nr * 2 * M_PI / nt;
      }
    return T;
  };
  const double T = (4 * midpoint(200, 500) - midpoint(100, 500)) / 3;
  const FilmLoads l = model.loads();
  EXPECT_LT(rel(l.friction_torque, T), 1e-6);
  EXPECT_NE(T, 0.0);
}

// Mixed hydrostatic + hydrodynamic film with a partial cavity (cavities born inside the dam and at
// the low-pressure edge): the piecewise rules converge; doubling both rules changes nothing at
// the 1e-9 level.
TEST(NarrowSeal, PartialCavitationQuadratureConverges)
{
  FilmThickness film;
  film.coning = 0.5e-3;
  film.tilt = 0.8 * film.clearance / film.outer_radius;
  film.tilt_angle = 1.0;
  OperatingConditions oc;
  oc.inner_pressure = 0;
  oc.outer_pressure = 2e5;
  oc.rotor_speed = 3000;
  const NarrowSealModel model(film, oc, Cavitation::half_sommerfeld);
  const std::vector<double> breaks = model.rupture_angles(512);
  ASSERT_GE(breaks.size(), 2u);
  NarrowSealQuadrature fine;
  fine.radial_points = 48;
  fine.angular_points = 1024;
  const FilmLoads a = model.loads(), b = model.loads(fine);
  EXPECT_GT(a.cavitated_fraction, 0.0);
  EXPECT_LT(a.cavitated_fraction, 0.5);
  for (auto [x, y] : {std::pair{a.force_z, b.force_z},
                      {a.moment_restoring, b.moment_restoring},
                      {a.moment_transverse, b.moment_transverse},
                      {a.friction_torque, b.friction_torque},
                      {a.cavitated_fraction, b.cavitated_fraction},
                      {a.leakage_inner, b.leakage_inner}})
    EXPECT_LT(rel(x, y), 1e-9);
  EXPECT_GE(a.min_pressure, 0.0);
  EXPECT_GT(a.max_pressure, oc.outer_pressure);
}

// Half-Sommerfeld with a partial cavity, against a brute-force midpoint rule over the dam of
// max(p, 0): the midpoint rule converges as n^-2 (kinks included), so Richardson extrapolation of
// n = 100 and 200 radial cells (20 n angular) is good to ~5e-7 (measured errors before
// extrapolation 1.7e-4 and 4.2e-5). The cavitated fraction, an indicator integral, converges more
// slowly (n^-1.3): the finer rule must be closer than the coarser and within 3e-4.
TEST(NarrowSeal, PartialCavitationAgainstBruteForce)
{
  FilmThickness film;
  film.coning = 0.5e-3;
  film.tilt = 0.8 * film.clearance / film.outer_radius;
  film.tilt_angle = 1.0;
  OperatingConditions oc;
  oc.inner_pressure = 0;
  oc.outer_pressure = 2e5;
  oc.rotor_speed = 3000;
  const NarrowSealModel model(film, oc, Cavitation::half_sommerfeld);
  const FilmLoads l = model.loads();
  const double ri = film.inner_radius, ro = film.outer_radius, psi = film.tilt_angle;
  struct Sums
  {
    double F = 0, Mr = 0, Mt = 0, cav = 0, pmax = 0;
  };
  auto midpoint = [&](const unsigned int nr)
  {
    const unsigned int nt = 20 * nr;
    Sums s;
    for (unsigned int i = 0; i < nr; ++i)
      for (unsigned int j = 0; j < nt; ++j)
      {
        const double r = ri + (i + 0.5) * (ro - ri) / nr, t = (j + 0.5) * 2 * M_PI / nt;
        const double dA = r * (ro - ri) / nr * 2 * M_PI / nt;
        const double p = model.pressure(r, t);
        s.F += p * dA;
        s.Mr -= p * r * std::cos(t - psi) * dA;
        s.Mt += p * r * std::sin(t - psi) * dA;
        if (model.full_film_pressure(r, t) < 0)
          s.cav += dA / (M_PI * (ro * ro - ri * ri));
        s.pmax = std::max(s.pmax, p);
      }
    return s;
  };
  const Sums a = midpoint(100), b = midpoint(200);
  EXPECT_LT(rel((4 * b.F - a.F) / 3, l.force_z), 2e-6);
  EXPECT_LT(rel((4 * b.Mr - a.Mr) / 3, l.moment_restoring), 2e-6);
  EXPECT_LT(rel((4 * b.Mt - a.Mt) / 3, l.moment_transverse), 2e-6);
  EXPECT_LT(rel(b.cav, l.cavitated_fraction), rel(a.cav, l.cavitated_fraction));
  EXPECT_LT(rel(b.cav, l.cavitated_fraction), 3e-4);
  EXPECT_GT(l.cavitated_fraction, 0.1);
  // the sampled maximum cannot exceed the true one, and comes within the sampling error
  EXPECT_LE(b.pmax, l.max_pressure * (1 + 1e-12));
  EXPECT_LT(rel(b.pmax, l.max_pressure), 1e-4);
  EXPECT_EQ(l.min_pressure, 0.0);
}

// Linearised moments of the narrow-seal loads against Varney & Green's closed forms (Table 1
// seal, curvature neglected as in their narrow-seal integrals), by central differences:
//  - hydrostatic angular stiffness -dM_x/dtilt_x = K_f, Eq. 19 (checks the hydrostatic pressure,
//    the moment definitions and the tilt-vector convention at once);
//  - squeeze damping -dM_x/d(tilt rate x) = 12 pi mu Rm^3 (ro/C0)^2 (1-Ri)^2 G_o ro^4 / C0, which
//    is Eq. 20 with S of Eq. 21 read with (1-Ri)^2; the printed (1-Ri^2) is larger by
//    (1+Ri)/(1-Ri) = 14.4, which no narrow-seal integration gives (doc/narrow_seal.md);
//  - a rotating film: the wedge term of a small tilt gamma equals the squeeze of a tilt rate
//    wbar gamma, so the transverse moment is M_t = wbar D gamma (to O(gamma^2)), the "(omega/2)
//    d11" cross-coupled stiffness.
TEST(NarrowSeal, LinearisedMomentsMatchVarneyGreen)
{
  FilmThickness film; // Varney & Green Table 1 seal
  OperatingConditions oc;
  oc.rotor_speed = 0;
  NarrowSealQuadrature q;
  q.curvature = Curvature::neglected;
  const double ri = film.inner_radius, ro = film.outer_radius, C = film.clearance;
  const double Ri = ri / ro, Rm = 0.5 * (1 + Ri), beta = film.coning * ro / C, w = 1 - Ri;
  const double dp = oc.outer_pressure - oc.inner_pressure, mu = oc.viscosity;

  const double d = 1e-7; // tilt step: gamma ro / C0 = 0.004
  FilmThickness plus = film, minus = film;
  plus.set_tilt_vector(d, 0);
  minus.set_tilt_vector(-d, 0);
  const double K = -(compute(plus, oc, Cavitation::none, q).moment_x -
                     compute(minus, oc, Cavitation::none, q).moment_x) /
                   (2 * d);
  const double Eo = w * Rm / (2 + beta * w);
  const double Kf = M_PI * dp * (beta * Ri - 1) * Eo * Eo * std::pow(ro, 4) / C;
  EXPECT_LT(rel(K, Kf), 1e-5); // central differences: O((gamma ro/C0)^2) ~ 1e-5

  const double rate = 1e-3;
  plus = minus = film;
  plus.tilt_rate_x = rate;
  minus.tilt_rate_x = -rate;
  const double D = -(compute(plus, oc, Cavitation::none, q).moment_x -
                     compute(minus, oc, Cavitation::none, q).moment_x) /
                   (2 * rate);
  const double Go =
      (std::log1p(beta * w) - 2 * beta * w / (2 + beta * w)) / (std::pow(beta, 3) * w * w);
  const double Df =
      12 * M_PI * mu * std::pow(Rm, 3) * (ro / C) * (ro / C) * w * w * Go * std::pow(ro, 4) / C;
  EXPECT_LT(rel(D, Df), 1e-12); // p is linear in the rate: exact

  oc.rotor_speed = 900;
  oc.stator_speed = 100;
  const double gamma = 1e-7;
  FilmThickness tilted = film;
  tilted.tilt = gamma;
  tilted.tilt_angle = 0.4;
  const FilmLoads spinning = compute(tilted, oc, Cavitation::none, q);
  oc.rotor_speed = oc.stator_speed = 0;
  const FilmLoads still = compute(tilted, oc, Cavitation::none, q);
  const double wbar = 500;
  // M_t is odd in gamma, so the linear relation holds to O(gamma^2): ~3e-6 at gamma ro/C0 = 0.004
  EXPECT_LT(rel(spinning.moment_transverse - still.moment_transverse, wbar * Df * gamma), 1e-5);
  EXPECT_LT(std::abs(still.moment_transverse), 1e-9 * std::abs(still.moment_restoring));
}

// Pure hydrodynamics: the cavity boundary is the tilt line, theta = psi and psi + pi.
TEST(NarrowSeal, RuptureAnglesOnTiltLine)
{
  const FilmThickness film = tilted_film(0.5, 0.8, 0.7);
  const NarrowSealModel model(film, etsion_conditions(), Cavitation::half_sommerfeld);
  const std::vector<double> a = model.rupture_angles(256);
  ASSERT_EQ(a.size(), 2u);
  EXPECT_NEAR(a[0], 0.7, 1e-13);
  EXPECT_NEAR(a[1], 0.7 + M_PI, 1e-13);
}

// Small-tilt limits (Eqs. 33, 45, 57, 59) and their next term: the closed forms approach the
// limits as 1 + c eps^2 with c from the Taylor series of the closed forms (doc/narrow_seal.md).
// At eps = 1e-7 they must agree to round-off: the printed forms would lose everything to
// cancellation there (their 1/eps^2 terms amplify it by 1e14).
TEST(EtsionClosedForms, SmallTiltLimits)
{
  for (const double Ri : {0.0, 0.5, 0.8, 0.95})
  {
    const double cF = (11 + 18 * Ri + 11 * Ri * Ri) / 20;
    const double cMx = (13 + 14 * Ri + 13 * Ri * Ri) / 20;
    const double cMz = (33 + 54 * Ri + 33 * Ri * Ri) / 80;
    const double e = 1e-3;
    EXPECT_NEAR((etsion::force(e, Ri) / etsion::force_small_tilt(e, Ri) - 1) / (e * e), cF,
                1e-4 * cF);
    EXPECT_NEAR((etsion::restoring_moment(e, Ri) / etsion::restoring_moment_small_tilt(e, Ri) - 1) /
                    (e * e),
                cMx, 1e-4 * cMx);
    EXPECT_NEAR(
        (etsion::transverse_moment(e, Ri) / etsion::transverse_moment_small_tilt(e, Ri) - 1) /
            (e * e),
        cMz, 1e-4 * cMz);
    EXPECT_NEAR((etsion::transverse_moment_full_film(e, Ri) /
                     etsion::transverse_moment_full_film_small_tilt(e, Ri) -
                 1) /
                    (e * e),
                cMz, 1e-4 * cMz);
    // Round-off: the O(eps) terms still cancel down to the (1 - Ri)^3 of the result.
    const double t = 1e-7, tol = 1e-13 + 64 * DBL_EPSILON / std::pow(1 - Ri, 3);
    EXPECT_NEAR(etsion::force(t, Ri) / etsion::force_small_tilt(t, Ri), 1, tol);
    EXPECT_NEAR(etsion::restoring_moment(t, Ri) / etsion::restoring_moment_small_tilt(t, Ri), 1,
                tol);
    EXPECT_NEAR(etsion::transverse_moment(t, Ri) / etsion::transverse_moment_small_tilt(t, Ri), 1,
                tol);
  }
  // and the narrow-seal model itself at a small tilt
  const FilmThickness film = tilted_film(0.01, 0.9);
  const OperatingConditions oc = etsion_conditions();
  const FilmLoads l = compute(film, oc, Cavitation::half_sommerfeld, etsion_measure());
  const double fs = etsion::force_scale(oc.viscosity, 300, film.clearance, film.outer_radius);
  const double cF = (11 + 18 * 0.9 + 11 * 0.81) / 20;
  EXPECT_NEAR(l.force_z / (fs * etsion::force_small_tilt(0.01, 0.9)), 1 + cF * 1e-4, 1e-7);
}

// Inputs outside the model are refused with a message.
TEST(NarrowSeal, RefusesInvalidInput)
{
  FilmThickness film;
  OperatingConditions oc;
  oc.inner_pressure = 1e4;
  EXPECT_THROW(NarrowSealModel(film, oc, Cavitation::half_sommerfeld, 2e4), std::runtime_error);
  EXPECT_NO_THROW(NarrowSealModel(film, oc, Cavitation::none, 2e4));
  film.coning = 0;
  film.tilt = 1.01 * film.clearance / film.inner_radius;
  EXPECT_THROW(compute(film, oc), std::runtime_error); // touch-down
  EXPECT_THROW(etsion::force(1.2, 0.9), std::invalid_argument);
  EXPECT_THROW(etsion::restoring_moment(0.5, 1.0), std::invalid_argument);
  FilmThickness coned; // default coning 1e-3: not Etsion's flat face
  EXPECT_THROW(etsion::loads(coned, oc, Cavitation::none), std::invalid_argument);
}
