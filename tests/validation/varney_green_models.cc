// FMS seal on a flexible rotor (Varney & Green, Varney & Green (2017)): the analytic forced
// response (Appendix B) against a direct solve and a time integration (SUNDIALS ARKode) of Eq.
// 24-27, the rotor critical speed, and the paper's qualitative findings.
#include <sealfe/closed_form/green_etsion.h>
#include <sealfe/dynamics/seal_dynamics.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

using namespace sealfe;

namespace
{
/// Varney & Green (2017) Tables 1 and 2; delta = I_tr / I_pr, ratio = I_tr / I_ts (I_tr held at 0.2
/// kg m^2).
AngularSealDynamics varney_green(const double delta, const double ratio = 0.2 / 1.7e-3,
                                 const double chi = 0.5e-3, const double chi_s = 0,
                                 const double gamma_si = 0, const double Kr = 5e5)
{
  RingProperties rotor, stator;
  rotor.transverse_inertia = 0.2;
  rotor.polar_inertia = 0.2 / delta;
  rotor.support_stiffness = Kr;
  rotor.support_damping = 20;
  rotor.rotating_damping = 1;
  rotor.dynamic_misalignment = chi;
  rotor.support_misalignment = chi_s;
  stator.transverse_inertia = 0.2 / ratio;
  stator.support_stiffness = 363.9;
  stator.support_damping = 0.22;
  stator.support_misalignment = gamma_si;
  const GreenEtsionCoefficients film(0.0355, 0.0408, 1e-6, 1e-3, 1.2e-3, 4e5);
  return AngularSealDynamics(SealConfiguration::fms_flexible_rotor, rotor, stator,
                             [film](double w1, double w2) { return film.coefficients(w1, w2); });
}
} // namespace

namespace
{
using cplx = std::complex<double>;

/// Synchronous relative tilt gamma* of the response at speed w (Eq. 8: |g_s - g_r|).
double relative_tilt(const AngularSealDynamics &d, const double w)
{
  return ForcedResponse::max_magnitude(d.forced_response(w, 0).relative_tilt);
}
double rotor_tilt(const AngularSealDynamics &d, const double w)
{
  return ForcedResponse::max_magnitude(d.forced_response(w, 0).rotor_tilt);
}

/// The speed in [a, b] at which f peaks: scan, then golden section around the best sample.
template <typename F>
double peak_speed(F f, double a, double b, const unsigned int n = 400)
{
  double best = a, fbest = -1;
  for (unsigned int i = 0; i <= n; ++i)
  {
    const double w = a + (b - a) * i / n;
    if (f(w) > fbest)
    {
      fbest = f(w);
      best = w;
    }
  }
  double lo = best - (b - a) / n, hi = best + (b - a) / n;
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  for (int it = 0; it < 60; ++it)
  {
    const double c = hi - g * (hi - lo), e = lo + g * (hi - lo);
    (f(c) > f(e) ? hi : lo) = (f(c) > f(e) ? e : c);
  }
  return 0.5 * (lo + hi);
}

/// The rotor alone (Eq. 26-27 without the film): (K_r - (I_tr - I_pr) w^2 + i w (D_r - D_wr)) G
/// = (I_tr - I_pr) chi w^2.
double rotor_alone_tilt(const double delta, const double w, const double chi = 0.5e-3,
                        const double Kr = 5e5)
{
  const double a = 0.2 - 0.2 / delta;
  return std::abs(a * chi * w * w / cplx(Kr - a * w * w, w * (20 - 1)));
}
} // namespace

// Appendix B (B3-B5, typos fixed as documented in seal_dynamics.h) equals the direct complex
// solve of the real equations (24)-(27), in magnitude and phase, for thick and thin rotors, light
// and heavy stators, dynamic and static rotor misalignment.
TEST(VarneyGreen, AppendixBEqualsDirectSolve)
{
  for (const double delta : {0.5, 2.0})
    for (const double ratio : {2.0, 50.0, 117.6})
      for (const double w : {50.0, 700.0, 1500.0, 2236.0, 4000.0})
      {
        const auto d = varney_green(delta, ratio, 0.5e-3, 0.2e-3);
        const auto vg = d.varney_green_synchronous_response(w);
        const auto r = d.forced_response(w, 0);
        const HarmonicTilt s = ForcedResponse::at_frequency(r.stator_tilt, w);
        const HarmonicTilt t = ForcedResponse::at_frequency(r.rotor_tilt, w);
        // (xi, eta) = Re((Gamma_xi, Gamma_eta) e^{i w t}): forward whirl, g = Gamma_xi e^{iwt}
        const double scale = std::abs(vg[2]);
        EXPECT_LT(std::abs(vg[0] - s.forward), 1e-10 * scale) << delta << " " << ratio << " " << w;
        EXPECT_LT(std::abs(vg[2] - t.forward), 1e-10 * scale) << delta << " " << ratio << " " << w;
        EXPECT_LT(std::abs(vg[1] + cplx(0, 1) * vg[0]), 1e-12 * scale);
        EXPECT_LT(std::abs(vg[3] + cplx(0, 1) * vg[2]), 1e-12 * scale);
        EXPECT_LT(std::abs(s.backward) + std::abs(t.backward), 1e-12 * scale);
        // the relative tilt, which is a small difference of two large tilts, too
        const double rel = std::abs(ForcedResponse::at_frequency(r.relative_tilt, w).forward);
        EXPECT_NEAR(std::abs(vg[0] - vg[2]), rel, 1e-6 * rel);
      }
}

