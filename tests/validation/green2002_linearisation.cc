// The nonlinear transient (Green 2002 Eq. 26, StatorTransient) against the linear angular
// dynamics of the same seal (AngularSealDynamics, what `sealfe stability` and `sealfe response`
// use): a small tilt transient decays at the least-damped eigenvalue of the FMS, and the steady
// relative misalignment under rotor runout is the linear forced response. The film's K and D are
// its own linearisation at the equilibrium (central differences of the level-0 loads); the
// numbers compared come from the linear model, never from the transient.
#include <sealfe/closed_form/narrow_seal_film.h>
#include <sealfe/dynamics/angular_dynamics.h>
#include <sealfe/dynamics/equilibrium.h>
#include <sealfe/dynamics/stator_transient.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <boost/math/tools/roots.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <iostream>
#include <limits>

using namespace sealfe;

namespace
{
constexpr double ri = 0.0355, ro = 0.0408, C0 = 1e-6, omega = 1500;

/// Green 2002 Table 1 seal at constant speed and pressures (100 / 500 kPa), fixed coning 1e-4
/// rad (a converging face that runs clear of contact), contact off, full film.
FlexibleStatorSeal constant_seal()
{
  FlexibleStatorSeal seal;
  seal.geometry.inner_radius = ri;
  seal.geometry.outer_radius = ro;
  seal.geometry.clearance = C0;
  seal.geometry.coning = 1e-4;
  seal.conditions.viscosity = 1.2e-3;
  seal.thermal.model = ThermalConing::Model::none;
  seal.ramps.speed = Ramp{omega, omega, 0, 1e300, 1e300};
  seal.ramps.outer_pressure = Ramp{5e5, 5e5, 0, 1e300, 1e300};
  seal.ramps.inner_pressure = Ramp{1e5, 1e5, 0, 1e300, 1e300};
  seal.contact = FaceContact(AsperityContact(AsperityContact::Model::none, {}), ri, ro, 8, 96);
  return seal;
}

NarrowSealFilm full_film(const FlexibleStatorSeal &seal)
{
  NarrowSealQuadrature q;
  q.radial_points = 8;
  q.angular_points = 64;
  return NarrowSealFilm(seal.geometry, seal.conditions, q, Cavitation::none);
}

/// The film state of constant_seal()'s conditions (aligned, at C0 until an offset is set).
FilmState constant_state(const FlexibleStatorSeal &seal)
{
  FilmState s;
  s.rotor_speed = omega;
  s.inner_pressure = 1e5;
  s.outer_pressure = 5e5;
  s.coning = seal.geometry.coning;
  return s;
}

/// The linear model of the transient's seal (`sealfe stability` / `sealfe response`): the FMS,
/// on the flexible rotor if the seal has one, the film linearised at the axial equilibrium
/// (aligned faces). The runout is the rotor's support misalignment chi_s (a rigid ring: its own
/// tilt, turning with it).
AngularSealDynamics linear_fms(const FlexibleStatorSeal &seal, const FilmForceModel &film)
{
  FilmState s = constant_state(seal);
  s.axial_offset = solve_equilibrium(seal, film, s).axial_offset;
  const FilmCoefficients k = central_difference_coefficients(
      film, s, s.apply(seal.geometry).minimum().value, seal.geometry.outer_radius);
  RingProperties stator, rotor;
  stator.transverse_inertia = seal.stator.transverse_inertia;
  stator.support_stiffness = seal.stator.angular_stiffness;
  stator.support_damping = seal.stator.angular_damping;
  if (seal.rotor.flexible)
    rotor = seal.rotor.angular;
  rotor.support_misalignment = seal.runout.tilt;
  return AngularSealDynamics(seal.rotor.flexible ? SealConfiguration::fms_flexible_rotor
                                                 : SealConfiguration::fms,
                             rotor, stator, [k](double, double) { return k; });
}

/// Transient settings that start on the axial equilibrium of constant_seal()'s conditions.
TransientSettings steady_settings(const FlexibleStatorSeal &seal, const FilmForceModel &film)
{
  TransientSettings settings;
  settings.initial_axial_offset =
      solve_equilibrium(seal, film, constant_state(seal)).axial_offset / C0;
  return settings;
}

/// The largest real part of the linear model's eigenvalues at the test's speed (1/s).
double slowest_root(const AngularSealDynamics &linear)
{
  double slowest = -std::numeric_limits<double>::infinity();
  for (const auto &l : linear.eigenvalues(omega, 0))
    slowest = std::max(slowest, l.real());
  return slowest;
}

std::complex<double> stator_tilt(const TransientSample &x)
{
  return {x.stator_tilt_x, x.stator_tilt_y};
}
} // namespace

