// The Campbell diagram and stability map of `sealfe stability` against theory: an FMS seal
// (flexible stator, no support damping) loses stability when the film's precession at the mean
// speed omega/2 reaches the stator's natural frequency, omega_cr = +-2 sqrt((k11 + k_s)/I)
// (Green & Etsion; Wileman & Green Eq. 17 with one ring), the neutral mode whirling at omega/2.
#include "../sealfe_cli.h"

#include <sealfe/closed_form/green_etsion.h>
#include <sealfe/dynamics/whirl_modes.h>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <map>
#include <vector>

namespace
{
using namespace sealfe::testing;

// Wileman & Green's reference seal (prm/stability.prm), stator flexible, rotor rigid
constexpr double ri = 0.032, ro = 0.04, C0 = 1e-5, beta_star = 3.13e-3, mu = 5e-4, dp = 1e6;
constexpr double I = 8e-4, ks = 400;
constexpr double from = -20000, to = 20000;
constexpr unsigned int points = 401; // grid spacing 100 rad/s

std::string prm(const std::string &stability_extra)
{
  return R"(
subsection Geometry
  set Inner radius = 0.032
  set Outer radius = 0.04
  set Clearance    = 1e-5
  set Coning       = 3.13e-3
end
subsection Operating conditions
  set Inner pressure = 0
  set Outer pressure = 1e6
  set Viscosity      = 5e-4
  set Rotor speed    = 1000
  set Stator speed   = 0
end
subsection Seal dynamics
  set Configuration = FMS
  set Film model    = closed form
  subsection Stator ring
    set Transverse inertia = 8e-4
    set Polar inertia      = 1.6e-3
    set Support stiffness  = 400
    set Support damping    = 0
    set Rotating damping   = 0
  end
end
subsection Stability
  set Swept speed  = Rotor speed
  set Speed from   = -20000
  set Speed to     = 20000
  set Speed points = 401
  set Plot         = false
)" + stability_extra +
         "end\n";
}

double critical_speed(const double support_stiffness)
{
  const sealfe::GreenEtsionCoefficients film(ri, ro, C0, beta_star, mu, dp);
  return 2 * std::sqrt((film.angular_stiffness() + support_stiffness) / I);
}
} // namespace

// The least damped mode's damping ratio changes sign where theory puts the threshold, once on
// each side, and there the mode whirls at the mean speed omega/2: forward (+) for omega > 0,
// backward (-) for omega < 0.
TEST(CampbellDiagram, DampingRatioChangesSignAtTheFmsThreshold)
{
  const fs::path dir = fresh_directory("sealfe_campbell_fms");
  const CliResult run = run_sealfe(dir, "stability", prm(""));
  ASSERT_EQ(run.status, 0) << run.err;
  auto m = read_csv(read_file(dir / "out" / "stability_campbell.csv"));
  const double w_cr = critical_speed(ks), h = (to - from) / (points - 1);

  // per swept speed: the least damped mode (smallest damping ratio) and its whirl
  std::vector<double> speed, zeta, whirl;
  for (std::size_t i = 0; i < m["swept_speed"].size(); ++i)
  {
    if (speed.empty() || speed.back() != m["swept_speed"][i])
    {
      speed.push_back(m["swept_speed"][i]);
      zeta.push_back(m["damping_ratio"][i]);
      whirl.push_back(m["whirl_frequency"][i]);
    }
    else if (m["damping_ratio"][i] < zeta.back())
    {
      zeta.back() = m["damping_ratio"][i];
      whirl.back() = m["whirl_frequency"][i];
    }
  }
  ASSERT_EQ(speed.size(), points);
  // one stator ring: two modes (forward and backward) at every speed
  EXPECT_EQ(m["swept_speed"].size(), 2 * points);

  std::vector<double> crossings, whirl_at_crossing;
  for (std::size_t i = 0; i + 1 < speed.size(); ++i)
    if ((zeta[i] < 0) != (zeta[i + 1] < 0))
    {
      const double t = zeta[i] / (zeta[i] - zeta[i + 1]);
      crossings.push_back(speed[i] + t * (speed[i + 1] - speed[i]));
      whirl_at_crossing.push_back(whirl[i] + t * (whirl[i + 1] - whirl[i]));
    }
  ASSERT_EQ(crossings.size(), 2u);
  // linear interpolation between grid speeds: within one spacing of the threshold
  EXPECT_NEAR(crossings[0], -w_cr, h);
  EXPECT_NEAR(crossings[1], w_cr, h);
  // the neutral mode whirls at the mean speed (omega1 + omega2)/2 = omega/2, direction included
  EXPECT_NEAR(whirl_at_crossing[0], -w_cr / 2, h);
  EXPECT_NEAR(whirl_at_crossing[1], w_cr / 2, h);
  // unstable outside, stable inside
  EXPECT_LT(zeta.front(), 0);
  EXPECT_LT(zeta.back(), 0);
  EXPECT_GT(zeta[points / 2], 0);

  // the bisected stable range the summary reports is the same threshold
  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  EXPECT_NEAR(summary["stable_range"][0].get<double>(), -w_cr, 1e-8 * w_cr);
  EXPECT_NEAR(summary["stable_range"][1].get<double>(), w_cr, 1e-8 * w_cr);
}

