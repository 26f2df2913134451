// Validation of the GW/CEB asperity contact model in the closed form of Green (2002): the exact
// plastic integral (Eq. 8/9) and the mean-value elastic approximation (Eq. 6/7) against direct
// quadrature of Eq. 2a/2b, the printed exponent typos, the Gaussian-tail decay, the paper's "moot
// above h/sigma = 3" argument for its Table 1 seal, derivatives and parameters.
#include <sealfe/film/asperity_contact.h>
#include <sealfe/film/flow_factors.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

using namespace sealfe;

namespace
{
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

double density(const double z, const double s)
{
  return std::exp(-0.5 * z * z / (s * s)) / (std::sqrt(2 * M_PI) * s);
}

/// Eq. 2b by quadrature: Int_{a+w}^inf 2 (z - a - w/2) phi*(z) dz.
double plastic_quadrature(const double a, const double s, const double w)
{
  const double a1 = a + w / 2, a2 = a + w;
  return integrate([=](double z) { return 2 * (z - a1) * density(z, s); }, a2, a2 + 40 * s);
}

/// Eq. 2a by quadrature, with z = a + w t^2 to remove the (z - a)^{3/2} root:
///   I_e = 2 w^{5/2} Int_0^1 t^4 phi*(a + w t^2) dt.
double elastic_quadrature(const double a, const double s, const double w)
{
  return 2 * std::pow(w, 2.5) *
         integrate([=](double t) { return std::pow(t, 4) * density(a + w * t * t, s); }, 0, 1, 20);
}

/// Int_a^{a+w} (z - a) phi*(z) dz by quadrature (elastic contact area, Eq. 7b).
double elastic_area_quadrature(const double a, const double s, const double w)
{
  return integrate([=](double z) { return (z - a) * density(z, s); }, a, a + w, 20);
}

// Green (2002) Table 1.
const AsperityContactParameters table1;
const double omega_c = 1. / (6.6167 * 6.6167); // sigma*_s / Psi^2 with sigma*_s = 1

AsperityContact table1_contact()
{
  return AsperityContact(AsperityContact::Model::gw_ceb, table1);
}
} // namespace

// ---------------------------------------------------------------------------------------------

TEST(Table1, DerivedQuantities)
{
  const AsperityContact c = table1_contact();
  // beta = eta R sigma = 4.16e11 * 1.7e-6 * 1e-7 = 0.07072; omega*_c = 1/6.6167^2 = 0.022841.
  EXPECT_NEAR(c.asperity_parameter(), 0.07072, 1e-12);
  EXPECT_NEAR(c.critical_interference(), 0.0228411, 1e-7);
  // CEB's own definition Psi = (2E/(pi K H)) sqrt(sigma_s/R) gives 25.539 * 0.242536 = 6.1941
  // with sigma_s = sigma, not the printed 6.6167 (which would need sigma_s = 1.141 sigma).
  EXPECT_NEAR(AsperityContact::ceb_plasticity_index(24.07e9, 1e9, 0.6, 1.7e-6, 1e-7), 6.1941, 1e-4);
}

TEST(ClosedForm, PlasticIntegralIsExact)
{
  // Eq. 8 against quadrature of Eq. 2b: exact, so agreement to round-off.
  for (const double s : {0.8, 1.})
    for (const double w : {omega_c, 0.3})
      for (const double a : {-1., 0., 0.5, 1., 2., 3., 4., 5.})
      {
        const double exact = plastic_quadrature(a, s, w);
        const ValueAndSlope I = gw_ceb::plastic_integral(a, s, w);
        EXPECT_NEAR(I.value, exact, 1e-11 * exact + 1e-300) << "a = " << a << ", s = " << s;
        // dI_p/da = -w phi*(a + w) - 2 Int_{a+w}^inf phi*: by quadrature too.
        const double tail =
            integrate([=](double z) { return 2 * density(z, s); }, a + w, a + w + 40 * s);
        EXPECT_NEAR(I.d_dh, -w * density(a + w, s) - tail, 1e-11 * tail);
      }
}

TEST(ClosedForm, PlasticIntegralFollowsTheGaussianTail)
{
  // For large a, with Q(x) = s^2 phi*(x)/x (1 - s^2/x^2 + 3 s^4/x^4 - 15 s^6/x^6 + ...):
  //   I_p = 2 [s^2 phi*(a2) - a1 Q(a2)],
  // truncated after the 15 s^6 term; the error is bounded by the next term, 105 s^8/a2^8.
  const double s = 1., w = omega_c;
  for (const double a : {6., 8., 10.})
  {
    const double a1 = a + w / 2, a2 = a + w, x2 = s * s / (a2 * a2);
    const double series = 1 - x2 + 3 * x2 * x2 - 15 * x2 * x2 * x2;
    const double prefactor = 2 * s * s * density(a2, s);
    const double asymptotic = prefactor * (1 - a1 / a2 * series);
    const double next_term = prefactor * a1 / a2 * 105 * std::pow(x2, 4);
    EXPECT_NEAR(gw_ceb::plastic_integral(a, s, w).value, asymptotic, next_term) << "a = " << a;
  }
}

