// Green 2002: the operating point of a flexibly mounted stator (closing force Eq. 22 against film
// + GW/CEB contact), the ramps of Eq. 17, the thermal coning of Eq. 11 and bad input. Numbers
// from the paper's Table 1 or from closed forms solved independently here.
#include <sealfe/closed_form/narrow_seal_film.h>
#include <sealfe/dynamics/equilibrium.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/tools/roots.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace sealfe;

namespace
{
/// The Green 2002 Table 1 seal with the closed-form (level 0) film.
struct Case
{
  FlexibleStatorSeal seal;
  Case(bool contact = true)
  {
    seal.geometry.inner_radius = 0.0355;
    seal.geometry.outer_radius = 0.0408;
    seal.geometry.clearance = 1e-6;
    seal.conditions.viscosity = 1.2e-3;
    seal.contact = FaceContact(
        AsperityContact(contact ? AsperityContact::Model::gw_ceb : AsperityContact::Model::none,
                        AsperityContactParameters()),
        0.0355, 0.0408, 8, 96);
  }
  NarrowSealFilm film() const
  {
    NarrowSealQuadrature q;
    q.radial_points = 8;
    q.angular_points = 64;
    return NarrowSealFilm(seal.geometry, seal.conditions, q, Cavitation::half_sommerfeld);
  }
  static FilmState at(double omega, double pi_, double po)
  {
    FilmState s;
    s.rotor_speed = omega;
    s.inner_pressure = pi_;
    s.outer_pressure = po;
    return s;
  }
};
} // namespace

// Table 1 / "Parametric investigation": at rest, with no pressure drop, the 20 N springs press the
// faces into easy contact at h_min/sigma = 3.5 (Z(0) = -0.65 C0).
TEST(Green2002Equilibrium, RestIsEasyContactAtThreePointFiveSigma)
{
  Case c;
  const auto film = c.film();
  const SealEquilibrium eq = solve_equilibrium(c.seal, film, Case::at(0, 1e5, 1e5));
  const double h_over_sigma = eq.contact.min_film / 1e-7;
  EXPECT_NEAR(h_over_sigma, 3.5, 0.05);
  // the contact carries the springs (+ the small axial support force -K_sz Z)
  EXPECT_NEAR(eq.contact.force, 20 + 5e5 * eq.axial_offset, 1e-6);
}

// The axial balance with a fixed coning and no contact against the narrow-seal hydrostatic force
// p = pi + (po - pi)(1/h_i^2 - 1/h^2)/(1/h_i^2 - 1/h_o^2) (Reynolds with constant radial flow,
// h linear in r) integrated by Gauss-Kronrod and solved by toms748 here.
TEST(Green2002Equilibrium, ClearanceMatchesIndependentHydrostaticBalance)
{
  Case c(false);
  c.seal.thermal.model = ThermalConing::Model::none;
  c.seal.geometry.coning = 1e-4;
  const double pi_ = 1e5, po = 5e5, ri = 0.0355, ro = 0.0408, C0 = 1e-6, beta = 1e-4;
  const auto film = c.film();
  const SealEquilibrium eq = solve_equilibrium(c.seal, film, Case::at(1500, pi_, po));

  const double closing = M_PI * (ro * ro - ri * ri) * (0.75 * po + 0.25 * pi_) + 20;
  auto balance = [&](const double C)
  {
    const double hi = C, ho = C + beta * (ro - ri);
    auto p = [&](const double r)
    {
      const double h = C + beta * (r - ri);
      return pi_ + (po - pi_) * (1 / (hi * hi) - 1 / (h * h)) / (1 / (hi * hi) - 1 / (ho * ho));
    };
    const double F = 2 * M_PI *
                     boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
                         [&](double r) { return p(r) * r; }, ri, ro, 10, 1e-14);
    return F - 5e5 * (C - C0) - closing;
  };
  boost::uintmax_t it = 100;
  const auto root = boost::math::tools::toms748_solve(
      balance, 1e-8, 1e-4, boost::math::tools::eps_tolerance<double>(50), it);
  const double C = 0.5 * (root.first + root.second);
  EXPECT_NEAR(C0 + eq.axial_offset, C, 1e-6 * C);
  EXPECT_NEAR(eq.closing_force, closing, 1e-9 * closing);
}