// Stability map over the stator's support stiffness: the threshold curve is
// +-2 sqrt((k11 + k_s)/I) at every k_s, the grid's verdict is |omega| < omega_cr(k_s), and at the
// prm's k_s the curve gives the single-parameter stable range.
TEST(StabilityMap, ThresholdCurveFollowsTheFmsClosedForm)
{
  const fs::path dir = fresh_directory("sealfe_stability_map_fms");
  const CliResult run = run_sealfe(dir, "stability",
                                   prm("  set Second parameter = Stator ring support stiffness\n"
                                       "  set Second parameter values = 0 : 4000 : 11\n"));
  ASSERT_EQ(run.status, 0) << run.err;
  auto sweep = read_csv(read_file(dir / "out" / "stability_sweep.csv"));
  ASSERT_EQ(sweep["stator_ring_support_stiffness"].size(), 11u);
  for (std::size_t i = 0; i < 11; ++i)
  {
    const double k = sweep["stator_ring_support_stiffness"][i], w_cr = critical_speed(k);
    EXPECT_NEAR(k, 400.0 * i, 1e-9);
    EXPECT_NEAR(sweep["stable_low"][i], -w_cr, 1e-8 * w_cr) << "k_s = " << k;
    EXPECT_NEAR(sweep["stable_high"][i], w_cr, 1e-8 * w_cr) << "k_s = " << k;
    EXPECT_EQ(sweep["stable_interval_count"][i], 1);
  }

  auto map = read_csv(read_file(dir / "out" / "stability_map.csv"));
  ASSERT_EQ(map["swept_speed"].size(), 11u * points);
  unsigned int checked = 0;
  for (std::size_t i = 0; i < map["swept_speed"].size(); ++i)
  {
    const double w = map["swept_speed"][i],
                 w_cr = critical_speed(map["stator_ring_support_stiffness"][i]);
    if (std::abs(std::abs(w) - w_cr) < 1e-6 * w_cr)
      continue; // on the threshold itself the verdict is round-off
    ++checked;
    EXPECT_EQ(map["stable"][i], std::abs(w) < w_cr ? 1.0 : 0.0) << "omega = " << w;
    // growth rate and verdict agree
    EXPECT_EQ(map["growth_rate"][i] < 0, map["stable"][i] == 1.0) << "omega = " << w;
  }
  EXPECT_GT(checked, 11u * points - 30);

  // the map at the prm's k_s = 400 N m/rad (value 1) and the single-parameter stable range
  const auto summary = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  EXPECT_DOUBLE_EQ(summary["stable_range"][0].get<double>(), sweep["stable_low"][1]);
  EXPECT_DOUBLE_EQ(summary["stable_range"][1].get<double>(), sweep["stable_high"][1]);
}

// The whirl direction from the eigenvector, against the gyroscopic splitting of one spinning ring
// (FMR) on a film of stiffness only: z = t_x + i t_y obeys I_t z'' - i I_p omega z' + k z = 0, so
// the modes whirl at psi = (I_p omega +- sqrt(I_p^2 omega^2 + 4 I_t k)) / (2 I_t), undamped: the
// + root forward (> 0), the - root backward (< 0), the one whirling with the spin stiffened.
TEST(WhirlModes, GyroscopicSplittingOfOneSpinningRing)
{
  sealfe::RingProperties rotor;
  rotor.transverse_inertia = 1e-3;
  rotor.polar_inertia = 1.5e-3;
  rotor.support_stiffness = 500;
  const double k_film = 1e4, k = k_film + rotor.support_stiffness;
  const sealfe::AngularSealDynamics d(sealfe::SealConfiguration::fmr, rotor,
                                      sealfe::RingProperties(),
                                      [k_film](double wr, double ws)
                                      {
                                        sealfe::FilmCoefficients f;
                                        f.stiffness[1][1] = f.stiffness[2][2] = k_film;
                                        f.rotor_speed = wr;
                                        f.stator_speed = ws;
                                        return f;
                                      });
  for (const double omega : {-3000.0, 0.0, 500.0, 4000.0})
  {
    const double a = rotor.polar_inertia * omega, I = rotor.transverse_inertia;
    const double forward = (a + std::sqrt(a * a + 4 * I * k)) / (2 * I),
                 backward = (a - std::sqrt(a * a + 4 * I * k)) / (2 * I);
    const auto modes = sealfe::whirl_modes(d, omega, 0.0);
    ASSERT_EQ(modes.size(), 2u) << "omega = " << omega;
    double found_forward = 0, found_backward = 0;
    for (const auto &m : modes)
    {
      EXPECT_NEAR(m.damping_ratio, 0, 1e-12) << "omega = " << omega;
      EXPECT_EQ(m.stator_share, 0) << "omega = " << omega; // the rotor ring only
      if (omega == 0)
      {
        // no spin: both directions at one frequency, the eigenvector any mix
        EXPECT_NEAR(std::abs(m.whirl_frequency), forward, 1e-9 * forward);
      }
      (m.whirl_frequency > 0 ? found_forward : found_backward) = m.whirl_frequency;
    }
    if (omega == 0)
      continue;
    EXPECT_NEAR(found_forward, forward, 1e-9 * forward) << "omega = " << omega;
    EXPECT_NEAR(found_backward, backward, 1e-9 * std::abs(backward)) << "omega = " << omega;
  }
}