TEST(ClosedForm, ElasticMeanValueApproximationError)
{
  // Eq. 6 (midpoint value of f(z) = (z - a)^{3/2} phi*(z)) against quadrature of Eq. 2a.
  // Expanding phi* about the midpoint a1 = a + w/2 (t = z - a):
  //   I_e / (phi*(a1) w^{5/2}) = 2/5 - (3/35)(a1/s^2) w + (23/1260)(a1^2/s^4 - 1/s^2) w^2 + O(w^3),
  // while the mean-value form is 2^{-3/2}. So for w -> 0 it is 5/(4 sqrt 2) = 0.8839 of the
  // exact integral (11.6 % low): the midpoint rule on t^{3/2}.
  for (const double s : {0.8, 1.})
    for (const double a : {-0.5, 0., 1., 2., 3., 4.})
    {
      const double w = omega_c, a1 = a + w / 2;
      const double exact = elastic_quadrature(a, s, w);
      const double expansion = 0.4 - 3. / 35. * a1 / (s * s) * w +
                               23. / 1260. * (a1 * a1 / std::pow(s, 4) - 1 / (s * s)) * w * w;
      const double expected_ratio = std::pow(2., -1.5) / expansion;
      const double ratio = gw_ceb::elastic_integral(a, s, w).value / exact;
      EXPECT_NEAR(ratio, expected_ratio, 5e-4) << "a = " << a << ", s = " << s;
    }
  EXPECT_NEAR(gw_ceb::elastic_integral(1., 1., 1e-4).value / elastic_quadrature(1., 1., 1e-4),
              5. / (4. * std::sqrt(2.)), 1e-4);
  // The printed Eq. 6/7a exponent 9/2 would be off by omega_c^2 = 5.2e-4: the quadrature decides
  // for 5/2 (dimensionally: w^{3/2} from (z-a)^{3/2} times the interval length w).
  const double a = 3., w = omega_c;
  const double printed = std::pow(0.5, 1.5) * std::pow(w, 4.5) * density(a + w / 2, 1.);
  EXPECT_LT(printed / elastic_quadrature(a, 1., w), 1e-3);
}

TEST(ClosedForm, ElasticAreaMeanValue)
{
  // Eq. 7b: Int (z-a) phi* dz ~ (w^2/2) phi*(a1). Expanding: exact / phi*(a1) =
  //   w^2/2 - (a1/s^2) w^3/12 + (a1^2/s^4 - 1/s^2) w^4/48 + O(w^5).
  // The printed "phi_c^{*2}/2" is omega_c^{*2}/2 (OCR), exponent 2 confirmed here.
  for (const double s : {0.8, 1.})
    for (const double a : {-0.5, 0., 1., 2., 3., 4.})
    {
      const double w = omega_c, a1 = a + w / 2;
      const double expansion = w * w / 2 - a1 / (s * s) * std::pow(w, 3) / 12 +
                               (a1 * a1 / std::pow(s, 4) - 1 / (s * s)) * std::pow(w, 4) / 48;
      const double ratio =
          gw_ceb::elastic_area_integral(a, s, w) / elastic_area_quadrature(a, s, w);
      EXPECT_NEAR(ratio, w * w / 2 / expansion, 1e-4) << "a = " << a << ", s = " << s;
    }
}

// ---------------------------------------------------------------------------------------------