// The same linear equations integrated in time from rest (SUNDIALS ARKode, implicit, rtol 1e-9)
// reach the analytic steady state: dynamic + static rotor misalignment (synchronous) and a static
// stator misalignment (constant part). The slowest mode decays as exp(-sigma t); integrating to
// 30/sigma leaves e^-30 of the start-up transient.
TEST(VarneyGreen, TimeIntegrationReachesAnalyticSteadyState)
{
  const auto d = varney_green(2, 0.2 / 1.7e-3, 0.5e-3, 0.1e-3, 0.2e-3);
  for (const double w : {1500.0, 2600.0})
  {
    double sigma = INFINITY;
    for (const auto &l : d.eigenvalues(w, 0))
      sigma = std::min(sigma, -l.real());
    ASSERT_GT(sigma, 0);
    const double t0 = 30 / sigma, T = 2 * M_PI / w;
    std::vector<double> times;
    for (int k = 0; k < 8; ++k)
      times.push_back(t0 + k * T / 8);
    const auto samples = d.integrate(w, 0, times.back(), times);
    const ForcedResponse r = d.forced_response(w, 0);
    auto analytic = [&](const std::vector<HarmonicTilt> &h, const double t)
    {
      cplx g = 0;
      for (const auto &x : h)
        g += x.forward * std::exp(cplx(0, x.frequency * t)) +
             x.backward * std::exp(cplx(0, -x.frequency * t));
      return g;
    };
    const double amplitude = ForcedResponse::max_magnitude(r.rotor_tilt);
    const double gamma_rel = ForcedResponse::max_magnitude(r.relative_tilt);
    for (const auto &s : samples)
    {
      const cplx gs = analytic(r.stator_tilt, s.time), gr = analytic(r.rotor_tilt, s.time);
      EXPECT_LT(std::abs(cplx(s.tilts[0], s.tilts[1]) - gs), 1e-6 * amplitude) << s.time;
      EXPECT_LT(std::abs(cplx(s.tilts[2], s.tilts[3]) - gr), 1e-6 * amplitude) << s.time;
      const cplx rel(s.tilts[0] - s.tilts[2], s.tilts[1] - s.tilts[3]);
      EXPECT_LT(std::abs(rel - analytic(r.relative_tilt, s.time)), 1e-3 * gamma_rel) << s.time;
    }
  }
}

// Varney & Green (2017) reports the rotor's forward critical speed at 990 rad/s. With Table 2 as
// printed (K_r = 5e5 N m/rad, I_tr = 0.2, I_pr = 0.1 kg m^2 for delta = 2) the rotor alone has its
// forward synchronous critical speed at sqrt(K_r/(I_tr - I_pr)) = 2236 rad/s. Coupled to the seal
// the peak of the rotor tilt lies between the rigidly riding stator's sqrt((K_r + K_s)/(I_tr - I_pr
// + I_ts)) and the rotor-alone peak of this omega^2-forced, damped mode, w_n/sqrt(1 - 2 zeta^2).
// K_r = 1e5 N m/rad reproduces the paper's 990 rad/s (I_tr/I_ts = 50, Fig. 6).
TEST(VarneyGreen, RotorCriticalSpeed)
{
  const double a = 0.2 - 0.1, Kr = 5e5, Ks = 363.9, Its = 0.2 / 50;
  const double w_n = std::sqrt(Kr / a);
  EXPECT_NEAR(w_n, 2236.07, 0.01);
  const double zeta = (20 - 1) / (2 * std::sqrt(Kr * a));
  const double upper = w_n / std::sqrt(1 - 2 * zeta * zeta);
  const double alone = peak_speed([](double w) { return rotor_alone_tilt(2, w); }, 500, 5000);
  EXPECT_NEAR(alone, upper, 1e-6 * upper);
  for (const double ratio : {50.0, 0.2 / 1.7e-3})
  {
    const auto d = varney_green(2, ratio);
    const double lower = std::sqrt((Kr + Ks) / (a + 0.2 / ratio));
    const double coupled = peak_speed([&](double w) { return rotor_tilt(d, w); }, 500, 5000);
    EXPECT_GT(coupled, lower) << "I_tr/I_ts = " << ratio;
    EXPECT_LT(coupled, upper) << "I_tr/I_ts = " << ratio;
    EXPECT_GT(std::abs(coupled - 990) / 990, 1.0) << "printed data cannot give 990 rad/s";
  }
  const auto paper = varney_green(2, 50, 0.5e-3, 0, 0, 1e5);
  const double w990 = peak_speed([&](double w) { return rotor_tilt(paper, w); }, 500, 2000);
  EXPECT_NEAR(w990, 990, 0.01 * 990);
  EXPECT_GT(w990, std::sqrt((1e5 + Ks) / (a + Its)));
}

