// (tests/long: ~30 s CPU — two 25-s and one 10-s held-speed transients.)
// Green 2002, separation of a contacting seal (Fig. 6 conditions: no pressure drop, no thermal
// coning, rotor runout gamma_r = 1e-3 rad): the quasi-static physics that sets the separation
// speed, derived here from the narrow-seal model and the angular equation of motion, not from the
// transient's output.
//
// While the stator rides on the rotor, its tilt a_s follows the whirling rotor tilt
// a_r = gamma_r e^{i omega t}; the moment that forces it to is
//   M = I a_r'' + D_s a_r' + K_s a_r,   |M| = gamma_r |K_s - I omega^2 + i D_s omega|,
// and it is the film that carries it (the film's angular stiffness at h ~ 3.5 sigma, ~1e8 N m/rad,
// is ~1e3 times the contact's, so the relative tilt stays < 1e-8 rad and the contact's share is
// < 0.2 %). At a relative tilt that small the film is uniform (h = h0) and the narrow-seal
// pressure of a synchronously whirling tilt is p = p_a + a q(r) cos(phi), q = (ro - r)(r - ri)
// (the source S(theta) read at r_m, doc/narrow_seal.md); half-Sommerfeld clips it at 0. With the
// ambient p_a = 100 kPa the clipped field carries a net opening force F_net(|M|) > 0 once
// a q_max > p_a. The contact then carries what is left of the spring preset:
//   A_n p_c(h0) + F_net(|M|) = F_spring - K_sz (C0 - h0)          (Eq. 22 with p_o = p_i, Eq. 26)
// and the faces separate when F_net exceeds F_spring - K_sz (C0 - h0): the separation speed
// grows with the angular support K_s through |M| only. The per-radius integrals over the cavity
// are closed form; r is integrated adaptively (Gauss-Kronrod).
#include <sealfe/closed_form/narrow_seal_film.h>
#include <sealfe/dynamics/stator_transient.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <complex>

using namespace sealfe;

