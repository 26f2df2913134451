// Validation of the annular-seal model against Fleming (NASA TM X-73654): closed form against a
// direct integration of the pressure, the paper's printed numbers and claims, and the run.
#include <sealfe/annular/annular_seal.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

using namespace sealfe::annular;

namespace
{
constexpr double pi = 3.14159265358979323846;

// ------------------------------------------------------------------------------------------------
// An independent implementation of Fleming's Eq. 5/8 for one angle theta, written from the paper
// and sharing no code with the module: the gap h(z) = C(z) + delta (delta = e cos(theta)), the
// friction integral I_z = int_0^z f(h)/h^3 dz by 3-point Gauss per cell, the pressure
//   p - p0 = -(p0 - pL) N(z) / N(L),  N(z) = xi/(2 h(0)^2) + 1/(2 h(z)^2) + I_z,
// and J = int_0^L (p - p0) dz by Simpson's rule on each piece where h is smooth.
struct DirectSeal
{
  Geometry geometry = Geometry::tapered;
  double D = 0.076, L = 0.043, C2 = 1.3e-4, H = 2, gamma = 0.7;
  double f2 = 0.007; // Fanning friction factor at h = C2
  double s = 0;      // f(h) = f2 (h/C2)^-s
  double xi = 0;     // entrance loss
  double dp = 136e5; // p0 - pL
  double rho = 71;
};

struct LineResult
{
  double J;  // int_0^L (p - p0) dz, Pa m
  double NL; // N(L), 1/m^2: m^2 = rho dp / N(L) (Eq. 7)
};

LineResult pressure_line(const DirectSeal &s, double delta)
{
  const double C1 = s.geometry == Geometry::straight ? s.C2 : s.H * s.C2;
  struct Piece
  {
    double z0, z1;
    std::function<double(double)> h;
  };
  std::vector<Piece> pieces;
  if (s.geometry == Geometry::stepped)
  {
    const double L1 = s.gamma * s.L;
    pieces.push_back({0, L1, [=](double) { return C1 + delta; }});
    if (s.gamma < 1)
      pieces.push_back({L1, s.L, [=](double) { return s.C2 + delta; }});
  }
  else
  {
    const double alpha = (C1 - s.C2) / s.L;
    pieces.push_back({0, s.L, [=](double z) { return C1 - alpha * z + delta; }});
  }
  const auto friction = [&](double h) { return s.f2 * std::pow(h / s.C2, -s.s) / (h * h * h); };
  const double h0 = pieces.front().h(0);
  const double entrance = s.xi / (2 * h0 * h0);
  const unsigned int n = 2000; // cells per piece (even, for Simpson)
  const double gx[3] = {-std::sqrt(0.6), 0, std::sqrt(0.6)}, gw[3] = {5. / 9, 8. / 9, 5. / 9};

  std::vector<std::vector<double>> N(pieces.size());
  double I = 0;
  for (std::size_t k = 0; k < pieces.size(); ++k)
  {
    const Piece &p = pieces[k];
    const double dz = (p.z1 - p.z0) / n;
    for (unsigned int i = 0; i <= n; ++i)
    {
      const double z = p.z0 + i * dz;
      if (i > 0)
        for (int q = 0; q < 3; ++q)
          I += 0.5 * dz * gw[q] * friction(p.h(z - 0.5 * dz + 0.5 * dz * gx[q]));
      const double h = p.h(z);
      N[k].push_back(entrance + 1 / (2 * h * h) + I);
    }
  }
  // exit: the outlet clearance is C2 (for gamma = 1 an orifice at z = L)
  const double hL = s.C2 + delta;
  const double NL =
      N.back().back() - 1 / (2 * std::pow(pieces.back().h(s.L), 2)) + 1 / (2 * hL * hL);
  double J = 0;
  for (std::size_t k = 0; k < pieces.size(); ++k)
  {
    const double dz = (pieces[k].z1 - pieces[k].z0) / n;
    double sum = N[k][0] + N[k][n];
    for (unsigned int i = 1; i < n; ++i)
      sum += (i % 2 ? 4 : 2) * N[k][i];
    J -= s.dp * sum * dz / 3 / NL;
  }
  return {J, NL};
}

/// Eq. 9: F = -(D/2) int int p cos(theta) dz dtheta for h = C(z) + e cos(theta); the theta
/// integral by the trapezoidal rule, spectrally accurate for this smooth periodic integrand.
double restoring_force(const DirectSeal &s, double e)
{
  const unsigned int n_theta = 64;
  double F = 0;
  for (unsigned int k = 0; k < n_theta; ++k)
  {
    const double theta = 2 * pi * k / n_theta;
    F += pressure_line(s, e * std::cos(theta)).J * std::cos(theta);
  }
  return -0.5 * s.D * F * 2 * pi / n_theta;
}

DimensionlessSeal dimensionless(const DirectSeal &s)
{
  DimensionlessSeal d;
  d.geometry = s.geometry;
  d.clearance_ratio = s.H;
  d.step_ratio = s.gamma;
  d.lambda = s.f2 * s.L / s.C2;
  d.entrance_loss = s.xi;
  d.friction_exponent = s.s;
  return d;
}

/// K = lim F/e by F(e)/e at eps = e/C2 = 1e-3. F is odd in e, so F/e = K + c e^2 + O(e^4): the
/// truncation is estimated by Richardson from e and e/2, (4/3)|K(e) - K(e/2)|. The tolerance is
/// twice that, plus 1e-8 K for the z- and theta-quadrature and rounding (amplified by 1/eps).
void expect_stiffness_matches_direct_integration(const DirectSeal &s, double K_model)
{
  const double e = 1e-3 * s.C2;
  const double K_e = restoring_force(s, e) / e, K_half = restoring_force(s, 0.5 * e) / (0.5 * e);
  const double truncation = 4.0 / 3.0 * std::abs(K_e - K_half);
  const double tolerance = 2 * truncation + 1e-8 * std::abs(K_model);
  EXPECT_NEAR(K_e, K_model, tolerance)
      << "truncation estimate " << truncation << ", relative " << truncation / K_model;
  // the estimate itself must reflect an O(eps^2) error, not a model difference
  EXPECT_LT(truncation, 1e-4 * std::abs(K_model));
}

double stiffness_from_dimensionless(const DirectSeal &s, double Kbar)
{
  return Kbar * s.dp * s.L * s.D / s.C2; // Eq. 17
}

std::vector<double> lambda_range(double lo, double hi, unsigned int n)
{
  std::vector<double> v;
  for (unsigned int i = 0; i < n; ++i)
    v.push_back(lo * std::pow(hi / lo, static_cast<double>(i) / (n - 1)));
  return v;
}

DimensionlessSeal seal_with_lambda(Geometry g, double lambda)
{
  DimensionlessSeal d;
  d.geometry = g;
  d.lambda = lambda;
  return d;
}
} // namespace