// "The FMS and rotor are essentially decoupled for inertia ratios I_tr/I_ts above 100": the
// stator then rides on the rotor and shifts its critical speed by about
// (1/2)(K_s/K_r - I_ts/(I_tr - I_pr)), under 1% for I_tr/I_ts >= 100 (delta = 2), against ~30%
// for comparable inertias.
TEST(VarneyGreen, SealAndRotorDecoupleForHeavyRotors)
{
  const double alone = peak_speed([](double w) { return rotor_alone_tilt(2, w); }, 500, 5000);
  for (const double ratio : {100.0, 0.2 / 1.7e-3, 200.0})
  {
    const auto d = varney_green(2, ratio);
    const double coupled = peak_speed([&](double w) { return rotor_tilt(d, w); }, 500, 5000);
    const double predicted = 0.5 * (363.9 / 5e5 - (0.2 / ratio) / 0.1);
    EXPECT_LT(std::abs(coupled / alone - 1), 0.01) << "I_tr/I_ts = " << ratio;
    EXPECT_NEAR(coupled / alone - 1, predicted, 0.25 * std::abs(predicted)) << ratio;
  }
  const auto light = varney_green(2, 2);
  const double coupled = peak_speed([&](double w) { return rotor_tilt(light, w); }, 500, 5000);
  EXPECT_GT(std::abs(coupled / alone - 1), 0.1);
}

// Fig. 5: the largest relative tilt over the speed range against I_tr/I_ts. A thick rotor
// (delta = 2) amplifies it at intermediate inertia ratios (an interior maximum; the paper finds it
// at 6.48), a thin rotor (delta = 0.5) gives a monotone decrease.
TEST(VarneyGreen, ThickRotorAmplifiesThinRotorDoesNot)
{
  auto largest = [](const double delta, const double ratio)
  {
    const auto d = varney_green(delta, ratio);
    double g = 0;
    for (double w = 20; w <= 6000; w += 20)
      g = std::max(g, relative_tilt(d, w));
    return g;
  };
  const std::vector<double> ratios{1, 2, 4, 6.48, 10, 20, 50, 100, 200};
  std::vector<double> thick, thin;
  for (const double r : ratios)
  {
    thick.push_back(largest(2, r));
    thin.push_back(largest(0.5, r));
  }
  const auto top = std::max_element(thick.begin(), thick.end()) - thick.begin();
  EXPECT_GT(top, 0);
  EXPECT_LT(top, long(ratios.size()) - 1);
  EXPECT_GT(thick[top], 1.2 * thick.front());
  for (unsigned int i = 1; i < thin.size(); ++i)
    EXPECT_LT(thin[i], thin[i - 1]) << "I_tr/I_ts = " << ratios[i];
}

// Fig. 7a: a thin rotor (delta = 0.5, a = I_tr - I_pr < 0) has no forward critical speed. Alone,
// its tilt |a| chi w^2 / |K_r + |a| w^2 + i w c| grows monotonically towards chi; with the stator
// riding on it the bound becomes chi |a| / (|a| - I_ts). The relative tilt shows no resonance
// peak: it grows monotonically above 500 rad/s (below, it wanders at ~1e-8 rad, 0.05% of the
// contact limit, where the stator's own support matters).
TEST(VarneyGreen, ThinRotorIsGyroscopicallyStabilised)
{
  const auto d = varney_green(0.5, 50);
  const double chi = 0.5e-3, a = 0.2, Its = 0.2 / 50, bound = chi * a / (a - Its);
  double previous_rotor = 0, previous_rel = 0;
  for (double w = 50; w <= 8000; w += 50)
  {
    const double g = rotor_tilt(d, w), rel = relative_tilt(d, w);
    EXPECT_LT(g, bound) << w;
    EXPECT_GT(g, previous_rotor) << w;
    if (w > 500)
    {
      EXPECT_GT(rel, previous_rel) << w;
    }
    previous_rotor = g;
    previous_rel = rel;
  }
  EXPECT_GT(rotor_tilt(d, 1e5), chi);
  EXPECT_LT(rotor_tilt(d, 1e5), bound);
}

