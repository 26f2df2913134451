// Validation of the Patir & Cheng average-flow factors (FlowFactors): published fits, symmetry,
// direction of the pattern effect, smooth limits with their analytic rates, closed forms against
// quadrature of their defining integrals, derivatives, clamping and parameters.
#include <sealfe/film/flow_factors.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <sstream>

using namespace sealfe;

namespace
{
const double sigma = 1e-7;
const double patterns[7] = {1. / 9., 1. / 6., 1. / 3., 1., 3., 6., 9.};

/// Composite Gauss-Legendre quadrature of f over [a, b].
double integrate(const std::function<double(double)> &f, const double a, const double b,
                 const unsigned int intervals = 400)
{
  const dealii::QGauss<1> q(10);
  const double dx = (b - a) / intervals;
  double sum = 0;
  for (unsigned int i = 0; i < intervals; ++i)
    for (unsigned int k = 0; k < q.size(); ++k)
      sum += q.weight(k) * dx * f(a + (i + q.point(k)[0]) * dx);
  return sum;
}

double gaussian(const double x)
{
  return std::exp(-0.5 * x * x) / std::sqrt(2 * M_PI);
}

FlowFactors rough(const double gamma, const double share = 0.5)
{
  return FlowFactors(FlowFactors::Model::patir_cheng, sigma, gamma, share);
}

/// Relative central difference check of an h-derivative.
void expect_slope(const std::function<ValueAndSlope(double)> &f, const double h, const char *what)
{
  const double dh = 1e-6 * h;
  const double fd = (f(h + dh).value - f(h - dh).value) / (2 * dh);
  const double analytic = f(h).d_dh;
  EXPECT_NEAR(analytic, fd, 1e-6 * std::max(std::abs(fd), 1. / sigma * 1e-3))
      << what << " at h/sigma = " << h / sigma;
}
} // namespace

// ---------------------------------------------------------------------------------------------
// The published fits. Reference values computed by hand from PC 1978 Table 1 (C, r) and PC 1979
// (A1, alpha1..3, A2), coefficient tables cross-checked against a second public implementation
// (doc/roughness.md). Tolerance: the 6-digit rounding of the hand values.

TEST(PublishedFits, PressureFlowFactorAtTablePoints)
{
  const double H[3] = {1., 2., 4.};
  const double expected[3][7] = {
      {0.027571, 0.093275, 0.224685, 0.485912, 1.225, 1.52, 1.87},
      {0.361068, 0.404239, 0.490582, 0.706348, 1.07955, 1.183848, 1.307591},
      {0.724167, 0.742804, 0.780079, 0.904187, 1.028125, 1.065, 1.10875}};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 7; ++k)
      EXPECT_NEAR(patir_cheng::pressure_flow_factor(H[i], patterns[k]).value, expected[i][k], 1e-6)
          << "gamma = " << patterns[k] << ", H = " << H[i];
}

TEST(PublishedFits, ShearFlowFactorPiecesMeetAtH5)
{
  // PC 1979 chose A2 so that A1 H^a1 exp(-a2 H + a3 H^2) and A2 exp(-H/4) meet at H = 5; with
  // A2 printed to 3 decimals (0.295 +- 0.0005: 0.17 %) they must meet to 0.2 %. A mistyped
  // coefficient in either piece breaks this.
  for (const double g : patterns)
  {
    const double below = patir_cheng::shear_flow_factor(5., g).value;
    const double above = patir_cheng::shear_flow_factor(5. + 1e-12, g).value;
    EXPECT_NEAR(above / below, 1., 2e-3) << "gamma = " << g;
  }
  // One hand value per regime, isotropic: 1.899 * 2^0.98 exp(-1.84 + 0.2) and 1.126 exp(-1.5).
  EXPECT_NEAR(patir_cheng::shear_flow_factor(2., 1.).value,
              1.899 * std::pow(2., 0.98) * std::exp(-1.84 + 0.2), 1e-12);
  EXPECT_NEAR(patir_cheng::shear_flow_factor(6., 1.).value, 1.126 * std::exp(-1.5), 1e-12);
}

TEST(PublishedFits, ShearStressFactorsIsotropic)
{
  // PC 1979, gamma = 1: Phi_fs = 11.1 H^2.31 exp(-2.38 H + 0.11 H^2) (H < 7, else 0) and
  // phi_fp = 1 - 1.40 exp(-0.66 H).
  for (const double H : {0.5, 1., 2., 4., 6.5})
  {
    EXPECT_NEAR(patir_cheng::roughness_shear_factor(H, 1.).value,
                11.1 * std::pow(H, 2.31) * std::exp(-2.38 * H + 0.11 * H * H), 1e-12);
    EXPECT_NEAR(patir_cheng::poiseuille_shear_factor(H, 1.).value, 1 - 1.40 * std::exp(-0.66 * H),
                1e-12);
  }
  EXPECT_EQ(patir_cheng::roughness_shear_factor(7.5, 1.).value, 0.);
}