// ---------------------------------------------------------------------------------------------
// The closed form against a direct numerical integration of the pressure.

TEST(AnnularSeal, ClosedFormEqualsDirectPressureIntegration)
{
  for (const Geometry g : {Geometry::straight, Geometry::tapered, Geometry::stepped})
    for (const double H : {1.0, 1.59, 3.0})
      for (const double gamma : {0.3, 0.7, 1.0})
      {
        if (g != Geometry::stepped && gamma != 0.7)
          continue;
        if (g == Geometry::straight && H != 1.0)
          continue;
        DirectSeal s;
        s.geometry = g;
        s.H = H;
        s.gamma = gamma;
        SCOPED_TRACE(to_string(g) + " H = " + std::to_string(H) +
                     " gamma = " + std::to_string(gamma));
        const auto closed = fleming_closed_form(g, H, gamma, s.f2 * s.L / s.C2);
        expect_stiffness_matches_direct_integration(
            s, stiffness_from_dimensionless(s, closed.stiffness));
        // leakage: M = pi D m (Eq. 19) with m^2 from Eq. 7, against Eq. 20
        const double M = pi * s.D * std::sqrt(s.rho * s.dp / pressure_line(s, 0).NL);
        EXPECT_NEAR(closed.leakage * pi * s.D * s.C2 * std::sqrt(s.dp * s.rho), M, 1e-10 * M);
      }
}