// Fig. 6: with the rotordynamics included (delta = 2, I_tr/I_ts = 50, chi = 0.5 mrad) the
// relative tilt exceeds the contact limit C0/ri near the critical speed, though not well below or
// above it.
TEST(VarneyGreen, FaceContactNearCriticalSpeed)
{
  const auto d = varney_green(2, 50);
  const double limit = 1e-6 / 0.0355;
  EXPECT_GT(relative_tilt(d, 2200), limit);
  EXPECT_LT(relative_tilt(d, 1000), 0.1 * limit);
  EXPECT_LT(relative_tilt(d, 5000), limit);
}

// ---------------------------------------------------------------------------------------------
// `sealfe response` front end, on the example prm/response.prm (Fig. 6: delta = 2,
// I_tr/I_ts = 50, chi = 0.5 mrad).
#include <sealfe/dynamics/response_study.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/operating_conditions.h>

#include <filesystem>
#include <fstream>

namespace
{
void declare_all(dealii::ParameterHandler &prm)
{
  prm.declare_entry("Output directory", "sealfe-output", dealii::Patterns::Anything());
  FilmThickness::declare_parameters(prm);
  OperatingConditions::declare_parameters(prm);
  response::declare_parameters(prm);
}
} // namespace

TEST(ResponseSubcommand, ExamplePrmFindsContactAroundTheCriticalSpeed)
{
  dealii::ParameterHandler prm;
  declare_all(prm);
  prm.parse_input(std::string(SEALFE_SOURCE_DIR) + "/prm/response.prm");
  prm.enter_subsection("Forced response");
  prm.set("Plot", false); // the plot is exercised by hand (doc/dynamics.md), not in CI
  prm.leave_subsection();
  const auto dir = std::filesystem::temp_directory_path() / "sealfe_test_response";
  std::filesystem::create_directories(dir);
  const nlohmann::json j = response::run(prm, dir.string());
  EXPECT_EQ(j["configuration"], "FMS with flexible rotor");
  EXPECT_EQ(j["film_model_level"], 0);
  EXPECT_NEAR(j["contact_tilt"].get<double>(), 1e-6 / 0.0355, 1e-15);
  EXPECT_NEAR(j["rotor_critical_speed"].get<double>(), std::sqrt(5e5 / 0.1), 1e-6);
  EXPECT_TRUE(j["contact"].get<bool>());
  // the peak lies between the rigidly riding stator's critical speed and the rotor-alone peak
  const double w = j["speed_at_peak_relative_tilt"].get<double>(), step = 4990.0 / 499;
  EXPECT_GT(w + step, std::sqrt((5e5 + 363.9) / (0.1 + 4e-3)));
  EXPECT_LT(w - step, 2240.1);
  ASSERT_EQ(j["contact_speed_ranges"].size(), 1u);
  EXPECT_LT(j["contact_speed_ranges"][0][0].get<double>(), w);
  EXPECT_GT(j["contact_speed_ranges"][0][1].get<double>(), w);
  EXPECT_EQ(j["unstable_speed_ranges"].size(), 0u);
  // the CSV (doc/csv.md: one header line of `name [unit]`, no comment lines) has one row per
  // speed and the columns the plot script reads
  std::ifstream csv(dir / "response.csv");
  std::string line, header;
  std::getline(csv, header);
  unsigned int rows = 0;
  while (std::getline(csv, line))
  {
    EXPECT_NE(line[0], '#');
    ++rows;
  }
  EXPECT_EQ(rows, 500u);
  for (const char *column :
       {"swept_speed [rad/s]", "relative_tilt [rad]", "relative_tilt_phase [deg]",
        "contact_margin [rad]", "contact_tilt [rad]", "stable [-]"})
    EXPECT_NE(header.find(column), std::string::npos) << column;
}

TEST(ResponseSubcommand, RefusesBadSpeedRange)
{
  dealii::ParameterHandler prm;
  declare_all(prm);
  prm.parse_input(std::string(SEALFE_SOURCE_DIR) + "/prm/response.prm");
  prm.enter_subsection("Forced response");
  prm.set("Speed to", "5");
  prm.leave_subsection();
  try
  {
    response::run(prm, std::filesystem::temp_directory_path().string());
    ADD_FAILURE() << "accepted Speed to < Speed from";
  }
  catch (const std::runtime_error &e)
  {
    EXPECT_NE(std::string(e.what()).find("Speed to"), std::string::npos) << e.what();
  }
}