TEST(ContactPressure, Table1AgainstQuadratureOfEq1)
{
  // p_c(h) for Table 1 against Eq. 1a/1b with quadrature of Eq. 2a/2b: plastic part exact, the
  // elastic part within its mean-value error (ratio 0.884 .. 0.90 here).
  const AsperityContact c = table1_contact();
  const double sigma = 1e-7, beta = 0.07072;
  const double plastic_scale = beta * M_PI * 0.6 * 1e9;
  const double elastic_scale = 4. / 3. * beta * std::sqrt(sigma / 1.7e-6) * 24.07e9;
  for (const double hs : {0.25, 0.5, 1., 2., 3., 3.5, 4., 5.})
  {
    const double h = hs * sigma;
    const double pcp = plastic_scale * plastic_quadrature(hs, 1., omega_c);
    const double pce = elastic_scale * elastic_quadrature(hs, 1., omega_c);
    EXPECT_NEAR(c.plastic_contact_pressure(h).value, pcp, 1e-10 * pcp) << "h* = " << hs;
    const double ratio = c.elastic_contact_pressure(h).value / pce;
    EXPECT_GT(ratio, 0.88);
    EXPECT_LT(ratio, 0.91);
    // With Psi^2 = 43.8 >> 1 the plastic part dominates (Green: "practically p_c = p_cp").
    EXPECT_LT(c.elastic_contact_pressure(h).value, 1e-2 * c.plastic_contact_pressure(h).value);
    EXPECT_DOUBLE_EQ(c.contact_pressure(h).value,
                     c.elastic_contact_pressure(h).value + c.plastic_contact_pressure(h).value);
    // Real contact area: plastic part exact (Eq. 9b = pi beta I_p).
    EXPECT_NEAR(c.plastic_contact_area_fraction(h),
                M_PI * beta * plastic_quadrature(hs, 1., omega_c),
                1e-10 * c.plastic_contact_area_fraction(h));
    EXPECT_NEAR(c.elastic_contact_area_fraction(h),
                M_PI * beta * elastic_area_quadrature(hs, 1., omega_c),
                0.025 * c.elastic_contact_area_fraction(h)); // a1 w/6 <= 0.019 for h* <= 5
  }
}

TEST(ContactPressure, MootAboveThreeSigmaQuantified)
{
  // Green (2002) argues contact is moot once h* > 3. For its Table 1 seal the nominal closing
  // pressure at the operating point (Eq. 22, B = 0.75, po = 500 kPa, pi = 100 kPa, 20 N spring
  // on pi (ro^2 - ri^2) = 1.2704e-3 m^2) is 400 kPa + 15.74 kPa = 415.74 kPa.
  const AsperityContact c = table1_contact();
  const double area = M_PI * (0.0408 * 0.0408 - 0.0355 * 0.0355);
  const double spring_pressure = 20. / area;
  const double p_nominal = 0.75 * 500e3 + 0.25 * 100e3 + spring_pressure;
  EXPECT_NEAR(p_nominal, 415.74e3, 10.);

  const double sigma = 1e-7;
  const double at3 = c.contact_pressure(3 * sigma).value / p_nominal;
  const double at4 = c.contact_pressure(4 * sigma).value / p_nominal;
  RecordProperty("contact_over_closing_at_h3", std::to_string(at3));
  RecordProperty("contact_over_closing_at_h4", std::to_string(at4));
  // Moot at h* = 4 (under 1 % of the closing load) but not yet at h* = 3 (a fifth of it).
  EXPECT_LT(at4, 0.01);
  EXPECT_GT(at3, 0.1);
  // The decay from 3 to 4 sigma is the Gaussian tail's: I_p(a) ~ phi(a2)/a2^2 times slowly varying
  // factors, so p_c(4)/p_c(3) ~ exp(-(a2(4)^2 - a2(3)^2)/2) within a factor (a2(3)/a2(4))^2..1.
  const double tail_ratio = std::exp(-0.5 * (std::pow(4 + omega_c, 2) - std::pow(3 + omega_c, 2)));
  const double ratio = at4 / at3;
  EXPECT_LT(ratio, tail_ratio);
  EXPECT_GT(ratio, tail_ratio * std::pow((3 + omega_c) / (4 + omega_c), 3));
}

TEST(ContactPressure, SpringAloneRestsAtEasyContact)
{
  // Green (2002) starts its seal "from rest at easy contact (h_min/sigma = 0.35 C0/sigma = 3.5)".
  // With Table 1 (sigma_s = sigma, y_s = 0) the contact pressure equals the spring pressure
  // 20 N / 1.2704e-3 m^2 = 15.74 kPa at h* = 3.5 to the paper's two digits. (y_s = 0.65 sigma,
  // the value 0.045944/beta of the McCool-type relations quoted in the later CEB literature --
  // not verified here -- would put it at 4.1; see doc/roughness.md.)
  const AsperityContact c = table1_contact();
  const double sigma = 1e-7;
  const double spring_pressure = 20. / (M_PI * (0.0408 * 0.0408 - 0.0355 * 0.0355));
  double lo = 2., hi = 5.; // p_c decreases with h: bisection on p_c(h*) = spring pressure
  for (int i = 0; i < 60; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (c.contact_pressure(mid * sigma).value > spring_pressure ? lo : hi) = mid;
  }
  EXPECT_NEAR(0.5 * (lo + hi), 3.5, 0.05);
}