TEST(AnnularSeal, GeneralModelEqualsDirectIntegrationWithEntranceLossAndRoughFriction)
{
  // the two generalisations beyond the paper: entrance loss xi and local fully rough friction
  for (const Geometry g : {Geometry::straight, Geometry::tapered, Geometry::stepped})
  {
    DirectSeal s;
    s.geometry = g;
    s.H = 1.8;
    s.gamma = 0.6;
    s.xi = 0.5;
    s.s = fully_rough_friction_exponent;
    SCOPED_TRACE(to_string(g));
    const auto c = dimensionless_coefficients(dimensionless(s));
    expect_stiffness_matches_direct_integration(s, stiffness_from_dimensionless(s, c.stiffness));
    const double M = pi * s.D * std::sqrt(s.rho * s.dp / pressure_line(s, 0).NL);
    EXPECT_NEAR(c.leakage * pi * s.D * s.C2 * std::sqrt(s.dp * s.rho), M, 1e-10 * M);
  }
}

TEST(AnnularSeal, GeneralModelReducesToPaperClosedForm)
{
  // quadrature of Eq. 5 and its exact eccentricity derivative against Eq. 15-17, 20 as printed
  for (const Geometry g : {Geometry::straight, Geometry::tapered, Geometry::stepped})
    for (const double H : {1.0, 1.3, 2.0, 5.0, 10.0})
      for (const double gamma : {0.05, 0.5, 0.9, 1.0})
        for (const double lambda : {1e-4, 0.1, 2.4, 50.0})
        {
          DimensionlessSeal d;
          d.geometry = g;
          d.clearance_ratio = H;
          d.step_ratio = gamma;
          d.lambda = lambda;
          const auto general = dimensionless_coefficients(d);
          const auto closed = fleming_closed_form(g, H, gamma, lambda);
          // Kbar is a difference of O(1) terms: rounding 1e-14 absolute
          EXPECT_NEAR(general.stiffness, closed.stiffness,
                      1e-12 * std::abs(closed.stiffness) + 1e-14)
              << to_string(g) << " H " << H << " gamma " << gamma << " Lambda " << lambda;
          EXPECT_NEAR(general.leakage, closed.leakage, 1e-13 * closed.leakage);
        }
}

TEST(AnnularSeal, StraightSealIsBlacksResult)
{
  // Eq. 16 with H = 1 "agrees with the results of reference 1" (Black): with Fleming's
  // assumptions Kbar = pi Lambda / (2 (1 + 2 Lambda)^2), Mbar = sqrt(2 / (1 + 2 Lambda)).
  for (const double lambda : {0.01, 0.5, 2.4, 30.0})
  {
    const auto c = fleming_closed_form(Geometry::straight, 1, 1, lambda);
    EXPECT_NEAR(c.stiffness, pi * lambda / (2 * std::pow(1 + 2 * lambda, 2)), 1e-14);
    EXPECT_NEAR(c.leakage, std::sqrt(2 / (1 + 2 * lambda)), 1e-14);
  }
}

// Straight seals with the two generalisations: n = int Nhat = u + v/2, d = Nhat(1) = u + v
// (the gap is eta everywhere), so d(n/d)/deta = (u' v - u v') / (2 (u + v)^2).

TEST(AnnularSeal, StraightSealWithLocalRoughFriction)
{
  // f(h) = f2 (h/C2)^-s around the eccentric gap: u = 1/(2 eta^2), v = Lambda eta^-(3+s),
  // u' v - u v' = (1 + s) u v / eta, so Kbar = pi (1 + s) Lambda / (2 (1 + 2 Lambda)^2): Black's
  // result times 1 + s. The concentric leakage is unchanged (f = f2 at h = C2).
  const double s = fully_rough_friction_exponent;
  for (const double lambda : {0.05, 2.4, 30.0})
  {
    DimensionlessSeal d;
    d.geometry = Geometry::straight;
    d.lambda = lambda;
    d.friction_exponent = s;
    const auto c = dimensionless_coefficients(d);
    EXPECT_NEAR(c.stiffness, pi * (1 + s) * lambda / (2 * std::pow(1 + 2 * lambda, 2)), 1e-14);
    EXPECT_NEAR(c.leakage, std::sqrt(2 / (1 + 2 * lambda)), 1e-14);
  }
}