// A small initial tilt (no runout, no misalignment: the equilibrium is aligned, a = 0) decays as
// the FMS's modes; once the fast one (-D/I ~ -4e8 1/s) has gone, a(t) = A exp(lambda t) with
// lambda the least-damped eigenvalue (complex: Im > 0 forward whirl, the tilt vector x + i y
// turning with the shaft). Re(lambda) from the amplitude over a long span, Im(lambda) from the
// phase over a tenth of a whirl period.
TEST(Green2002Linearisation, TiltTransientDecaysAtTheLeastDampedEigenvalue)
{
  FlexibleStatorSeal seal = constant_seal();
  seal.runout.tilt = 0;
  const auto film = full_film(seal);
  const auto eig = linear_fms(seal, film).eigenvalues(omega, 0);
  const std::complex<double> lambda =
      *std::max_element(eig.begin(), eig.end(), [](auto a, auto b) { return a.real() < b.real(); });
  ASSERT_LT(lambda.real(), 0);

  TransientSettings settings = steady_settings(seal, film);
  settings.initial_tilt = 1e-7; // 4e-9 m at ro against a 0.8 um film: linear
  settings.frame = "inertial";
  settings.order = 5; // accurate phase and amplitude of a lightly damped whirl at small steps
  settings.relative_tolerance = 1e-10;
  settings.absolute_tolerance = 1e-10;
  const double dt = 0.1 * 2 * M_PI / std::abs(lambda.imag());
  const double t0 = 50 / std::abs(lambda);  // many fast-mode decay times
  const double span = 0.1 / -lambda.real(); // the amplitude falls by 10 %
  settings.output_interval = dt;
  settings.end_time = t0 + span + dt;
  const StatorTransient transient(seal, film, settings);
  const auto result = transient.run();
  ASSERT_TRUE(result.complete) << result.stop_reason;
  const auto &x = result.samples;
  const std::size_t i1 = std::lround(t0 / dt), i2 = x.size() - 1;
  ASSERT_LT(i1 + 1, i2);
  const std::complex<double> a1 = stator_tilt(x[i1]), a2 = stator_tilt(x[i2]);
  const double decay = std::log(std::abs(a2) / std::abs(a1)) / (x[i2].time - x[i1].time);
  const double whirl = std::arg(stator_tilt(x[i1 + 1]) / a1) / (x[i1 + 1].time - x[i1].time);
  std::cout << "transient: decay " << decay << " 1/s, whirl " << whirl
            << " rad/s; linear FMS: " << lambda << std::endl;
  EXPECT_NEAR(decay / lambda.real(), 1, 0.01) << decay << " vs " << lambda;
  // the real 4 x 4 system has lambda and its conjugate; the complex tilt x + i y carries the
  // forward one (the film's cross-coupled stiffness, omega/2 times its damping, drives the tilt
  // round with the shaft)
  EXPECT_NEAR(whirl / std::abs(lambda.imag()), 1, 0.01) << whirl << " vs " << lambda;
}

// Rotor runout gamma_r whirling at the shaft speed, no contact: the steady relative misalignment
// (constant in the frame turning with the shaft) equals the linear forced response.
TEST(Green2002Linearisation, RunoutTrackingEqualsTheLinearForcedResponse)
{
  FlexibleStatorSeal seal = constant_seal();
  seal.runout.tilt = 1e-6; // 4e-8 m at ro against a 0.8 um film: linear
  const auto film = full_film(seal);
  const AngularSealDynamics linear = linear_fms(seal, film);
  const double expected =
      ForcedResponse::max_magnitude(linear.forced_response(omega, 0).relative_tilt);
  const double slowest = slowest_root(linear);

  TransientSettings settings = steady_settings(seal, film);
  settings.relative_tolerance = 1e-9;
  settings.absolute_tolerance = 1e-9;
  // the stator starts at rest against a whirling rotor: the relative tilt rate excites the fast
  // mode (~ -4e8 1/s), whose first steps are far below 1e-12 s
  settings.minimum_step = 1e-18;
  settings.end_time = 12 / -slowest; // the start-up transient has decayed by e^-12
  settings.output_interval = settings.end_time;
  const StatorTransient transient(seal, film, settings);
  const auto result = transient.run();
  ASSERT_TRUE(result.complete) << result.stop_reason;
  std::cout << "relative tilt: transient " << result.samples.back().relative_tilt << " rad, linear "
            << expected << " rad" << std::endl;
  EXPECT_NEAR(result.samples.back().relative_tilt / expected, 1, 0.01)
      << "transient " << result.samples.back().relative_tilt << " rad, linear " << expected
      << " rad";
}