// ---------------------------------------------------------------------------------------------
// Orientation

TEST(Orientation, GammaAndInverseSwapTheDirections)
{
  // PC 1978: phi_y(H, gamma) = phi_x(H, 1/gamma), for tabulated and interpolated patterns.
  for (const double g : {1. / 9., 0.2, 1. / 3., 0.5, 1., 2., 3., 4.5, 9.})
    for (const double H : {1., 1.7, 3., 6.})
    {
      const ValueAndSlope radial = rough(g).radial_pressure_flow_factor(H * sigma);
      const ValueAndSlope circ = rough(1. / g).circumferential_pressure_flow_factor(H * sigma);
      EXPECT_NEAR(radial.value, circ.value, 1e-14) << "gamma = " << g << ", H = " << H;
      EXPECT_NEAR(radial.d_dh * sigma, circ.d_dh * sigma, 1e-12);
    }
}

TEST(Orientation, RadialRidgesRaiseLeakageCircumferentialLayLowersIt)
{
  // Patir-Cheng (and second-order perturbation theory, Tripp 1983: phi_x - 1 ~ (1 - 3/(1 + gamma))
  // 3/H^2): flow along the ridges is easier. In a seal sliding is circumferential, so transverse
  // roughness (gamma < 1, ridges radial) has phi_r > 1 (more leakage) and phi_theta < 1;
  // longitudinal roughness (gamma > 1, circumferential lay) has phi_r < 1 (less leakage).
  // Isotropic roughness blocks flow both ways (phi < 1).
  for (const double H : {1., 1.5, 2., 3., 4., 6.})
  {
    for (const double g : {1. / 9., 1. / 6., 1. / 3.})
    {
      EXPECT_GT(rough(g).radial_pressure_flow_factor(H * sigma).value, 1.) << g << " " << H;
      EXPECT_LT(rough(g).circumferential_pressure_flow_factor(H * sigma).value, 1.);
    }
    for (const double g : {3., 6., 9.})
    {
      EXPECT_LT(rough(g).radial_pressure_flow_factor(H * sigma).value, 1.) << g << " " << H;
      EXPECT_GT(rough(g).circumferential_pressure_flow_factor(H * sigma).value, 1.);
    }
    EXPECT_LT(rough(1.).radial_pressure_flow_factor(H * sigma).value, 1.);
    // The radial factor falls monotonically as the lay turns from radial to circumferential.
    double previous = 1e300;
    for (const double g : {1. / 9., 0.15, 1. / 6., 0.25, 1. / 3., 0.6, 1., 2., 3., 4., 6., 9.})
    {
      const double phi_r = rough(g).radial_pressure_flow_factor(H * sigma).value;
      EXPECT_LT(phi_r, previous) << "gamma = " << g << ", H = " << H;
      previous = phi_r;
    }
  }
}