TEST(AnnularSeal, StraightSealWithEntranceLoss)
{
  // entrance loss xi: u = (1 + xi)/(2 eta^2), v = Lambda / eta^3, u' v - u v' = u v / eta, so
  // Kbar = pi (1 + xi) Lambda / (2 (1 + xi + 2 Lambda)^2) and Mbar = sqrt(2 / (1 + xi + 2 Lambda)).
  for (const double xi : {0.0, 0.3, 1.0})
    for (const double lambda : {0.1, 2.4})
    {
      DimensionlessSeal d;
      d.geometry = Geometry::straight;
      d.lambda = lambda;
      d.entrance_loss = xi;
      const auto c = dimensionless_coefficients(d);
      EXPECT_NEAR(c.stiffness, pi * (1 + xi) * lambda / (2 * std::pow(1 + xi + 2 * lambda, 2)),
                  1e-14);
      EXPECT_NEAR(c.leakage, std::sqrt(2 / (1 + xi + 2 * lambda)), 1e-14);
    }
}

// ---------------------------------------------------------------------------------------------
// The concentric pressure profile against Eq. 8 and Eq. 11 (with the OCR typo p_1 -> p_L in 11b).

TEST(AnnularSeal, PressureProfileIntegratesToEquation11)
{
  const double dp = 1, L = 1, C2 = 1, f = 0.02, lambda = f * L / C2;
  for (const Geometry g : {Geometry::tapered, Geometry::stepped})
  {
    DimensionlessSeal d;
    d.geometry = g;
    d.clearance_ratio = 1.7;
    d.step_ratio = 0.7;
    d.lambda = lambda;
    const auto profile = pressure_profile(d, 20001);
    // J = int (p - p0) dz by the trapezoidal rule: error <= Delta^2 L max|p''| / 12 ~ 1e-9 here
    double J = 0;
    for (std::size_t i = 1; i < profile.size(); ++i)
      J -= 0.5 * (profile[i].pressure_drop_fraction + profile[i - 1].pressure_drop_fraction) *
           (profile[i].axial_ratio - profile[i - 1].axial_ratio) * dp * L;
    const double h1 = d.clearance_ratio * C2, h2 = C2;
    double J_paper;
    if (g == Geometry::tapered)
    {
      const double alpha = (h1 - h2) / L; // Eq. 11a
      J_paper = dp / ((alpha + f) * h1 * h1 - f * h2 * h2) *
                ((1 + f / alpha) * h1 * h2 * (h2 - h1) + f * L * h2 * h2);
    }
    else
    {
      const double L1 = d.step_ratio * L, L2 = L - L1; // Eq. 11b
      J_paper = -dp *
                (h1 * std::pow(h2, 3) * L1 + f * std::pow(h2, 3) * L1 * (L1 + 2 * L2) +
                 std::pow(h1, 3) * h2 * L2 + f * std::pow(h1, 3) * L2 * L2) /
                (std::pow(h1, 3) * h2 + 2 * f * (std::pow(h2, 3) * L1 + std::pow(h1, 3) * L2));
    }
    EXPECT_NEAR(J, J_paper, 1e-7 * std::abs(J_paper)) << to_string(g);
    // and Eq. 12 at eps = 0: J = -(p0 - pL) L A / E
    const auto c = fleming_coefficients(g, d.clearance_ratio, d.step_ratio, lambda);
    EXPECT_NEAR(J_paper, -dp * L * c.A / c.E, 1e-12);
  }
}