// The flexible rotor of Varney & Green 2017 (Eq. 5-6: K_r, D_r, D_omega_r, gyroscopic I_pr omega,
// dynamic misalignment chi, static misalignment chi_s) under the same stator, no contact: the
// steady relative misalignment equals the linear forced response of the FMS on a flexible rotor
// (AngularSealDynamics, Appendix B's solution), and so does the rotor's own tilt.
TEST(VarneyGreen2017Transient, FlexibleRotorTrackingEqualsTheLinearForcedResponse)
{
  FlexibleStatorSeal seal = constant_seal();
  seal.runout.tilt = 1e-6; // chi_s
  seal.rotor.flexible = true;
  // Varney & Green 2017 Table 2's rotor (RotorRing's defaults: I_tr 0.2, I_pr 0.1 kg m^2, K_r
  // 5e5 N m/rad, D_r 20, D_wr 1 N m s/rad); (I_tr - I_pr) chi omega^2 ~ K_r chi_s at 1500 rad/s
  seal.rotor.angular.dynamic_misalignment = 2e-6;
  const auto film = full_film(seal);

  const AngularSealDynamics linear = linear_fms(seal, film);
  const ForcedResponse response = linear.forced_response(omega, 0);
  const double expected_relative = ForcedResponse::max_magnitude(response.relative_tilt);
  const double expected_rotor = ForcedResponse::max_magnitude(response.rotor_tilt);
  const double slowest = slowest_root(linear);
  ASSERT_LT(slowest, 0);

  TransientSettings settings = steady_settings(seal, film);
  settings.relative_tolerance = 1e-9;
  settings.absolute_tolerance = 1e-9;
  settings.minimum_step = 1e-18; // the fast mode is excited at t = 0 (see above)
  settings.end_time = 12 / -slowest;
  settings.output_interval = settings.end_time;
  const StatorTransient transient(seal, film, settings);
  const auto result = transient.run();
  ASSERT_TRUE(result.complete) << result.stop_reason;
  const TransientSample &end = result.samples.back();
  const double rotor_tilt = std::hypot(end.rotor_tilt_x, end.rotor_tilt_y);
  std::cout << "relative tilt: transient " << end.relative_tilt << " rad, linear "
            << expected_relative << " rad; rotor tilt: transient " << rotor_tilt << " rad, linear "
            << expected_rotor << " rad; slowest root " << slowest << " 1/s" << std::endl;
  EXPECT_NEAR(end.relative_tilt / expected_relative, 1, 0.01);
  EXPECT_NEAR(rotor_tilt / expected_rotor, 1, 0.01);
}

// The operating point with tilts (what `sealfe equilibrium` solves): a small stator misalignment g
// fixed in space, no runout, no contact. Linear statics: the film's tilt stiffness K_f (2 x 2 with
// its cross-coupled part, central differences of the loads at the aligned equilibrium) and the
// support K_s share the misalignment: (K_f + K_s I) a = K_s g.
TEST(Green2002Equilibrium, TiltedBalanceIsTheLinearStaticsOfTheMisalignment)
{
  FlexibleStatorSeal seal = constant_seal();
  seal.runout.tilt = 0;
  // a support as stiff as the film (K_f ~ 3e8 N m/rad here): the two share the misalignment
  seal.stator.angular_stiffness = 3e8;
  seal.stator.initial_misalignment = 1e-7;
  seal.stator.misalignment_angle = 0.3;
  const auto film = full_film(seal);
  const TransientSettings settings = steady_settings(seal, film);
  const StatorTransient transient(seal, film, settings);
  const TransientState y = transient.steady_state(0, transient.initial_state());

  FilmState s = constant_state(seal);
  s.axial_offset = settings.initial_axial_offset * C0;
  const FilmCoefficients k = central_difference_coefficients(
      film, s, s.apply(seal.geometry).minimum().value, seal.geometry.outer_radius);
  const double Ks = seal.stator.angular_stiffness;
  const auto g = tilt_vector(seal.stator.initial_misalignment, seal.stator.misalignment_angle);
  const double a11 = k.stiffness[1][1] + Ks, a12 = k.stiffness[1][2], a21 = k.stiffness[2][1],
               a22 = k.stiffness[2][2] + Ks;
  const double det = a11 * a22 - a12 * a21;
  const double ax = Ks * (a22 * g[0] - a12 * g[1]) / det, ay = Ks * (a11 * g[1] - a21 * g[0]) / det;
  std::cout << "tilt: steady state (" << y[2] << ", " << y[3] << "), linear statics (" << ax << ", "
            << ay << ") rad" << std::endl;
  const double size = std::hypot(ax, ay);
  // the relative tilt a ro ~ 2e-9 m against a 0.27 um film: nonlinearity < 1e-2 of the tilt
  EXPECT_NEAR(y[2], ax, 1e-2 * size);
  EXPECT_NEAR(y[3], ay, 1e-2 * size);
}