// Eq. 11 with d/dt = 0: the equilibrium coning equals beta_ref (h_ref/h)(omega/omega_ref)^2 with
// h the dissipation-mean film Int r^2 dA / Int r^2/h dA of the equilibrium film (computed here).
TEST(Green2002Equilibrium, QuasiStaticConingFollowsEquationEleven)
{
  Case c;
  const auto film = c.film();
  const SealEquilibrium eq = solve_equilibrium(c.seal, film, Case::at(1500, 1e5, 5e5));
  const double ri = 0.0355, ro = 0.0408, C = 1e-6 + eq.axial_offset, b = eq.coning;
  using GK = boost::math::quadrature::gauss_kronrod<double, 31>;
  const double num = GK::integrate([&](double r) { return r * r * r; }, ri, ro, 10, 1e-14);
  const double den =
      GK::integrate([&](double r) { return r * r * r / (C + b * (r - ri)); }, ri, ro, 10, 1e-14);
  const double h = num / den;
  EXPECT_NEAR(eq.coning, 5e-6 * (0.3e-6 / h) * 9, 1e-6 * eq.coning);
}

TEST(Green2002Equilibrium, UnbalanceableClosingForceIsRefused)
{
  Case c;
  const auto film = c.film();
  c.seal.closing.spring_force = 1e6;
  try
  {
    solve_equilibrium(c.seal, film, Case::at(0, 1e5, 1e5));
    FAIL();
  }
  catch (std::runtime_error &e)
  {
    EXPECT_NE(std::string(e.what()).find("below any film"), std::string::npos);
  }
  c.seal.closing.spring_force = 0;
  c.seal.closing.balance_ratio = 0.1;
  c.seal.thermal.model = ThermalConing::Model::none;
  c.seal.geometry.coning = 0;
  c.seal.stator.axial_stiffness = 0; // otherwise the support spring holds the ring
  try
  {
    solve_equilibrium(c.seal, film, Case::at(0, 1e5, 5e5));
    FAIL();
  }
  catch (std::runtime_error &e)
  {
    EXPECT_NE(std::string(e.what()).find("open without bound"), std::string::npos);
  }
}

// Eq. 17: the trapezoid and its integral (the shaft angle) in closed form.
TEST(Green2002Ramps, TrapezoidAndShaftAngle)
{
  const Ramp speed{0, 1500, 3, 6, 9};
  EXPECT_DOUBLE_EQ(speed.value(1.5), 750);
  EXPECT_DOUBLE_EQ(speed.value(4), 1500);
  EXPECT_DOUBLE_EQ(speed.value(7.5), 750);
  EXPECT_DOUBLE_EQ(speed.value(10), 0);
  // area of the trapezoid: 1500 (3/2 + 3 + 3/2)
  EXPECT_NEAR(speed.integral(9), 9000, 1e-9);
  EXPECT_NEAR(speed.integral(20), 9000, 1e-9);
  EXPECT_NEAR(speed.integral(1), 1500 / 6.0, 1e-9);
  EXPECT_THROW((Ramp{0, 1, 3, 2, 9}.validate("Speed")), std::runtime_error);
}

TEST(Green2002Input, BadValuesAreRefused)
{
  ThermalConing t;
  t.time_constant = -1;
  EXPECT_THROW(t.validate(), std::runtime_error);
  ClosingForce f;
  f.balance_ratio = 1.2;
  EXPECT_THROW(f.validate(), std::runtime_error);
  f.balance_ratio = 0;
  EXPECT_THROW(f.validate(), std::runtime_error);
  StatorRing s;
  s.mass = 0;
  EXPECT_THROW(s.validate(), std::runtime_error);
}

// Eq. 13: at constant h and omega, tau beta' + beta = beta_inf gives beta = beta_inf (1 -
// e^-t/tau); the rate of Eq. 11 integrated exactly (exponential integrator) over the paper's tau =
// 2 s.
TEST(Green2002ThermalConing, RateIsTheFirstOrderLag)
{
  ThermalConing t;
  const double h = 0.3e-6, omega = 500;
  EXPECT_DOUBLE_EQ(t.quasi_static(h, omega), 5e-6);
  EXPECT_DOUBLE_EQ(t.rate(0, h, omega), 5e-6 / 2);
  EXPECT_DOUBLE_EQ(t.quasi_static(2 * h, 2 * omega), 10e-6);
}