TEST(AnnularSeal, PressureProfileEndsAndStepJump)
{
  DimensionlessSeal d;
  d.geometry = Geometry::stepped;
  d.clearance_ratio = 1.59;
  d.step_ratio = 0.7;
  d.lambda = 2.4;
  d.entrance_loss = 0.3;
  const auto profile = pressure_profile(d, 101);
  const double H = d.clearance_ratio;
  // Eq. 7 with the entrance loss: m^2 / (rho dp) C2^2 = 1 / N(L)
  const double NL = d.entrance_loss / (2 * H * H) + 0.5 +
                    d.lambda * (d.step_ratio / std::pow(H, 3) + (1 - d.step_ratio));
  // inlet: (p0 - p)/dp = (1 + xi) rho V1^2 / 2 / dp
  EXPECT_NEAR(profile.front().pressure_drop_fraction, (1 + d.entrance_loss) / (2 * H * H) / NL,
              1e-14);
  EXPECT_NEAR(profile.back().pressure_drop_fraction, 1.0, 1e-14);
  // the step: two points at z = gamma L, the drop between them the Bernoulli term
  // (1/2 - 1/(2 H^2)) / N(L) (Eq. 4 at the step)
  int steps = 0;
  for (std::size_t i = 1; i < profile.size(); ++i)
  {
    EXPECT_GE(profile[i].pressure_drop_fraction, profile[i - 1].pressure_drop_fraction);
    if (profile[i].axial_ratio == profile[i - 1].axial_ratio)
    {
      ++steps;
      EXPECT_NEAR(profile[i].axial_ratio, d.step_ratio, 1e-15);
      EXPECT_NEAR(profile[i].pressure_drop_fraction - profile[i - 1].pressure_drop_fraction,
                  (0.5 - 1 / (2 * H * H)) / NL, 1e-14);
    }
  }
  EXPECT_EQ(steps, 1);
}

// ---------------------------------------------------------------------------------------------
// The paper's numbers (tolerance: half a unit of the last printed digit).

TEST(AnnularSeal, PaperStraightSealAtLambda2p4)
{
  // "From figure 6 for a smooth seal, Kbar = 0.11" at Lambda = 2.4
  EXPECT_NEAR(fleming_closed_form(Geometry::straight, 1, 1, 2.4).stiffness, 0.11, 0.005);
}

TEST(AnnularSeal, PaperOptimumStepSealForStiffnessPerLeakageAtLambda2p4)
{
  // "From figure 3, the optimum clearance ratio is H = 1.59. From figure 4, the optimum step
  // length is gamma = 0.70. Figure 6 shows the stiffness Kbar to be 0.29, or nearly three times
  // the stiffness of the straight seal." Both with gamma free and with gamma <= 0.8.
  for (const double gamma_max : {1.0, 0.8})
  {
    OptimisationBounds b;
    b.step_ratio_max = gamma_max;
    const Optimum o =
        optimise(seal_with_lambda(Geometry::stepped, 2.4), Objective::stiffness_per_leakage, b);
    EXPECT_NEAR(o.clearance_ratio, 1.59, 0.005);
    EXPECT_NEAR(o.step_ratio, 0.70, 0.005);
    EXPECT_NEAR(o.coefficients.stiffness, 0.29, 0.005);
    const double ratio =
        o.coefficients.stiffness / fleming_closed_form(Geometry::straight, 1, 1, 2.4).stiffness;
    EXPECT_GT(ratio, 2.5); // "nearly three times"
    EXPECT_LT(ratio, 3.0);
    EXPECT_FALSE(o.step_ratio_at_bound);
  }
}

TEST(AnnularSeal, OptimumClearanceRatioForShortSeals)
{
  // "as seal length approaches zero, the optimum clearance ratio approaches 2 for the tapered
  // seal and 1.5 for the stepped seal. The same value of H maximizes both K and K/M." At
  // Lambda = 0, Eq. 17 gives Kbar = pi (H - 1) / (2 H^2) (tapered) and pi gamma (H - 1) / H^3
  // (stepped), maximal at H = 2 (pi/8) and H = 1.5, gamma = 1 (4 pi / 27); Mbar = sqrt(2) does not
  // depend on H. The optimum moves by O(Lambda): at Lambda = 1e-6 the tolerance 1e-4 allows an
  // O(1) coefficient a hundredfold.
  const double lambda = 1e-6;
  for (const Objective obj : {Objective::stiffness, Objective::stiffness_per_leakage})
  {
    const Optimum t = optimise(seal_with_lambda(Geometry::tapered, lambda), obj);
    EXPECT_NEAR(t.clearance_ratio, 2.0, 1e-4);
    EXPECT_NEAR(t.coefficients.stiffness, pi / 8, 1e-4);
    const Optimum s = optimise(seal_with_lambda(Geometry::stepped, lambda), obj,
                               OptimisationBounds{10, 1e-3, 1.0});
    EXPECT_NEAR(s.clearance_ratio, 1.5, 1e-4);
    EXPECT_NEAR(s.step_ratio, 1.0, 1e-4);
    EXPECT_NEAR(s.coefficients.stiffness, 4 * pi / 27, 1e-4);
    // with gamma <= 0.8 the optimum H is still 1.5 (Kbar is proportional to gamma)
    const Optimum s8 = optimise(seal_with_lambda(Geometry::stepped, lambda), obj,
                                OptimisationBounds{10, 1e-3, 0.8});
    EXPECT_NEAR(s8.clearance_ratio, 1.5, 1e-4);
    EXPECT_NEAR(s8.step_ratio, 0.8, 1e-4);
  }
}