// A transient at these constant conditions settles on that tilted operating point (to the
// integrator's tolerance), started aligned.
TEST(Green2002Equilibrium, TransientSettlesOnTheTiltedBalance)
{
  FlexibleStatorSeal seal = constant_seal();
  seal.runout.tilt = 0;
  seal.stator.initial_misalignment = 1e-6;
  const auto film = full_film(seal);
  TransientSettings settings = steady_settings(seal, film);
  const StatorTransient steady(seal, film, settings);
  const TransientState y = steady.steady_state(0, steady.initial_state());

  const double slowest = slowest_root(linear_fms(seal, film));
  settings.relative_tolerance = 1e-9;
  settings.absolute_tolerance = 1e-9;
  settings.end_time = 20 / -slowest; // the start has decayed by e^-20
  settings.output_interval = settings.end_time;
  const StatorTransient transient(seal, film, settings);
  const auto result = transient.run();
  ASSERT_TRUE(result.complete) << result.stop_reason;
  const TransientSample &end = result.samples.back();
  const double size = std::hypot(y[2], y[3]);
  std::cout << "relative tilt: transient (" << end.stator_tilt_x << ", " << end.stator_tilt_y
            << "), steady state (" << y[2] << ", " << y[3] << ") rad" << std::endl;
  EXPECT_NEAR(end.stator_tilt_x, y[2], 1e-5 * size); // rotor aligned: a_s = a
  EXPECT_NEAR(end.stator_tilt_y, y[3], 1e-5 * size);
  EXPECT_NEAR(end.axial_offset, y[0], 1e-6 * C0);
}

// Varney & Green 2017 Eq. 7, statics: with the rotor axially flexible (K_zr) the film pushes it
// back by F_f / K_zr and the stator follows, so the gap offset g solves
//   F_f(g) - F_cls - K_sz (g - F_f(g) / K_zr) = 0
// (no contact) — solved here by toms748 on the film alone, against the steady state.
TEST(VarneyGreen2017Transient, AxiallyFlexibleRotorStatics)
{
  FlexibleStatorSeal seal = constant_seal();
  seal.runout.tilt = 0;
  seal.rotor.flexible = true;
  seal.rotor.axial_stiffness = 1e9; // N/m: the rotor gives 0.5 um under the ~500 N film force
  seal.rotor.mass = 2;
  const auto film = full_film(seal);
  FilmState s = constant_state(seal);
  const double F_cls = seal.closing.value(ri, ro, 1e5, 5e5);
  const double K_sz = seal.stator.axial_stiffness, K_zr = seal.rotor.axial_stiffness;
  auto balance = [&](const double g)
  {
    FilmState at = s;
    at.axial_offset = g;
    const double F = film.loads(at).force_z;
    return F - F_cls - K_sz * (g - F / K_zr);
  };
  boost::uintmax_t iterations = 200;
  const auto root = boost::math::tools::toms748_solve(
      balance, -0.95 * C0, 5 * C0, boost::math::tools::eps_tolerance<double>(50), iterations);
  const double g = 0.5 * (root.first + root.second);
  FilmState at = s;
  at.axial_offset = g;
  const double u_zr = -film.loads(at).force_z / K_zr;

  TransientSettings settings = steady_settings(seal, film);
  const StatorTransient transient(seal, film, settings);
  const TransientState y = transient.steady_state(0, transient.initial_state());
  std::cout << "gap offset: steady state " << y[0] - y[12] << " m, independent " << g
            << " m; rotor " << y[12] << " m vs " << u_zr << " m" << std::endl;
  EXPECT_NEAR(y[0] - y[12], g, 1e-9 * C0);
  EXPECT_NEAR(y[12], u_zr, 1e-9 * std::abs(u_zr));
  EXPECT_NEAR(y[0], g + u_zr, 1e-9 * C0);
}

