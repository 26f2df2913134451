// Green 2002 Eq. 26 in time (StatorTransient, level-0 film): settling on the axial balance, the
// decay of a small axial offset at the root of m s^2 + D s + K = 0, and the thermal coning's
// first-order lag (Eq. 11-13). Numbers from the equilibrium solver, the film's linearisation and
// closed forms, never from the transient itself.
#include <sealfe/closed_form/narrow_seal_film.h>
#include <sealfe/dynamics/equilibrium.h>
#include <sealfe/dynamics/stator_transient.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace sealfe;

namespace
{
constexpr double ri = 0.0355, ro = 0.0408, C0 = 1e-6;

/// The Green 2002 Table 1 seal at constant operating conditions (steps at t = 0, held), no runout.
FlexibleStatorSeal constant_seal(double omega, double pi_, double po, bool contact)
{
  FlexibleStatorSeal seal;
  seal.geometry.inner_radius = ri;
  seal.geometry.outer_radius = ro;
  seal.geometry.clearance = C0;
  seal.conditions.viscosity = 1.2e-3;
  seal.runout.tilt = 0;
  seal.ramps.speed = Ramp{omega, omega, 0, 1e300, 1e300};
  seal.ramps.outer_pressure = Ramp{po, po, 0, 1e300, 1e300};
  seal.ramps.inner_pressure = Ramp{pi_, pi_, 0, 1e300, 1e300};
  seal.contact = FaceContact(
      AsperityContact(contact ? AsperityContact::Model::gw_ceb : AsperityContact::Model::none,
                      AsperityContactParameters()),
      ri, ro, 8, 96);
  return seal;
}

NarrowSealFilm narrow_film(const FlexibleStatorSeal &seal)
{
  NarrowSealQuadrature q;
  q.radial_points = 8;
  q.angular_points = 64;
  return NarrowSealFilm(seal.geometry, seal.conditions, q, Cavitation::half_sommerfeld);
}

FilmState steady_state(const FlexibleStatorSeal &seal)
{
  FilmState s;
  s.rotor_speed = seal.ramps.speed.steady;
  s.inner_pressure = seal.ramps.inner_pressure.steady;
  s.outer_pressure = seal.ramps.outer_pressure.steady;
  return s;
}

/// A film that carries exactly the closing force of Eq. 22 at any state (test double): the
/// stator stays where it starts, so the film of the thermal coning is constant.
class ClosingForceFilm : public FilmForceModel
{
public:
  explicit ClosingForceFilm(const FlexibleStatorSeal &seal) : seal(seal) {}
  FilmLevel level() const override { return FilmLevel::closed_form; }
  std::string description() const override { return "carries the closing force"; }
  FilmLoads loads(const FilmState &s) const override
  {
    FilmLoads l;
    l.force_z = seal.closing.value(ri, ro, s.inner_pressure, s.outer_pressure);
    return l;
  }
  FilmCoefficients coefficients(const FilmState &) const override { return {}; }

private:
  const FlexibleStatorSeal &seal;
};
} // namespace

// At the reference steady point (1500 rad/s, 100/500 kPa, B = 0.75, GW/CEB contact, a short
// thermal time constant) the transient started off the balance and with flat faces settles on the
// clearance and coning of solve_equilibrium.
TEST(Green2002Transient, SettlesOnTheEquilibrium)
{
  FlexibleStatorSeal seal = constant_seal(1500, 1e5, 5e5, true);
  seal.thermal.time_constant = 0.05;
  const auto film = narrow_film(seal);
  const SealEquilibrium eq = solve_equilibrium(seal, film, steady_state(seal));

  TransientSettings settings;
  settings.end_time = 8; // the axial creep has a time constant of ~0.4 s here
  settings.output_interval = 8;
  settings.relative_tolerance = 1e-9;
  settings.absolute_tolerance = 1e-9;
  settings.order = 5; // no tilt is excited (no runout): a smooth, non-oscillating problem
  settings.initial_axial_offset = eq.axial_offset / C0 + 0.05;
  const StatorTransient transient(seal, film, settings);
  const auto result = transient.run();
  ASSERT_TRUE(result.complete) << result.stop_reason;
  const TransientSample &end = result.samples.back();
  EXPECT_NEAR(end.axial_offset / C0, eq.axial_offset / C0, 1e-6);
  EXPECT_NEAR(end.axial_velocity, 0, 1e-9);
  // the coning is settled on Eq. 11 at the transient's own film (beta ~ 1/h: a 1e-6 C0 offset
  // in Z alone moves it by ~4e-6 relative, so it is checked against Eq. 11, not eq.coning)
  const double beta_eq11 = seal.thermal.reference_coning *
                           (seal.thermal.reference_film / end.heating_film) *
                           std::pow(1500 / seal.thermal.reference_speed, 2);
  EXPECT_NEAR(end.coning / beta_eq11, 1, 1e-6);
  EXPECT_NEAR(end.coning / eq.coning, 1, 1e-6 * C0 / end.min_film + 1e-6);
}