TEST(AnnularSeal, PaperClaimsOverTheRangeOfSealLengths)
{
  // The paper's range of Lambda is not printed; 0.1 <= Lambda <= 20 is consistent with all its
  // statements (optimum gamma = 1 at the short end; "1.7 to 14 times" and "approximately 60
  // percent" more flow at the long end).
  double min_tapered_ratio = 1e9, min_stepped_ratio = 1e9, max_leakage_ratio = 0;
  for (const double lambda : lambda_range(0.1, 20, 31))
  {
    SCOPED_TRACE("Lambda = " + std::to_string(lambda));
    const double K_straight = fleming_closed_form(Geometry::straight, 1, 1, lambda).stiffness;
    const double M_straight = fleming_closed_form(Geometry::straight, 1, 1, lambda).leakage;
    const Optimum tK = optimise(seal_with_lambda(Geometry::tapered, lambda), Objective::stiffness);
    const Optimum tKM =
        optimise(seal_with_lambda(Geometry::tapered, lambda), Objective::stiffness_per_leakage);
    const OptimisationBounds free{10, 1e-3, 1.0};
    const Optimum sK =
        optimise(seal_with_lambda(Geometry::stepped, lambda), Objective::stiffness, free);
    const Optimum sKM = optimise(seal_with_lambda(Geometry::stepped, lambda),
                                 Objective::stiffness_per_leakage, free);
    // Fig. 5: "the optimum seal stiffness is always at least 70 percent greater than that of a
    // straight seal"
    EXPECT_GE(tK.coefficients.stiffness / K_straight, 1.70);
    min_tapered_ratio = std::min(min_tapered_ratio, tK.coefficients.stiffness / K_straight);
    min_stepped_ratio = std::min(min_stepped_ratio, sKM.coefficients.stiffness / K_straight);
    max_leakage_ratio = std::max(max_leakage_ratio, tKM.coefficients.leakage / M_straight);
    // "For both seals, the optimum clearance ratio is higher for maximum K than for maximum K/M"
    EXPECT_GT(tK.clearance_ratio, tKM.clearance_ratio);
    EXPECT_GT(sK.clearance_ratio, sKM.clearance_ratio);
    // "the optimum stepped seal is always stiffer than the optimum tapered seal, if the step
    // length is allowed to vary freely"
    EXPECT_GT(sK.coefficients.stiffness, tK.coefficients.stiffness);
    // "The latter optimization yielded stiffnesses only slightly lower than maximum, while
    // reducing the leakage flow"
    EXPECT_LT(tKM.coefficients.leakage, tK.coefficients.leakage);
    EXPECT_LT(sKM.coefficients.leakage, sK.coefficients.leakage);
    // "with gamma limited to 0.8 [this] became the optimum value for the entire range ... when
    // maximizing K"
    const Optimum s8K = optimise(seal_with_lambda(Geometry::stepped, lambda), Objective::stiffness,
                                 OptimisationBounds{10, 1e-3, 0.8});
    EXPECT_TRUE(s8K.step_ratio_at_bound);
  }
  // "The stiffness of a stepped seal varies from 1.7 to 14 times that of a similarly dimensioned
  // straight seal": the smallest ratio (near Lambda = 0.6) is 1.7 to the printed digit
  EXPECT_GE(min_stepped_ratio, 1.7);
  EXPECT_LT(min_stepped_ratio, 1.8);
  EXPECT_LT(min_tapered_ratio, 1.8); // the 70 % bound is nearly reached, not loose
  // "reaches approximately 60 percent for the longest seals investigated"
  EXPECT_NEAR(max_leakage_ratio, 1.6, 0.05);
  const Optimum sKM20 = optimise(seal_with_lambda(Geometry::stepped, 20),
                                 Objective::stiffness_per_leakage, OptimisationBounds{10, 1e-3, 1});
  EXPECT_NEAR(sKM20.coefficients.stiffness /
                  fleming_closed_form(Geometry::straight, 1, 1, 20).stiffness,
              14, 0.5);
}