namespace
{
constexpr double ri = 0.0355, ro = 0.0408, C0 = 1e-6, ambient = 1e5, runout = 1e-3;
constexpr double ramp_rate = 1e4; // rad/s^2, Green 2002 Fig. 6

/// The Table 1 seal with p_i = p_o = 100 kPa, no coning, GW/CEB contact, speed ramped at
/// 1e4 rad/s^2 to `omega` and held there.
FlexibleStatorSeal fig6_seal(const double omega, const double angular_stiffness)
{
  FlexibleStatorSeal seal;
  seal.geometry.inner_radius = ri;
  seal.geometry.outer_radius = ro;
  seal.geometry.clearance = C0;
  seal.geometry.coning = 0;
  seal.conditions.viscosity = 1.2e-3;
  seal.thermal.model = ThermalConing::Model::none;
  seal.runout.tilt = runout;
  seal.stator.angular_stiffness = angular_stiffness;
  seal.ramps.speed = Ramp{0, omega, omega / ramp_rate, 1e300, 1e300};
  seal.ramps.outer_pressure = Ramp{ambient, ambient, 0, 1e300, 1e300};
  seal.ramps.inner_pressure = Ramp{ambient, ambient, 0, 1e300, 1e300};
  seal.contact = FaceContact(
      AsperityContact(AsperityContact::Model::gw_ceb, AsperityContactParameters()), ri, ro, 8, 96);
  return seal;
}

struct WhirlLoads
{
  double moment; ///< N m, magnitude
  double force;  ///< N, net opening force above p_a A
};

/// p = p_a + a (ro - r)(r - ri) cos(phi) clipped at 0, integrated over the dam (dA = r dr dphi,
/// arms r). Per radius, with c = p_a / (a q) < 1 the cavity is |phi - pi| < t = acos(c):
///   net force  Int (p_clipped - p_a) dphi = 2 (a q sin t - p_a t)
///   moment     Int p_clipped cos(phi) dphi = pi a q - [a q (t + sin t cos t) - 2 p_a sin t].
WhirlLoads clipped_whirl_loads(const double a)
{
  using Quad = boost::math::quadrature::gauss_kronrod<double, 31>;
  const auto q = [](const double r) { return (ro - r) * (r - ri); };
  const auto moment = [&](const double r)
  {
    const double aq = a * q(r);
    double m = M_PI * aq;
    if (aq > ambient)
    {
      const double t = std::acos(ambient / aq);
      m -= aq * (t + std::sin(t) * std::cos(t)) - 2 * ambient * std::sin(t);
    }
    return m * r * r;
  };
  const auto force = [&](const double r)
  {
    const double aq = a * q(r);
    if (aq <= ambient)
      return 0.0;
    const double t = std::acos(ambient / aq);
    return 2 * (aq * std::sin(t) - ambient * t) * r;
  };
  // split at the radii where the cavity opens (a q(r) = p_a), where the integrands have kinks
  const double W = ro - ri, disc = W * W / 4 - ambient / std::max(a, 1e-300);
  if (disc <= 0)
    return {Quad::integrate(moment, ri, ro, 15, 1e-13), 0};
  const double r1 = 0.5 * (ri + ro) - std::sqrt(disc), r2 = 0.5 * (ri + ro) + std::sqrt(disc);
  WhirlLoads l{0, 0};
  for (const auto &[lo, hi] : {std::pair{ri, r1}, std::pair{r1, r2}, std::pair{r2, ro}})
  {
    l.moment += Quad::integrate(moment, lo, hi, 15, 1e-13);
    l.force += Quad::integrate(force, lo, hi, 15, 1e-13);
  }
  return l;
}

/// F_net of the film that carries the moment magnitude M (the amplitude a by toms748).
WhirlLoads film_carrying(const double M)
{
  boost::math::tools::eps_tolerance<double> tol(50);
  std::uintmax_t it = 200;
  double top = 1e10;
  while (clipped_whirl_loads(top).moment < M)
    top *= 4;
  const auto [lo, hi] = boost::math::tools::toms748_solve(
      [&](const double a) { return clipped_whirl_loads(a).moment - M; }, 0.0, top, -M,
      clipped_whirl_loads(top).moment - M, tol, it);
  return clipped_whirl_loads(0.5 * (lo + hi));
}

/// |K_s - I omega^2 + i D_s omega| gamma_r: the moment that keeps the stator on the rotor's tilt.
double tracking_moment(const FlexibleStatorSeal &seal, const double omega)
{
  const StatorRing &s = seal.stator;
  return runout *
         std::abs(std::complex<double>(s.angular_stiffness - s.transverse_inertia * omega * omega,
                                       s.angular_damping * omega));
}

/// The speed (above the stator's natural frequency) at which the film opens with `force`.
double speed_for_opening_force(const FlexibleStatorSeal &seal, const double force)
{
  boost::math::tools::eps_tolerance<double> tol(40);
  std::uintmax_t it = 200;
  const double w0 = std::sqrt(seal.stator.angular_stiffness / seal.stator.transverse_inertia) + 1;
  const auto f = [&](const double w)
  { return film_carrying(tracking_moment(seal, w)).force - force; };
  const auto [lo, hi] = boost::math::tools::toms748_solve(f, w0, 2e4, f(w0), f(2e4), tol, it);
  return 0.5 * (lo + hi);
}

/// The film h0 at which the contact carries the rest of the spring preset:
/// A_n p_c(h0) + F_net = F_spring - K_sz (C0 - h0).
double contact_film(const FlexibleStatorSeal &seal, const double opening_force)
{
  const AsperityContact contact(AsperityContact::Model::gw_ceb, AsperityContactParameters());
  const double An = seal.face_area();
  const auto f = [&](const double h)
  {
    return An * contact.contact_pressure(h).value + opening_force - seal.closing.spring_force +
           seal.stator.axial_stiffness * (C0 - h);
  };
  boost::math::tools::eps_tolerance<double> tol(50);
  std::uintmax_t it = 200;
  const auto [lo, hi] = boost::math::tools::toms748_solve(f, 1e-8, 1e-6, f(1e-8), f(1e-6), tol, it);
  return 0.5 * (lo + hi);
}

NarrowSealFilm narrow_film(const FlexibleStatorSeal &seal)
{
  NarrowSealQuadrature q;
  q.radial_points = 8;
  q.angular_points = 64;
  return NarrowSealFilm(seal.geometry, seal.conditions, q, Cavitation::half_sommerfeld);
}

StatorTransient::Result run(const FlexibleStatorSeal &seal, const NarrowSealFilm &film,
                            const double end_time)
{
  TransientSettings settings;
  settings.end_time = end_time;
  settings.output_interval = 0.5;
  settings.start_at_rest_equilibrium = true;
  return StatorTransient(seal, film, settings).run();
}
} // namespace