TEST(Orientation, PressureFlowFactorBelowArithmeticMeanBound)
{
  // Wiener bound: whatever the pattern, the effective "conductivity" phi h^3 of a film with
  // local conductivity h_T^3 cannot exceed its arithmetic mean E[h_T^3] (parallel channels).
  // Gaussian heights, h_T = max(h + d, 0).
  for (const double H : {0.5, 1., 2., 3., 4., 6.})
  {
    const double mean_cube =
        integrate([H](double d) { return std::pow(H + d, 3) * gaussian(d); }, -H, 12.);
    for (const double g : patterns)
    {
      const FlowFactors f = rough(g);
      if (H < patir_cheng::pressure_flow_factor_validity(g) ||
          H < patir_cheng::pressure_flow_factor_validity(1. / g))
        continue;
      EXPECT_LE(f.circumferential_pressure_flow_factor(H * sigma).value, mean_cube / (H * H * H));
      EXPECT_LE(f.radial_pressure_flow_factor(H * sigma).value, mean_cube / (H * H * H));
      EXPECT_GT(f.radial_pressure_flow_factor(H * sigma).value, 0.);
      EXPECT_GT(f.circumferential_pressure_flow_factor(H * sigma).value, 0.);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Between the tabulated patterns and beyond the fits' range (doc/roughness.md 2.2): the published
// fits at the seven patterns for H <= 6, Tripp's (1983) perturbative 1 + T(gamma)/H^2 from
// H = 12, T(gamma) = 3 (1 - 3/(1 + gamma)) for the Peklenik gamma.

namespace
{
/// <k_x^2/|k|^2> over the spectrum of a Peklenik surface: an isotropic spectrum stretched by the
/// correlation lengths (k_x = u/lambda_x, k_y = v/lambda_y, gamma = lambda_x/lambda_y), so the
/// mean over the direction t of (u, v): cos^2 t / (cos^2 t + gamma^2 sin^2 t). Midpoint rule on
/// a periodic analytic integrand: exponentially accurate.
double stretched_direction_mean(const double gamma)
{
  const int n = 4000;
  double sum = 0;
  for (int i = 0; i < n; ++i)
  {
    const double t = (i + 0.5) * 2 * M_PI / n;
    const double c = std::cos(t), s = std::sin(t);
    sum += c * c / (c * c + gamma * gamma * s * s);
  }
  return sum / n;
}

/// The PC 1978 Table 1 fit at tabulated pattern k, typed from the table.
double published_pressure_fit(const int k, const double H)
{
  const double C[7] = {1.48, 1.38, 1.18, 0.90, 0.225, 0.520, 0.870};
  const double r[7] = {0.42, 0.42, 0.42, 0.56, 1.5, 1.5, 1.5};
  return k <= 3 ? 1 - C[k] * std::exp(-r[k] * H) : 1 + C[k] * std::pow(H, -r[k]);
}
} // namespace

TEST(BetweenPatterns, TrippShapeIsTheSecondOrderPerturbation)
{
  // Second-order perturbation of the conductance h^3 = h0^3 (1 + 3 d/h0 + 3 d^2/h0^2 + ...) of a
  // 2-D random medium: K_xx/h0^3 = 1 + 3/H^2 - 9/H^2 <k_x^2/|k|^2>, so T = 3 (1 - 3 <.>). The
  // angular mean by quadrature must be 1/(1 + gamma) (not 1/(1 + gamma^2)).
  for (const double g : {1. / 9., 0.2, 0.5, 1., std::sqrt(2.), 2., 4.5, 9.})
  {
    EXPECT_NEAR(stretched_direction_mean(g), 1. / (1. + g), 1e-12) << "gamma = " << g;
    EXPECT_NEAR(patir_cheng::tripp_shape(g), 3 * (1 - 3 * stretched_direction_mean(g)), 1e-11);
  }
  // The 1-D limits are the exact results 1/E[h^-3] -> 1 - 6/H^2 (transverse ridges, gamma -> 0)
  // and E[h^3] -> 1 + 3/H^2 (longitudinal, gamma -> infinity); the trace of the tensor,
  // (phi_x - 1) + (phi_y - 1) = (6 - 9)/H^2, does not depend on the pattern.
  EXPECT_NEAR(patir_cheng::tripp_shape(0.), -6., 1e-15);
  EXPECT_NEAR(patir_cheng::tripp_shape(1e12), 3., 1e-11);
  for (const double g : {0.13, 0.5, 1., 2., 7.})
    EXPECT_NEAR(patir_cheng::tripp_shape(g) + patir_cheng::tripp_shape(1. / g), -3., 1e-14);
  // At H = 6, the largest H of PC's simulations, the published fits' (phi_x - 1) H^2 at the six
  // anisotropic patterns lie closer to this T than to 3 (1 - 3/(1 + gamma^2)).
  for (const int k : {0, 1, 2, 4, 5, 6})
  {
    const double g = patterns[k];
    const double fit = (published_pressure_fit(k, 6.) - 1) * 36.;
    const double other = 3 * (1 - 3 / (1 + g * g));
    EXPECT_LT(std::abs(fit - patir_cheng::tripp_shape(g)), std::abs(fit - other))
        << "gamma = " << g;
  }
}

TEST(BetweenPatterns, PublishedFitsAtTheTabulatedPatterns)
{
  for (int k = 0; k < 7; ++k)
    for (const double H : {0.5, 0.75, 1., 1.5, 2., 3., 4., 5., 6.})
    {
      EXPECT_NEAR(patir_cheng::pressure_flow_factor(H, patterns[k]).value,
                  published_pressure_fit(k, H), 1e-14)
          << "gamma = " << patterns[k] << ", H = " << H;
      // ... and through FlowFactors, along and across sliding (PC: phi_y(gamma) = phi_x(1/gamma))
      if (H >= patir_cheng::pressure_flow_factor_validity(patterns[k]) &&
          H >= patir_cheng::pressure_flow_factor_validity(patterns[6 - k]))
      {
        EXPECT_NEAR(rough(patterns[k]).circumferential_pressure_flow_factor(H * sigma).value,
                    published_pressure_fit(k, H), 1e-14);
        EXPECT_NEAR(rough(patterns[k]).radial_pressure_flow_factor(H * sigma).value,
                    published_pressure_fit(6 - k, H), 1e-14);
      }
    }
}

TEST(BetweenPatterns, TrippLimitAtLargeFilmParameter)
{
  // From H = 12 on, (phi - 1) H^2 = T(gamma) at every pattern, tabulated or not.
  for (const double g : {1. / 9., 0.5, 1., 2., 3., 4.5, 9.})
    for (const double H : {12., 20., 50., 1e3})
    {
      const double T = 3 * (1 - 3 / (1 + g));
      const FlowFactors f = rough(g);
      EXPECT_NEAR((f.circumferential_pressure_flow_factor(H * sigma).value - 1) * H * H, T,
                  1e-12 * H * H)
          << "gamma = " << g << ", H = " << H;
      EXPECT_NEAR((f.radial_pressure_flow_factor(H * sigma).value - 1) * H * H,
                  3 * (1 - 3 / (1 + 1 / g)), 1e-12 * H * H);
    }
  // Below H = 12 the blend moves from the fits towards it: at H = 9 (half way) the departure lies
  // between the fit's and Tripp's (isotropic: 1 - 0.9 exp(-0.56 H) and 1 - 1.5/H^2).
  const double at9 = patir_cheng::pressure_flow_factor(9., 1.).value;
  EXPECT_LT(at9, 1 - 0.9 * std::exp(-0.56 * 9.));
  EXPECT_GT(at9, 1 - 1.5 / 81.);
}

TEST(BetweenPatterns, CrossesOneAtTrippsPattern)
{
  // phi_x - 1 has the sign of T(gamma): it vanishes at gamma = 2 for every H (the rule scales the
  // gamma = 1..3 departure by T), and the radial factor at gamma = 1/2. sqrt(2) (the crossing of
  // 3 (1 - 3/(1 + gamma^2))) is on the blocking side.
  for (const double H : {0.5, 1., 2., 4., 6., 9., 12., 50.})
  {
    EXPECT_NEAR(patir_cheng::pressure_flow_factor(H, 2.).value, 1., 1e-15) << "H = " << H;
    EXPECT_NEAR(rough(0.5).radial_pressure_flow_factor(H * sigma).value, 1., 1e-15);
    EXPECT_LT(patir_cheng::pressure_flow_factor(H, 1.9).value, 1.);
    EXPECT_GT(patir_cheng::pressure_flow_factor(H, 2.1).value, 1.);
    EXPECT_LT(patir_cheng::pressure_flow_factor(H, std::sqrt(2.)).value, 1.);
  }
}

TEST(BetweenPatterns, MonotonicInThePatternAndContinuous)
{
  // Along sliding the flow rises as the lay turns from transverse to longitudinal, at every H
  // (the tabulated fits are ordered so; the rule keeps the order between them).
  const int n = 800;
  for (const double H : {0.5, 0.8, 1., 1.5, 2., 3., 4., 6., 7., 9., 11., 12., 30.})
  {
    double previous = -1e300;
    for (int i = 0; i <= n; ++i)
    {
      const double g = std::exp(std::log(1. / 9.) + i * std::log(81.) / n);
      const double phi = patir_cheng::pressure_flow_factor(H, g).value;
      EXPECT_GT(phi, previous) << "gamma = " << g << ", H = " << H;
      previous = phi;
    }
    // No jump at the tabulated patterns: a relative step of 1e-9 in gamma moves phi by
    // |d phi/d ln gamma| 1e-9, and |d phi/d ln gamma| < 3 (largest: gamma = 6..9 at H = 0.5,
    // (0.87 - 0.52) 0.5^-1.5 / ln 1.5 = 2.44).
    for (int k = 1; k < 6; ++k)
    {
      const double at = patir_cheng::pressure_flow_factor(H, patterns[k]).value;
      for (const double e : {-1e-9, 1e-9})
        EXPECT_NEAR(patir_cheng::pressure_flow_factor(H, patterns[k] * (1 + e)).value, at, 3e-9)
            << "gamma = " << patterns[k] << ", H = " << H;
    }
  }
  // No jump in H where the blend starts and ends (value and slope, C1).
  for (const double g : {1. / 9., 0.5, 1., 1.5, 4.5})
    for (const double H : {patir_cheng::fits_upper_limit, patir_cheng::tripp_from})
    {
      const ValueAndSlope below = patir_cheng::pressure_flow_factor(H * (1 - 1e-12), g);
      const ValueAndSlope above = patir_cheng::pressure_flow_factor(H * (1 + 1e-12), g);
      EXPECT_NEAR(below.value, above.value, 1e-12) << "gamma = " << g << ", H = " << H;
      EXPECT_NEAR(below.d_dh, above.d_dh, 1e-10) << "gamma = " << g << ", H = " << H;
    }
}

TEST(BetweenPatterns, MirrorSymmetry)
{
  // PC 1978: phi_y(H, gamma) = phi_x(H, 1/gamma) at every pattern and H, in all three ranges.
  for (const double g : {0.12, 0.2, 0.4, 0.5, 0.7, 1.3, 2., 2.5, 4.5, 7.})
    for (const double H : {1., 3., 6., 8., 10., 12., 40.})
    {
      const ValueAndSlope radial = rough(g).radial_pressure_flow_factor(H * sigma);
      const ValueAndSlope circ = rough(1. / g).circumferential_pressure_flow_factor(H * sigma);
      EXPECT_NEAR(radial.value, circ.value, 1e-14) << "gamma = " << g << ", H = " << H;
      EXPECT_NEAR(radial.d_dh * sigma, circ.d_dh * sigma, 1e-12);
    }
}

// ---------------------------------------------------------------------------------------------
// Shear flow: the sign rule of PC 1979, phi_s = (V_r1 - V_r2) Phi_s.

TEST(ShearFlow, SwappingTheRoughFaceFlipsTheSign)
{
  for (const double g : {1. / 9., 0.5, 1., 3., 9.})
    for (const double H : {0.7, 2., 4., 8.})
    {
      const double h = H * sigma;
      const double Phi_s = patir_cheng::shear_flow_factor(H, g).value;
      EXPECT_GT(Phi_s, 0.);
      // Only the rotor rough: the moving rough face drags extra fluid, +Phi_s.
      EXPECT_DOUBLE_EQ(rough(g, 1.).shear_flow_factor(h).value, Phi_s);
      // Only the stator rough: -Phi_s.
      EXPECT_DOUBLE_EQ(rough(g, 0.).shear_flow_factor(h).value, -Phi_s);
      for (const double share : {0.2, 0.35})
      {
        EXPECT_NEAR(rough(g, share).shear_flow_factor(h).value,
                    -rough(g, 1 - share).shear_flow_factor(h).value, 1e-15);
        EXPECT_NEAR(rough(g, share).shear_stress_factors(h).phi_fs.value,
                    -rough(g, 1 - share).shear_stress_factors(h).phi_fs.value, 1e-15);
      }
      EXPECT_EQ(rough(g, 0.5).shear_flow_factor(h).value, 0.);
    }
}

// ---------------------------------------------------------------------------------------------
// Limits

TEST(SmoothLimit, ModelNoneIsTheSmoothFilm)
{
  const FlowFactors f(FlowFactors::Model::none, 1e-7, 3., 1.);
  for (const double h : {-1e-7, 0., 1e-8, 1e-6})
  {
    const FlowFactors::FilmFactors ff = f.film_factors(h);
    EXPECT_EQ(ff.phi_theta.value, 1.);
    EXPECT_EQ(ff.phi_r.value, 1.);
    EXPECT_EQ(ff.phi_s.value, 0.);
    EXPECT_EQ(ff.h_T.value, h);
    EXPECT_EQ(ff.h_T.d_dh, 1.);
    EXPECT_EQ(ff.phi_theta.d_dh + ff.phi_r.d_dh + ff.phi_s.d_dh, 0.);
    const FlowFactors::ShearStressFactors s = f.shear_stress_factors(h);
    EXPECT_EQ(s.phi_f.value, 1.);
    EXPECT_EQ(s.phi_fs.value, 0.);
    EXPECT_EQ(s.phi_fp.value, 1.);
  }
  EXPECT_EQ(f.clamp_count(), 0u);
  // Smooth wall stresses (film with the rotor at z = 0 moving at u1, stator at z = h at u2):
  // tau_1 = mu (u2 - u1)/h - h/2 dp/dx on the rotor, tau_2 = mu (u1 - u2)/h - h/2 dp/dx on the
  // stator; together they balance the pressure drop, tau_1 + tau_2 = -h dp/dx.
  const double h = 2e-6, mu = 1.2e-3, u1 = 30., u2 = -4., dpdx = 3e7;
  EXPECT_DOUBLE_EQ(f.rotor_shear_stress(h, mu, u1, u2, dpdx), mu * (u2 - u1) / h - h / 2 * dpdx);
  EXPECT_DOUBLE_EQ(f.stator_shear_stress(h, mu, u1, u2, dpdx), mu * (u1 - u2) / h - h / 2 * dpdx);
  EXPECT_NEAR(f.rotor_shear_stress(h, mu, u1, u2, dpdx) +
                  f.stator_shear_stress(h, mu, u1, u2, dpdx),
              -h * dpdx, 1e-9);
}

TEST(SmoothLimit, ExpectedGapApproachesHWithTheGaussianTailRate)
{
  // h_T/sigma - H = phi(H) - H Q(H) = phi(H) (1/H^2 - 3/H^4 + 15/H^6 - ...) (Mills ratio): the
  // ratio to phi(H)/H^2 is 1 - 3/H^2 within the next term 15/H^4.
  const FlowFactors f = rough(1.);
  for (const double H : {4., 5., 6.})
  {
    const double excess = f.expected_gap(H * sigma).value / sigma - H;
    const double ratio = excess / (gaussian(H) / (H * H));
    EXPECT_NEAR(ratio, 1 - 3 / (H * H), 15 / std::pow(H, 4)) << "H = " << H;
  }
  // and from below: h_T -> 0 as h -> -infinity, h_T >= max(h, 0), h_T(0) = sigma/sqrt(2 pi).
  EXPECT_NEAR(f.expected_gap(0.).value, sigma / std::sqrt(2 * M_PI), 1e-22);
  EXPECT_LT(f.expected_gap(-6 * sigma).value, 1e-9 * sigma);
  for (const double H : {-2., -0.5, 0.3, 1., 3.})
    EXPECT_GE(f.expected_gap(H * sigma).value, std::max(H, 0.) * sigma);
}

TEST(SmoothLimit, PressureAndShearFactorsTendToSmoothValues)
{
  // Pressure flow factors from H = 12: Tripp's phi_x - 1 = T(gamma)/H^2, |T| <= 5.1 (gamma = 1/9),
  // i.e. within 1.3 % at H = 20 and 0.32 % at H = 40. The fits' own decay for the others (PC):
  // Phi_s = A2 exp(-H/4) (H > 5), Phi_fs = 0 (H >= 7), 1 - phi_fp = D exp(-s H). The deviations
  // shrink from H = 20 to 40.
  for (const double g : patterns)
  {
    const FlowFactors f = rough(g, 1.);
    for (const double H : {20., 40.})
    {
      const double h = H * sigma;
      const double tol = H == 40. ? 5e-3 : 1.5e-2;
      EXPECT_NEAR(f.circumferential_pressure_flow_factor(h).value, 1., tol) << g;
      EXPECT_NEAR(f.radial_pressure_flow_factor(h).value, 1., tol) << g;
      EXPECT_NEAR(f.shear_flow_factor(h).value, 0., 1.1 * 2.046 * std::exp(-H / 4));
      EXPECT_EQ(f.shear_stress_factors(h).phi_fs.value, 0.);
      EXPECT_NEAR(f.shear_stress_factors(h).phi_fp.value, 1.,
                  1.51 * std::exp(-0.52 * H) * (1 + 1e-9));
    }
    EXPECT_LT(std::abs(f.radial_pressure_flow_factor(40 * sigma).value - 1),
              std::abs(f.radial_pressure_flow_factor(20 * sigma).value - 1));
  }
}

TEST(SmoothLimit, CouetteShearFactorRate)
{
  // phi_f = h E[1/(h + d)] = 1 + E[d^2]/h^2 + E[d^4]/h^4 + ..., and for the polynomial density
  // E[d^2] = c^2/9 = sigma^2, E[d^4] = c^4/33: phi_f - 1 - 1/H^2 = 81/(33 H^4) + O(H^-6).
  for (const double H : {8., 12., 20., 60.})
  {
    const double excess = patir_cheng::couette_shear_factor(H).value - 1 - 1 / (H * H);
    EXPECT_NEAR(excess, 81. / 33. / std::pow(H, 4), 40. / std::pow(H, 6)) << "H = " << H;
  }
}

// ---------------------------------------------------------------------------------------------
// Closed forms against quadrature of their definitions

TEST(ClosedForms, ExpectedGapIsTheMeanOfThePositiveGap)
{
  // h_T = E[max(h + d, 0)] and d h_T/dh = P(h + d > 0), d ~ N(0, sigma^2).
  const FlowFactors f = rough(1.);
  for (const double H : {-2., -0.5, 0., 0.5, 1., 3.})
  {
    const double mean = integrate([H](double d) { return (H + d) * gaussian(d); }, -H, 14.);
    const double open = integrate([](double d) { return gaussian(d); }, -H, 14.);
    const ValueAndSlope hT = f.expected_gap(H * sigma);
    EXPECT_NEAR(hT.value / sigma, mean, 1e-12) << "H = " << H;
    EXPECT_NEAR(hT.d_dh, open, 1e-12) << "H = " << H;
  }
}

TEST(ClosedForms, CouetteShearFactorAgainstItsIntegral)
{
  // phi_f = z Int (35/32)(1 - u^2)^3/(z + u) du over the open gap, z = H/3. For z > 1 the
  // closed form is exact. For z <= 1 the gap is cut off at eps* = 1/300 (of c) and PC's closed
  // form drops an O(eps*) polynomial part; adding it back must give the integral exactly.
  const double eps = 1. / 300.;
  for (const double H : {0.3, 0.9, 1.5, 2.2, 2.9, 3.3, 4.5, 7., 12.})
  {
    const double z = H / 3;
    const double lower = z <= 1 ? -z + eps : -1.;
    // Integrate in v = ln(z + u) to resolve the 1/(z + u) layer near the cut-off.
    const double integral = integrate(
        [z](double v)
        {
          const double u = std::exp(v) - z;
          const double q = 1 - u * u;
          return 35. / 32. * q * q * q;
        },
        std::log(z + lower), std::log(z + 1.), 2000);
    if (z > 1)
    {
      EXPECT_NEAR(patir_cheng::couette_shear_factor(H).value, z * integral, 1e-11) << "H = " << H;
      continue;
    }
    // The part PC dropped: (35/32) z Int_0^eps* g(v) dv, g(v) = [(1-(v-z)^2)^3 - (1-z^2)^3]/v.
    const double dropped = integrate(
        [z](double v)
        {
          const double q = 1 - (v - z) * (v - z), q0 = 1 - z * z;
          return 35. / 32. * (q * q * q - q0 * q0 * q0) / v;
        },
        0., eps, 10);
    EXPECT_NEAR(patir_cheng::couette_shear_factor(H).value, z * (integral + dropped), 1e-11)
        << "H = " << H;
    // ... and it is the O(eps*) error of the published form: to first order
    // (35/32) 6 z^2 (1 - z^2)^2 eps*, at most 3.3e-3 (at z^2 = 1/3).
    EXPECT_NEAR(z * dropped, 35. / 32. * 6 * z * z * std::pow(1 - z * z, 2) * eps, 2e-4);
    EXPECT_LT(std::abs(z * dropped), 3.3e-3);
  }
  // Both published branches give exactly 7/6 at H = 3 (z = 1), and the series takes over from
  // the closed form at H = 6 without a jump.
  EXPECT_NEAR(patir_cheng::couette_shear_factor(3.).value, 7. / 6., 1e-14);
  EXPECT_NEAR(patir_cheng::couette_shear_factor(3. + 1e-12).value, 7. / 6., 1e-10);
  // (slope about -2/H^3 = -0.0093 over the 1e-9 step, plus round-off)
  EXPECT_NEAR(patir_cheng::couette_shear_factor(6. - 1e-9).value,
              patir_cheng::couette_shear_factor(6.).value, 1e-11 + 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Derivatives (for Newton and the linearisation)

TEST(Derivatives, MatchCentralDifferences)
{
  for (const double g : {1. / 9., 0.25, 1., 2., 9.})
  {
    const FlowFactors f = rough(g, 0.8);
    for (const double H : {1.2, 2.5, 4.3, 6.2, 9., 16., 30.})
    {
      const double h = H * sigma;
      expect_slope([&](double x) { return f.circumferential_pressure_flow_factor(x); }, h,
                   "phi_theta");
      expect_slope([&](double x) { return f.radial_pressure_flow_factor(x); }, h, "phi_r");
      expect_slope([&](double x) { return f.shear_flow_factor(x); }, h, "phi_s");
      expect_slope([&](double x) { return f.expected_gap(x); }, h, "h_T");
      expect_slope([&](double x) { return f.shear_stress_factors(x).phi_f; }, h, "phi_f");
      expect_slope([&](double x) { return f.shear_stress_factors(x).phi_fs; }, h, "phi_fs");
      expect_slope([&](double x) { return f.shear_stress_factors(x).phi_fp; }, h, "phi_fp");
    }
  }
  // phi_f's low-H branch, where the log cut-off matters.
  for (const double H : {0.6, 1.1, 2.7})
  {
    const double dH = 1e-6;
    EXPECT_NEAR(patir_cheng::couette_shear_factor(H).d_dh,
                (patir_cheng::couette_shear_factor(H + dH).value -
                 patir_cheng::couette_shear_factor(H - dH).value) /
                    (2 * dH),
                1e-7);
  }
}

// ---------------------------------------------------------------------------------------------
// Validity limits: clamp, count, warn once

TEST(Validity, BelowTheFitsValuesAreHeldAndCounted)
{
  FlowFactors::rearm_clamp_warning();
  const FlowFactors f = rough(1. / 9., 1.);
  EXPECT_EQ(f.clamp_count(), 0u);

  // gamma = 1/9: phi_theta = phi_x(1/9) holds for H > 1, phi_r = phi_x(9) for H > 0.5.
  testing::internal::CaptureStderr();
  const ValueAndSlope theta = f.circumferential_pressure_flow_factor(0.8 * sigma);
  const std::string first_warning = testing::internal::GetCapturedStderr();
  EXPECT_DOUBLE_EQ(theta.value, patir_cheng::pressure_flow_factor(1., 1. / 9.).value);
  EXPECT_EQ(theta.d_dh, 0.);
  EXPECT_EQ(f.clamp_count(), 1u);
  EXPECT_NE(first_warning.find("validity"), std::string::npos) << first_warning;

  const ValueAndSlope radial = f.radial_pressure_flow_factor(0.8 * sigma);
  EXPECT_DOUBLE_EQ(radial.value, patir_cheng::pressure_flow_factor(0.8, 9.).value);
  EXPECT_EQ(f.clamp_count(), 1u);

  // Shear fits hold for H > 0.5; h <= 0 is clamped, not NaN.
  testing::internal::CaptureStderr();
  const ValueAndSlope s = f.shear_flow_factor(0.2 * sigma);
  const FlowFactors::ShearStressFactors t = f.shear_stress_factors(-1e-7);
  const ValueAndSlope theta_negative = f.circumferential_pressure_flow_factor(-2 * sigma);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), ""); // warned once per run only
  EXPECT_DOUBLE_EQ(s.value, patir_cheng::shear_flow_factor(0.5, 1. / 9.).value);
  EXPECT_TRUE(std::isfinite(t.phi_f.value) && std::isfinite(t.phi_fs.value) &&
              std::isfinite(t.phi_fp.value));
  EXPECT_TRUE(std::isfinite(theta_negative.value));
  EXPECT_EQ(f.clamp_count(), 4u);
  EXPECT_DOUBLE_EQ(f.lowest_clamped_film_parameter(), -2.);

  f.reset_clamp_record();
  EXPECT_EQ(f.clamp_count(), 0u);
  // The expected gap is closed-form for every h: never clamped.
  f.expected_gap(-3 * sigma);
  EXPECT_EQ(f.clamp_count(), 0u);
}

// ---------------------------------------------------------------------------------------------
// Parameters

TEST(Parameters, DefaultsParseAndBadInputIsRefused)
{
  dealii::ParameterHandler prm;
  FlowFactors::declare_parameters(prm);
  FlowFactors f;
  f.parse_parameters(prm);
  EXPECT_TRUE(f.is_smooth());
  EXPECT_DOUBLE_EQ(f.composite_roughness(), 1e-7);
  EXPECT_DOUBLE_EQ(f.surface_pattern(), 1.);
  EXPECT_DOUBLE_EQ(f.rotor_roughness_share(), 0.5);

  prm.parse_input_from_string("subsection Roughness\n set Model = patir-cheng\n"
                              " set Composite roughness = 2e-7\n set Surface pattern = 0.1111\n"
                              " set Rotor roughness share = 0.8\nend\n");
  f.parse_parameters(prm);
  EXPECT_FALSE(f.is_smooth());
  EXPECT_DOUBLE_EQ(f.film_parameter(4e-7), 2.);
  // 0.1111 is 1/9 as typed: accepted and evaluated as 1/9.
  EXPECT_NEAR(f.radial_pressure_flow_factor(4e-7).value,
              patir_cheng::pressure_flow_factor(2., 9.).value, 1e-12);

  prm.parse_input_from_string("subsection Roughness\n set Surface pattern = 12\nend\n");
  EXPECT_THROW(f.parse_parameters(prm), std::runtime_error);
  prm.parse_input_from_string("subsection Roughness\n set Surface pattern = 1\n"
                              " set Composite roughness = 0\nend\n");
  EXPECT_THROW(f.parse_parameters(prm), std::runtime_error);
}