// A small axial offset from the balance (no contact, fixed coning) decays at the slow root of
// m s^2 + (D_zz + D_sz) s + (K_zz + K_sz) = 0, with K_zz and D_zz the film's linearisation at the
// equilibrium (overdamped: D^2 >> 4 m K, so there is no frequency; both roots are real).
TEST(Green2002Transient, AxialOffsetDecaysAtTheLinearisedRoot)
{
  FlexibleStatorSeal seal = constant_seal(1500, 1e5, 5e5, false);
  seal.thermal.model = ThermalConing::Model::none;
  seal.geometry.coning = 1e-4;
  const auto film = narrow_film(seal);
  FilmState s = steady_state(seal);
  const SealEquilibrium eq = solve_equilibrium(seal, film, s);
  s.axial_offset = eq.axial_offset;
  s.coning = seal.geometry.coning;
  // the linearisation at the equilibrium state itself (not the closed forms' at C0)
  const FilmCoefficients k = central_difference_coefficients(
      film, s, s.apply(seal.geometry).minimum().value, seal.geometry.outer_radius);
  const double m = seal.stator.mass;
  const double D = k.damping[0][0] + seal.stator.axial_damping;
  const double K = k.stiffness[0][0] + seal.stator.axial_stiffness;
  ASSERT_GT(D * D, 4 * m * K);
  const double slow = (-D + std::sqrt(D * D - 4 * m * K)) / (2 * m);

  TransientSettings settings;
  const double t1 = 0.2 / -slow, t2 = 1.2 / -slow;
  settings.end_time = t2;
  settings.output_interval = t1;
  settings.relative_tolerance = 1e-10;
  settings.absolute_tolerance = 1e-10;
  const double offset = 1e-3;
  settings.initial_axial_offset = eq.axial_offset / C0 + offset;
  const StatorTransient transient(seal, film, settings);
  const auto result = transient.run();
  ASSERT_TRUE(result.complete) << result.stop_reason;
  const double z1 = result.samples[1].axial_offset - eq.axial_offset;
  const double z2 = result.samples.back().axial_offset - eq.axial_offset;
  const double rate = std::log(z2 / z1) / (result.samples.back().time - result.samples[1].time);
  EXPECT_NEAR(rate / slow, 1, 0.01);
}

// Eq. 11-13: at constant film (the stator held by a film that carries the closing force, coning
// driven by the centerline clearance C0) and constant speed, beta = beta_ss (1 - exp(-t/tau)) with
// beta_ss = beta_ref (h_ref/C0)(omega/omega_ref)^2 (Table 1: 5e-6 rad, 0.3 um, 500 rad/s).
TEST(Green2002Transient, ConingFollowsTheFirstOrderLag)
{
  FlexibleStatorSeal seal = constant_seal(1500, 1e5, 1e5, false);
  seal.thermal.film = ThermalConing::Film::centerline;
  const ClosingForceFilm film(seal);
  TransientSettings settings;
  settings.end_time = 4;
  settings.output_interval = 0.5;
  settings.relative_tolerance = 1e-9;
  settings.absolute_tolerance = 1e-9;
  settings.initial_axial_offset = 0;
  settings.order = 5; // a smooth exponential: BDF up to order 5
  const StatorTransient transient(seal, film, settings);
  const auto result = transient.run();
  ASSERT_TRUE(result.complete) << result.stop_reason;
  const double tau = 2, beta_ss = 5e-6 * (0.3e-6 / C0) * std::pow(1500.0 / 500.0, 2);
  ASSERT_EQ(result.samples.size(), 9u);
  for (const TransientSample &x : result.samples)
    EXPECT_NEAR(x.coning / beta_ss, 1 - std::exp(-x.time / tau), 1e-7) << "t = " << x.time;
}