TEST(ContactPressure, DerivativesMatchCentralDifferences)
{
  AsperityContactParameters p = table1;
  p.asperity_deviation_ratio = 0.9;
  p.asperity_offset = 0.3;
  for (const AsperityContact &c :
       {table1_contact(), AsperityContact(AsperityContact::Model::gw_ceb, p)})
    for (const double hs : {-0.5, 0.2, 1., 2.5, 4., 5.5})
    {
      const double h = hs * 1e-7, dh = 1e-6 * 1e-7;
      {
        for (const auto &part :
             {std::function<ValueAndSlope(double)>([&](double x) { return c.contact_pressure(x); }),
              std::function<ValueAndSlope(double)>([&](double x)
                                                   { return c.elastic_contact_pressure(x); })})
        {
          const double fd = (part(h + dh).value - part(h - dh).value) / (2 * dh);
          EXPECT_NEAR(part(h).d_dh, fd, 1e-6 * std::abs(fd) + 1e-9) << "h* = " << hs;
        }
        EXPECT_LT(c.contact_pressure(h).d_dh, 0.); // closing the gap raises the contact pressure
      }
    }
}

TEST(ContactPressure, ModelNoneIsZero)
{
  const AsperityContact none;
  EXPECT_FALSE(none.enabled());
  for (const double h : {-1e-7, 0., 1e-7, 1e-6})
  {
    EXPECT_EQ(none.contact_pressure(h).value, 0.);
    EXPECT_EQ(none.contact_pressure(h).d_dh, 0.);
    EXPECT_EQ(none.real_contact_area_fraction(h), 0.);
  }
}

TEST(ContactPressure, OffsetEntersThroughTheSeparation)
{
  // Asperities touch where their height above their own mean exceeds h - y_s: raising y_s by
  // dy (in sigma) is the same as closing the gap by dy sigma.
  AsperityContactParameters p = table1;
  p.asperity_offset = 0.65;
  const AsperityContact shifted(AsperityContact::Model::gw_ceb, p);
  const AsperityContact c = table1_contact();
  for (const double hs : {1., 2., 3.5})
  {
    const double expected = c.contact_pressure((hs - 0.65) * 1e-7).value;
    EXPECT_NEAR(shifted.contact_pressure(hs * 1e-7).value, expected, 1e-13 * expected);
  }
}

// ---------------------------------------------------------------------------------------------

TEST(Parameters, DefaultsAreTable1)
{
  dealii::ParameterHandler prm;
  FlowFactors::declare_parameters(prm);
  AsperityContact::declare_parameters(prm);
  AsperityContact c;
  c.parse_parameters(prm);
  EXPECT_FALSE(c.enabled());
  const AsperityContactParameters &p = c.parameters();
  EXPECT_DOUBLE_EQ(p.composite_roughness, 1e-7);
  EXPECT_DOUBLE_EQ(p.asperity_radius, 1.7e-6);
  EXPECT_DOUBLE_EQ(p.asperity_density, 4.16e11);
  EXPECT_DOUBLE_EQ(p.plasticity_index, 6.6167);
  EXPECT_DOUBLE_EQ(p.elastic_modulus, 24.07e9);
  EXPECT_DOUBLE_EQ(p.hardness, 1e9);
  EXPECT_DOUBLE_EQ(p.pressure_factor, 0.6);
  EXPECT_DOUBLE_EQ(p.asperity_deviation_ratio, 1.);
  EXPECT_DOUBLE_EQ(p.asperity_offset, 0.);

  prm.parse_input_from_string("subsection Contact\n set Model = gw-ceb\n"
                              " set Plasticity index = auto\nend\n"
                              "subsection Roughness\n set Composite roughness = 2e-7\nend\n");
  c.parse_parameters(prm);
  EXPECT_TRUE(c.enabled());
  EXPECT_DOUBLE_EQ(c.parameters().composite_roughness, 2e-7);
  EXPECT_NEAR(c.parameters().plasticity_index, 6.1941 * std::sqrt(2.), 2e-4);

  prm.parse_input_from_string("subsection Contact\n set Plasticity index = six\nend\n");
  EXPECT_THROW(c.parse_parameters(prm), std::runtime_error);
  prm.parse_input_from_string("subsection Contact\n set Plasticity index = 6.6\n"
                              " set Hardness = 0\nend\n");
  EXPECT_THROW(c.parse_parameters(prm), std::runtime_error);

  dealii::ParameterHandler only_contact;
  AsperityContact::declare_parameters(only_contact);
  EXPECT_THROW(c.parse_parameters(only_contact), std::runtime_error);
}