// Varney & Green 2017 Eq. 7, dynamics: a small axial offset of the stator decays at the slowest
// root of the two-mass system stator - film - rotor, linearised at the balance:
//   m_s Z'' = -K_f (Z - u) - D_f (Z' - u') - K_sz Z - D_sz Z'
//   m_r u'' =  K_f (Z - u) + D_f (Z' - u') - K_zr u - D_zr u'
// (K_f, D_f: the film's central differences at the balance; eigenvalues by LAPACK).
TEST(VarneyGreen2017Transient, AxiallyFlexibleRotorDecaysAtTheLinearisedRoot)
{
  FlexibleStatorSeal seal = constant_seal();
  seal.runout.tilt = 0;
  seal.rotor.flexible = true;
  seal.rotor.axial_stiffness = 1e9;
  seal.rotor.axial_damping = 1e3;
  seal.rotor.mass = 2;
  const auto film = full_film(seal);
  TransientSettings settings = steady_settings(seal, film);
  const StatorTransient balance(seal, film, settings);
  const TransientState y_eq = balance.steady_state(0, balance.initial_state());
  FilmState s = constant_state(seal);
  s.axial_offset = y_eq[0] - y_eq[12];
  const FilmCoefficients k = central_difference_coefficients(
      film, s, s.apply(seal.geometry).minimum().value, seal.geometry.outer_radius);
  const double Kf = k.stiffness[0][0], Df = k.damping[0][0], ms = seal.stator.mass,
               mr = seal.rotor.mass;
  const double Ks = seal.stator.axial_stiffness, Ds = seal.stator.axial_damping,
               Kr = seal.rotor.axial_stiffness, Dr = seal.rotor.axial_damping;
  // x = (Z, u, Z', u')
  dealii::LAPACKFullMatrix<double> A(4, 4);
  A(0, 2) = A(1, 3) = 1;
  A(2, 0) = -(Kf + Ks) / ms;
  A(2, 1) = Kf / ms;
  A(2, 2) = -(Df + Ds) / ms;
  A(2, 3) = Df / ms;
  A(3, 0) = Kf / mr;
  A(3, 1) = -(Kf + Kr) / mr;
  A(3, 2) = Df / mr;
  A(3, 3) = -(Df + Dr) / mr;
  A.compute_eigenvalues();
  double slow = -std::numeric_limits<double>::infinity();
  for (unsigned int i = 0; i < 4; ++i)
  {
    const auto l = A.eigenvalue(i);
    if (l.real() > slow)
    {
      slow = l.real();
      ASSERT_NEAR(l.imag(), 0, 1e-9 * std::abs(l)) << "the slowest root is real here";
    }
  }
  ASSERT_LT(slow, 0);

  const double t1 = 0.2 / -slow, t2 = 1.2 / -slow;
  // the initial axial offset is the gap's; the rotor starts deflected by the film there
  settings.initial_axial_offset = (y_eq[0] - y_eq[12]) / C0 + 1e-3;
  settings.end_time = t2;
  settings.output_interval = t1;
  settings.relative_tolerance = 1e-10;
  settings.absolute_tolerance = 1e-10;
  const StatorTransient transient(seal, film, settings);
  const auto result = transient.run();
  ASSERT_TRUE(result.complete) << result.stop_reason;
  // Z - Z_eq decays at the slow root once the fast ones have gone
  const double z1 = result.samples[1].axial_offset - y_eq[0];
  const double z2 = result.samples.back().axial_offset - y_eq[0];
  const double rate = std::log(z2 / z1) / (result.samples.back().time - result.samples[1].time);
  std::cout << "axial decay with the flexible rotor: transient " << rate << " 1/s, linear " << slow
            << " 1/s" << std::endl;
  EXPECT_NEAR(rate / slow, 1, 0.01);
}