// The limits of Eq. 11: tau -> 0 gives the quasi-static coning beta_ss at once (tau = 0 is solved
// algebraically; a tau of 1 us relaxes within the first output interval), tau -> infinity keeps
// beta(0).
TEST(Green2002Transient, ConingLimitsOfTheTimeConstant)
{
  const double beta_ss = 5e-6 * (0.3e-6 / C0) * std::pow(1500.0 / 500.0, 2);
  for (const double tau : {0.0, 1e-6, 1e9})
  {
    FlexibleStatorSeal seal = constant_seal(1500, 1e5, 1e5, false);
    seal.thermal.film = ThermalConing::Film::centerline;
    seal.thermal.time_constant = tau;
    seal.thermal.initial_coning = 2e-5;
    const ClosingForceFilm film(seal);
    TransientSettings settings;
    settings.end_time = 1;
    settings.output_interval = 0.25;
    settings.relative_tolerance = 1e-9;
    settings.absolute_tolerance = 1e-9;
    settings.initial_axial_offset = 0;
    const auto result = StatorTransient(seal, film, settings).run();
    ASSERT_TRUE(result.complete) << result.stop_reason;
    for (const TransientSample &x : result.samples)
    {
      if (x.time == 0 && tau > 0)
        continue; // beta(0) is the initial coning
      const double expected = tau > 1 ? 2e-5 : beta_ss;
      EXPECT_NEAR(x.coning / expected, 1, 1e-6) << "tau = " << tau << " s, t = " << x.time;
    }
  }
}

// Lift-off is located by IDA's root finding, not by the output rows: on the Green 2002 reference
// start-up with beta_ref = 1.23e-4 rad (the faces lift off, doc/transient.md) and rows 1 s apart,
// the reported lift-off time t* is where the contact force equals the contact threshold times the
// closing force (the definition), checked by a second run that ends at t*.
TEST(Green2002Transient, LiftOffIsLocatedByRootFinding)
{
  FlexibleStatorSeal seal;
  seal.geometry.inner_radius = ri;
  seal.geometry.outer_radius = ro;
  seal.geometry.clearance = C0;
  seal.conditions.viscosity = 1.2e-3;
  seal.thermal.reference_coning = 1.23e-4;
  seal.contact = FaceContact(
      AsperityContact(AsperityContact::Model::gw_ceb, AsperityContactParameters()), ri, ro, 8, 96);
  const auto film = narrow_film(seal);
  TransientSettings settings;
  settings.end_time = 3;
  settings.output_interval = 1;
  settings.relative_tolerance = 1e-7;
  settings.absolute_tolerance = 1e-7;
  const auto first = StatorTransient(seal, film, settings).run();
  ASSERT_TRUE(first.complete) << first.stop_reason;
  ASSERT_FALSE(first.contact_events.empty()) << "no lift-off in the start-up";
  const auto lift_off = first.contact_events.front();
  ASSERT_TRUE(lift_off.lift_off);
  EXPECT_GT(lift_off.time, 0);
  EXPECT_LT(lift_off.time, 3);
  EXPECT_NEAR(lift_off.rotor_speed, 1500 * lift_off.time / 3, 1e-9); // on the ramp of Eq. 17

  settings.end_time = lift_off.time;
  settings.output_interval = lift_off.time;
  const auto second = StatorTransient(seal, film, settings).run();
  ASSERT_TRUE(second.complete) << second.stop_reason;
  const TransientSample &at = second.samples.back();
  // the integration error of the contact force, relative to F_cls, is of the order of the
  // tolerance times the contact's sensitivity to h (CEB: ~ (h/sigma) per unit relative change)
  EXPECT_NEAR(at.contact_force / at.closing_force, settings.contact_threshold, 1e-4)
      << "t* = " << lift_off.time << " s";
  std::cout << "lift-off at " << lift_off.time << " s, " << lift_off.rotor_speed
            << " rad/s; contact/F_cls there " << at.contact_force / at.closing_force << std::endl;
}