// Below separation (the film opening with 3/4 of the spring preset) the stator rides on the
// contact and the film: held at that speed, the contact force settles on the balance above. The
// support moves the separation speed (K_s = 50 and 500 N m/rad: 1.97e3 and 2.10e3 rad/s here)
// only through |M|. Tolerance 0.1 N: the contact's share of the moment (< 0.2 % of |M|, i.e.
// < 0.05 N of F_net), the film's O(gamma ro / h0 ~ 1e-3) departure from uniform, and what is left
// of the axial creep after 25 s (time constant ~2 s).
TEST(Green2002Separation, ContactCarriesWhatTheWhirlingFilmLeaves)
{
  for (const double Ks : {50.0, 500.0})
  {
    FlexibleStatorSeal seal = fig6_seal(0, Ks);
    const double F_open = 0.75 * seal.closing.spring_force;
    const double omega = speed_for_opening_force(seal, F_open);
    seal = fig6_seal(omega, Ks);
    const WhirlLoads expected = film_carrying(tracking_moment(seal, omega));
    const double h0 = contact_film(seal, expected.force);
    const double contact_expected =
        seal.closing.spring_force - seal.stator.axial_stiffness * (C0 - h0) - expected.force;

    const auto film = narrow_film(seal);
    const auto result = run(seal, film, 25);
    ASSERT_TRUE(result.complete) << result.stop_reason;
    const TransientSample &end = result.samples.back();
    const double film_net = end.film_force - ambient * seal.face_area();
    SCOPED_TRACE("K_s = " + std::to_string(Ks) + ", omega = " + std::to_string(omega));
    EXPECT_NEAR(std::hypot(end.film_moment_x, end.film_moment_y), expected.moment,
                2e-3 * expected.moment);
    EXPECT_NEAR(film_net, expected.force, 0.1);
    EXPECT_NEAR(end.contact_force, contact_expected, 0.1);
    EXPECT_NEAR(end.min_film, h0, 0.01 * h0);
  }
}

// Above separation (the film opening with 1.25 x the spring preset, more than the contact can
// be loaded with at any h0 <= C0) the faces lift off: the contact force falls below 1 % of its
// rest value.
TEST(Green2002Separation, FaceLiftsOffAboveTheSeparationSpeed)
{
  FlexibleStatorSeal seal = fig6_seal(0, 50);
  const double omega = speed_for_opening_force(seal, 1.25 * seal.closing.spring_force);
  seal = fig6_seal(omega, 50);
  const auto film = narrow_film(seal);
  const auto result = run(seal, film, 10);
  const double rest = result.samples.front().contact_force;
  bool lifted = false;
  for (const TransientSample &x : result.samples)
    lifted = lifted || x.contact_force < 0.01 * rest;
  EXPECT_TRUE(lifted) << "omega = " << omega << ", last contact force "
                      << result.samples.back().contact_force << " N of " << rest << " N at rest; "
                      << result.stop_reason;
}