TEST(AnnularSeal, PaperStepLengthRegimes)
{
  const OptimisationBounds free{10, 1e-3, 1.0}, bounded{10, 1e-3, 0.8};
  // "The optimum step length became 1 for low seal lengths."
  for (const Objective obj : {Objective::stiffness, Objective::stiffness_per_leakage})
    EXPECT_NEAR(optimise(seal_with_lambda(Geometry::stepped, 0.1), obj, free).step_ratio, 1.0,
                1e-6);
  // "for maximum K/M, gamma = 0.8 is optimum only up to Lambda = 0.6" (printed to 0.05)
  EXPECT_TRUE(
      optimise(seal_with_lambda(Geometry::stepped, 0.55), Objective::stiffness_per_leakage, bounded)
          .step_ratio_at_bound);
  EXPECT_FALSE(
      optimise(seal_with_lambda(Geometry::stepped, 0.65), Objective::stiffness_per_leakage, bounded)
          .step_ratio_at_bound);
  // "When the step length is restricted to a maximum of 0.3 [0.8: OCR typo], the optimum tapered
  // seal is stiffer for seal length Lambda < 0.5" (printed to 0.05)
  const auto tapered_minus_stepped = [&](double lambda)
  {
    return optimise(seal_with_lambda(Geometry::tapered, lambda), Objective::stiffness)
               .coefficients.stiffness -
           optimise(seal_with_lambda(Geometry::stepped, lambda), Objective::stiffness, bounded)
               .coefficients.stiffness;
  };
  EXPECT_GT(tapered_minus_stepped(0.45), 0);
  EXPECT_LT(tapered_minus_stepped(0.55), 0);
}

TEST(AnnularSeal, OptimiserFindsTheGlobalMaximum)
{
  // brute force on a fine grid of the paper's closed form, in and around the cusp region where
  // the gamma = 1 and interior regimes compete
  for (const double lambda : {0.3, 0.45, 0.6, 2.4, 10.0})
    for (const Objective obj : {Objective::stiffness, Objective::stiffness_per_leakage})
    {
      double best = 0;
      for (double H = 1; H <= 5; H += 0.005)
        for (double g = 0.002; g <= 1.0 + 1e-12; g += 0.002)
        {
          const auto c = fleming_closed_form(Geometry::stepped, H, std::min(g, 1.0), lambda);
          best =
              std::max(best, obj == Objective::stiffness ? c.stiffness : c.stiffness / c.leakage);
        }
      const Optimum o = optimise(seal_with_lambda(Geometry::stepped, lambda), obj,
                                 OptimisationBounds{10, 1e-3, 1.0});
      const double value = obj == Objective::stiffness
                               ? o.coefficients.stiffness
                               : o.coefficients.stiffness / o.coefficients.leakage;
      EXPECT_GE(value, best * (1 - 1e-12)) << "Lambda " << lambda << " " << to_string(obj);
      // and it is not far above the grid (grid spacing 0.005: second-order loss only)
      EXPECT_LT(value, best * (1 + 1e-3));
    }
}

// ---------------------------------------------------------------------------------------------
// Friction factor from roughness.

TEST(AnnularSeal, FullyRoughFrictionFactor)
{
  // "the relative roughness d/e_r is 300 and the friction factor 0.007"
  EXPECT_NEAR(fully_rough_friction_factor(1.0 / 300), 0.007, 0.0005);
  EXPECT_NEAR(von_karman_friction_factor(1.0 / 300), 0.007, 0.0005);
  // "a good approximation" of 1/sqrt(f) = 4 log10(d/e_r) + 2.28: within 3 % for d/e_r in
  // [100, 1000] (our reading of "good")
  for (double r = 100; r <= 1000; r *= 1.1)
    EXPECT_NEAR(fully_rough_friction_factor(1 / r) / von_karman_friction_factor(1 / r), 1, 0.03)
        << "d/e_r = " << r;
  // the exponent: "f2 = f1 H^0.29"
  EXPECT_NEAR(fully_rough_friction_factor(1.0 / 150) / fully_rough_friction_factor(1.0 / 300),
              std::pow(2.0, 0.29), 1e-14);
}

