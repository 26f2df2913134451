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

/// The FMS of the linear model: the stator ring of the transient, the film linearised at the
/// axial equilibrium (aligned faces).
AngularSealDynamics linear_fms(const FlexibleStatorSeal &seal, const FilmForceModel &film,
                               double runout)
{
  FilmState s;
  s.rotor_speed = omega;
  s.inner_pressure = 1e5;
  s.outer_pressure = 5e5;
  s.coning = seal.geometry.coning;
  s.axial_offset = solve_equilibrium(seal, film, s).axial_offset;
  const FilmCoefficients k = central_difference_coefficients(
      film, s, s.apply(seal.geometry).minimum().value, seal.geometry.outer_radius);
  RingProperties stator, rotor;
  stator.transverse_inertia = seal.stator.transverse_inertia;
  stator.support_stiffness = seal.stator.angular_stiffness;
  stator.support_damping = seal.stator.angular_damping;
  rotor.support_misalignment = runout; // a rigid ring: its own tilt, turning with it (run-out)
  return AngularSealDynamics(SealConfiguration::fms, rotor, stator,
                             [k](double, double) { return k; });
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
  const auto eig = linear_fms(seal, film, 0).eigenvalues(omega, 0);
  const std::complex<double> lambda =
      *std::max_element(eig.begin(), eig.end(), [](auto a, auto b) { return a.real() < b.real(); });
  ASSERT_LT(lambda.real(), 0);

  FilmState s;
  s.rotor_speed = omega;
  s.inner_pressure = 1e5;
  s.outer_pressure = 5e5;
  s.coning = seal.geometry.coning;
  TransientSettings settings;
  settings.initial_axial_offset = solve_equilibrium(seal, film, s).axial_offset / C0;
  settings.initial_tilt = 1e-7; // 4e-9 m at ro against a 0.8 um film: linear
  settings.frame = "inertial";
  settings.order = 5; // accurate phase and amplitude of a lightly damped whirl at small steps
  settings.relative_tolerance = 1e-10;
  settings.absolute_tolerance = 1e-10;
  // the fast mode (~ -4e8 1/s) is excited at t = 0: its first steps are far below 1e-12 s
  settings.minimum_step = 1e-18;
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
  const AngularSealDynamics linear = linear_fms(seal, film, seal.runout.tilt);
  const double expected =
      ForcedResponse::max_magnitude(linear.forced_response(omega, 0).relative_tilt);
  const auto eig = linear.eigenvalues(omega, 0);
  double slowest = -std::numeric_limits<double>::infinity();
  for (const auto &l : eig)
    slowest = std::max(slowest, l.real());

  FilmState s;
  s.rotor_speed = omega;
  s.inner_pressure = 1e5;
  s.outer_pressure = 5e5;
  s.coning = seal.geometry.coning;
  TransientSettings settings;
  settings.initial_axial_offset = solve_equilibrium(seal, film, s).axial_offset / C0;
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