// ---------------------------------------------------------------------------------------------
// The sub-command.

namespace
{
std::string temporary_directory(const std::string &name)
{
  const auto dir = std::filesystem::temp_directory_path() / ("sealfe_annular_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}
} // namespace

TEST(AnnularSeal, RunDefaultsAreTheExampleSeal)
{
  dealii::ParameterHandler prm;
  declare_parameters(prm);
  const std::string dir = temporary_directory("defaults");
  prm.enter_subsection("Annular seal");
  prm.enter_subsection("Lambda sweep");
  prm.set("Points", "0");
  prm.leave_subsection();
  prm.leave_subsection();
  const nlohmann::json j = run(prm, dir);
  for (const char *key : {"stiffness", "stiffness_dimensionless", "leakage",
                          "leakage_dimensionless", "clearance_ratio", "step_ratio", "lambda"})
    EXPECT_TRUE(j.contains(key)) << key;
  // the SSME HPFTP seal: D = 76 mm, L = 43 mm, C2 = 0.13 mm, f = 0.007, 136 bar; H = 1.59,
  // gamma = 0.70
  const double lambda = 0.007 * 0.043 / 1.3e-4;
  EXPECT_NEAR(j["lambda"].get<double>(), lambda, 1e-12);
  const auto c = fleming_closed_form(Geometry::stepped, 1.59, 0.70, lambda);
  EXPECT_NEAR(j["stiffness_dimensionless"].get<double>(), c.stiffness, 1e-12);
  EXPECT_NEAR(j["stiffness"].get<double>(), c.stiffness * 136e5 * 0.043 * 0.076 / 1.3e-4,
              1e-9 * j["stiffness"].get<double>());
  EXPECT_NEAR(j["leakage"].get<double>(), c.leakage * pi * 0.076 * 1.3e-4 * std::sqrt(136e5 * 71),
              1e-12 * j["leakage"].get<double>());
  EXPECT_TRUE(std::filesystem::exists(dir + "/annular_pressure_profile.csv"));
}

TEST(AnnularSeal, RunOptimisesThePaperExample)
{
  dealii::ParameterHandler prm;
  declare_parameters(prm);
  const std::string dir = temporary_directory("optimise");
  prm.enter_subsection("Annular seal");
  std::ostringstream f;
  f << std::setprecision(17) << 2.4 * 1.3e-4 / 0.043; // Lambda = 2.4
  prm.set("Friction factor", f.str());
  prm.set("Optimise", "stiffness per leakage");
  prm.set("Clearance ratio", "");
  prm.enter_subsection("Lambda sweep");
  prm.set("Values", "0.5, 2.4");
  prm.leave_subsection();
  prm.leave_subsection();
  const nlohmann::json j = run(prm, dir);
  EXPECT_NEAR(j["lambda"].get<double>(), 2.4, 1e-9);
  EXPECT_NEAR(j["clearance_ratio"].get<double>(), 1.59, 0.005);
  EXPECT_NEAR(j["step_ratio"].get<double>(), 0.70, 0.005);
  EXPECT_NEAR(j["stiffness_dimensionless"].get<double>(), 0.29, 0.005);
  EXPECT_NEAR(j["inlet_clearance"].get<double>(), j["clearance_ratio"].get<double>() * 1.3e-4,
              1e-15);
  // the sweep: per Lambda one straight row, and for K and K/M one tapered and two stepped rows
  // (gamma free and gamma <= 0.8)
  std::ifstream csv(dir + "/annular_lambda_sweep.csv");
  ASSERT_TRUE(csv.good());
  std::string line;
  int rows = -1;
  while (std::getline(csv, line))
    ++rows;
  EXPECT_EQ(rows, 2 * (1 + 2 * 3));
}
