#include <sealfe/film/flow_factors.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
namespace patir_cheng
{
const double tabulated_patterns[n_patterns] = {1. / 9., 1. / 6., 1. / 3., 1., 3., 6., 9.};

namespace
{
// Patir & Cheng (1978) Table 1, pressure flow factor phi_x: coefficient C, exponent r and the
// film parameter above which the fit holds. Checked against the foam-extend implementation
// (flowFactorsPatirCheng.C), see doc/roughness.md.
const double pressure_C[n_patterns] = {1.48, 1.38, 1.18, 0.90, 0.225, 0.520, 0.870};
const double pressure_r[n_patterns] = {0.42, 0.42, 0.42, 0.56, 1.5, 1.5, 1.5};
const double pressure_H_min[n_patterns] = {1., 1., 0.75, 0.5, 0.5, 0.5, 0.5};

// Patir & Cheng (1979), shear flow factor Phi_s.
const double shear_A1[n_patterns] = {2.046, 1.962, 1.858, 1.899, 1.560, 1.290, 1.011};
const double shear_a1[n_patterns] = {1.12, 1.08, 1.01, 0.98, 0.85, 0.62, 0.54};
const double shear_a2[n_patterns] = {0.78, 0.77, 0.76, 0.92, 1.13, 1.09, 1.07};
const double shear_a3[n_patterns] = {0.03, 0.03, 0.03, 0.05, 0.08, 0.08, 0.08};
const double shear_A2[n_patterns] = {1.856, 1.754, 1.561, 1.126, 0.556, 0.388, 0.295};

// Patir & Cheng (1979), shear-stress factor Phi_fs.
const double stress_A3[n_patterns] = {14.1, 13.4, 12.3, 11.1, 9.8, 10.1, 8.7};
const double stress_a4[n_patterns] = {2.45, 2.42, 2.32, 2.31, 2.25, 2.25, 2.15};
const double stress_a5[n_patterns] = {2.30, 2.30, 2.30, 2.38, 2.80, 2.90, 2.97};
const double stress_a6[n_patterns] = {0.10, 0.10, 0.10, 0.11, 0.18, 0.18, 0.18};

// Patir & Cheng (1979), shear-stress factor phi_fp = 1 - D exp(-s H). Only gamma = 1 could be
// checked against a second source (doc/roughness.md).
const double stress_D[n_patterns] = {1.51, 1.51, 1.47, 1.40, 0.98, 0.97, 0.73};
const double stress_s[n_patterns] = {0.52, 0.54, 0.58, 0.66, 0.79, 0.91, 0.91};

/// Where gamma sits among the tabulated patterns: lower index and weight of the upper one,
/// linear in ln(gamma) (the table is symmetric in ln gamma, so gamma <-> 1/gamma mirrors it).
struct Bracket
{
  int lower;
  double weight;
};

Bracket bracket(const double gamma)
{
  const double lg = std::log(gamma);
  const double lmin = std::log(tabulated_patterns[0]);
  const double lmax = std::log(tabulated_patterns[n_patterns - 1]);
  if (!(lg >= lmin - 1e-12 && lg <= lmax + 1e-12))
  {
    std::ostringstream s;
    s << "Patir-Cheng flow factors: surface pattern gamma = " << gamma
      << " is outside the tabulated range [1/9, 9]";
    throw std::domain_error(s.str());
  }
  for (int k = 0; k < n_patterns - 1; ++k)
  {
    const double l0 = std::log(tabulated_patterns[k]);
    const double l1 = std::log(tabulated_patterns[k + 1]);
    if (lg <= l1 + 1e-12)
    {
      double w = (lg - l0) / (l1 - l0);
      // Snap to the table so that tabulated patterns evaluate exactly one fit.
      if (std::abs(w) < 1e-9)
        w = 0;
      if (std::abs(w - 1) < 1e-9)
        w = 1;
      return {k, std::clamp(w, 0., 1.)};
    }
  }
  return {n_patterns - 2, 1.};
}

template <typename Fit>
ValueAndSlope interpolate(const double gamma, const Fit &fit)
{
  const Bracket b = bracket(gamma);
  if (b.weight == 0)
    return fit(b.lower);
  if (b.weight == 1)
    return fit(b.lower + 1);
  const ValueAndSlope f0 = fit(b.lower), f1 = fit(b.lower + 1);
  return {(1 - b.weight) * f0.value + b.weight * f1.value,
          (1 - b.weight) * f0.d_dh + b.weight * f1.d_dh};
}

ValueAndSlope pressure_fit(const int k, const double H)
{
  const double C = pressure_C[k], r = pressure_r[k];
  if (tabulated_patterns[k] <= 1.)
  {
    const double e = C * std::exp(-r * H);
    return {1 - e, r * e};
  }
  const double p = C * std::pow(H, -r);
  return {1 + p, -r * p / H};
}

// A H^alpha exp(-beta H + delta H^2): the form of both Phi_s (H <= 5) and Phi_fs (H < 7).
ValueAndSlope power_gauss(const double A, const double alpha, const double beta, const double delta,
                          const double H)
{
  const double f = A * std::pow(H, alpha) * std::exp(-beta * H + delta * H * H);
  return {f, f * (alpha / H - beta + 2 * delta * H)};
}
} // namespace

double tripp_shape(const double gamma)
{
  // Second-order perturbation of the film conductance h^3 (Tripp 1983; derivation in
  // doc/roughness.md section 2.2): phi_x - 1 = (3/H^2)(1 - 3 <k_x^2/|k|^2>), and for the Peklenik
  // pattern (the spectrum is an isotropic one stretched by the correlation lengths) the angular
  // mean is <k_x^2/|k|^2> = 1/(1 + gamma).
  return 3. * (1. - 3. / (1. + gamma));
}

ValueAndSlope pressure_flow_factor(const double H, const double gamma)
{
  const Bracket b = bracket(gamma); // also refuses gamma outside the tables, at every H
  // Departure from 1 of the fits (exact at the tabulated patterns) for H <= fits_upper_limit.
  const auto departure = [gamma, &b](const double x) -> ValueAndSlope
  {
    const auto fit = [x](const int k)
    {
      const ValueAndSlope f = pressure_fit(k, x);
      return ValueAndSlope{f.value - 1., f.d_dh};
    };
    if (b.weight == 0)
      return fit(b.lower);
    if (b.weight == 1)
      return fit(b.lower + 1);
    const ValueAndSlope f0 = fit(b.lower), f1 = fit(b.lower + 1);
    const double w = b.weight;
    // (gamma = 1 is tabulated, so no bracket straddles it; the sign changes inside [1, 3].)
    if (tabulated_patterns[b.lower] == 1.)
    {
      // Between gamma = 1 (phi_x < 1) and gamma = 3 (phi_x > 1) the departure changes sign: the
      // fits' departures are scaled by Tripp's shape T(gamma), the scaled values interpolated,
      // and the result multiplied by T(gamma) again, so phi_x = 1 exactly where T = 0 (gamma = 2).
      const double T0 = tripp_shape(tabulated_patterns[b.lower]);
      const double T1 = tripp_shape(tabulated_patterns[b.lower + 1]);
      const double T = tripp_shape(gamma);
      return {T * ((1 - w) * f0.value / T0 + w * f1.value / T1),
              T * ((1 - w) * f0.d_dh / T0 + w * f1.d_dh / T1)};
    }
    // Both neighbours on the same side of 1: the departure, linear in ln(gamma).
    return {(1 - w) * f0.value + w * f1.value, (1 - w) * f0.d_dh + w * f1.d_dh};
  };
  if (H <= fits_upper_limit)
  {
    const ValueAndSlope d = departure(H);
    return {1. + d.value, d.d_dh};
  }
  const double T = tripp_shape(gamma);
  const ValueAndSlope tripp{T / (H * H), -2. * T / (H * H * H)};
  if (H >= tripp_from)
    return {1. + tripp.value, tripp.d_dh};
  // Between the two: a C1 blend (smoothstep in H) from the fits to Tripp's asymptote.
  const ValueAndSlope d = departure(H);
  const double span = tripp_from - fits_upper_limit;
  const double s = (H - fits_upper_limit) / span;
  const double t = s * s * (3. - 2. * s), dt = 6. * s * (1. - s) / span;
  return {1. + (1. - t) * d.value + t * tripp.value,
          (1. - t) * d.d_dh + t * tripp.d_dh + dt * (tripp.value - d.value)};
}

double pressure_flow_factor_validity(const double gamma)
{
  const Bracket b = bracket(gamma);
  if (b.weight == 0)
    return pressure_H_min[b.lower];
  if (b.weight == 1)
    return pressure_H_min[b.lower + 1];
  // Between two patterns both fits enter, so both must be valid.
  return std::max(pressure_H_min[b.lower], pressure_H_min[b.lower + 1]);
}

ValueAndSlope shear_flow_factor(const double H, const double gamma)
{
  return interpolate(gamma,
                     [H](const int k) -> ValueAndSlope
                     {
                       if (H <= 5.)
                         return power_gauss(shear_A1[k], shear_a1[k], shear_a2[k], shear_a3[k], H);
                       const double f = shear_A2[k] * std::exp(-0.25 * H);
                       return {f, -0.25 * f};
                     });
}

ValueAndSlope couette_shear_factor(const double H)
{
  // phi_f = z * (35/32) Int (1-u^2)^3 / (z+u) du with z = H/3 (the density's support is
  // |delta| <= c = 3 sigma). Three forms of one function: the published closed forms for
  // z <= 1 (gap cut off at eps* = 1/300) and 1 < z < 2, and for z >= 2 the convergent series
  // sum_k E[u^2k] z^-2k, which avoids the cancellation of the closed form's z^5 terms (at z = 3
  // the closed form already loses four digits).
  const double z = H / 3.;
  const double k35 = 35. / 32.;
  if (z <= 1.)
  {
    const double eps = 1. / 300.;
    const double L = std::log((z + 1.) / eps);
    const double q = 1. - z * z;
    const double P =
        -55. + z * (132. + z * (345. + z * (-160. + z * (-405. + z * (60. + z * 147.)))));
    const double dP = 132. + z * (690. + z * (-480. + z * (-1620. + z * (300. + z * 882.))));
    const double bracket_value = q * q * q * L + P / 60.;
    const double value = k35 * z * bracket_value;
    const double d_dz =
        k35 * bracket_value + k35 * z * (-6. * z * q * q * L + q * q * q / (z + 1.) + dP / 60.);
    return {value, d_dz / 3.};
  }
  if (z < 2.)
  {
    const double L = std::log((z + 1.) / (z - 1.));
    const double q = 1. - z * z;
    const double z2 = z * z;
    const double bracket_value = q * q * q * L + z / 15. * (66. + z2 * (30. * z2 - 80.));
    const double value = k35 * z * bracket_value;
    const double d_dz =
        k35 * bracket_value +
        k35 * z * (-6. * z * q * q * L + 2. * q * q + (66. + z2 * (150. * z2 - 240.)) / 15.);
    return {value, d_dz / 3.};
  }
  // Moments of the density: E[u^2k] = E[u^2(k-1)] (k - 1/2)/(k + 7/2).
  double moment = 1., value = 1., d_dz = 0., zpow = 1.;
  const double iz2 = 1. / (z * z);
  // Terms fall like k^-4 4^-k at z = 2: 40 of them reach round-off.
  for (int k = 1; k <= 40; ++k)
  {
    moment *= (k - 0.5) / (k + 3.5);
    zpow *= iz2;
    value += moment * zpow;
    d_dz += -2. * k * moment * zpow / z;
  }
  return {value, d_dz / 3.};
}

ValueAndSlope roughness_shear_factor(const double H, const double gamma)
{
  return interpolate(gamma,
                     [H](const int k) -> ValueAndSlope
                     {
                       if (H < 7.)
                         return power_gauss(stress_A3[k], stress_a4[k], stress_a5[k], stress_a6[k],
                                            H);
                       return {0., 0.};
                     });
}

ValueAndSlope poiseuille_shear_factor(const double H, const double gamma)
{
  return interpolate(gamma,
                     [H](const int k) -> ValueAndSlope
                     {
                       const double e = stress_D[k] * std::exp(-stress_s[k] * H);
                       return {1 - e, stress_s[k] * e};
                     });
}

ValueAndSlope expected_gap(const double H)
{
  // E[max(H + d, 0)] for d ~ N(0, 1): H P(d > -H) + density(H). For H > 0 it is written as
  // H + (density - H Q(H)), Q the upper tail, so that the small excess over H is not lost in
  // 1 - Q rounding to 1.
  const double density = std::exp(-0.5 * H * H) / std::sqrt(2. * M_PI);
  if (H > 0)
  {
    const double Q = 0.5 * std::erfc(H / std::sqrt(2.));
    return {H + (density - H * Q), 1. - Q};
  }
  const double cdf = 0.5 * std::erfc(-H / std::sqrt(2.));
  return {H * cdf + density, cdf};
}
} // namespace patir_cheng

// ---------------------------------------------------------------------------------------------

namespace
{
std::atomic<bool> clamp_warning_given{false};
}

FlowFactors::FlowFactors(const Model model, const double composite_roughness,
                         const double surface_pattern, const double rotor_roughness_share)
    : model_(model), sigma(composite_roughness), gamma(surface_pattern),
      rotor_share(rotor_roughness_share)
{
  validate();
}

FlowFactors::FlowFactors(const FlowFactors &other)
    : model_(other.model_), sigma(other.sigma), gamma(other.gamma), rotor_share(other.rotor_share),
      n_clamped(other.n_clamped.load()), lowest_clamped(other.lowest_clamped.load())
{
}

FlowFactors &FlowFactors::operator=(const FlowFactors &other)
{
  model_ = other.model_;
  sigma = other.sigma;
  gamma = other.gamma;
  rotor_share = other.rotor_share;
  n_clamped = other.n_clamped.load();
  lowest_clamped = other.lowest_clamped.load();
  return *this;
}

void FlowFactors::declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  prm.enter_subsection("Roughness");
  prm.declare_entry("Model", "none", Selection("none|patir-cheng"),
                    "Rough-film model: none (smooth faces) or patir-cheng (average flow model of "
                    "Patir & Cheng 1978/1979: pressure and shear flow factors, expected gap, "
                    "shear-stress factors).");
  prm.declare_entry("Composite roughness", "1e-7", Double(0),
                    "sigma (m) = sqrt(sigma_rotor^2 + sigma_stator^2), the RMS of the combined "
                    "surface heights. Also the sigma of the asperity contact model.");
  prm.declare_entry("Surface pattern", "1", Double(0),
                    "Peklenik gamma of the roughness relative to sliding (circumferential): 1 "
                    "isotropic, < 1 transverse (ridges radial), > 1 longitudinal (ridges "
                    "circumferential). Tabulated range 1/9 .. 9.");
  prm.declare_entry("Rotor roughness share", "0.5", Double(0, 1),
                    "(sigma_rotor/sigma)^2. Sets the sign and size of the shear flow factor: "
                    "phi_s = (2 share - 1) Phi_s; 0.5 (equally rough faces) gives phi_s = 0.");
  prm.leave_subsection();
}

void FlowFactors::parse_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Roughness");
  const std::string m = prm.get("Model");
  model_ = (m == "patir-cheng") ? Model::patir_cheng : Model::none;
  sigma = prm.get_double("Composite roughness");
  gamma = prm.get_double("Surface pattern");
  rotor_share = prm.get_double("Rotor roughness share");
  prm.leave_subsection();
  validate();
}

void FlowFactors::validate() const
{
  for (const double v : {sigma, gamma, rotor_share})
    if (!std::isfinite(v))
      throw std::runtime_error("Roughness: a parameter is not a finite number");
  if (!(rotor_share >= 0 && rotor_share <= 1))
  {
    std::ostringstream s;
    s << "Roughness: Rotor roughness share must lie in [0, 1] (got " << rotor_share << ")";
    throw std::runtime_error(s.str());
  }
  if (model_ == Model::none)
    return;
  if (!(sigma > 0))
  {
    std::ostringstream s;
    s << "Roughness: Composite roughness must be positive for the patir-cheng model (got " << sigma
      << " m)";
    throw std::runtime_error(s.str());
  }
  // The fits exist for 1/9 <= gamma <= 9 only; no extrapolation in the pattern.
  if (!(gamma >= 1. / 9. * (1 - 1e-3) && gamma <= 9. * (1 + 1e-3)))
  {
    std::ostringstream s;
    s << "Roughness: Surface pattern gamma = " << gamma
      << " is outside the range of the Patir-Cheng tables, [1/9, 9]";
    throw std::runtime_error(s.str());
  }
}

double FlowFactors::limited(const double H, const double limit, bool &clamped) const
{
  clamped = H < limit;
  if (!clamped)
    return H;
  n_clamped.fetch_add(1, std::memory_order_relaxed);
  double seen = lowest_clamped.load(std::memory_order_relaxed);
  while (H < seen && !lowest_clamped.compare_exchange_weak(seen, H, std::memory_order_relaxed))
  {
  }
  if (!clamp_warning_given.exchange(true))
    std::cerr << "sealfe: warning: Patir-Cheng flow factors evaluated at h/sigma = " << H
              << ", below the validity limit " << limit
              << " of the published fits; they are held at the limit (counted, reported "
                 "once per run)\n";
  return limit;
}

namespace
{
/// Clamp gamma into the tabulated range (validate() allows 0.1 % of slack for rounded input).
double tabulated_range(const double gamma)
{
  return std::clamp(gamma, 1. / 9., 9.);
}
} // namespace

ValueAndSlope FlowFactors::circumferential_pressure_flow_factor(const double h) const
{
  if (is_smooth())
    return {1., 0.};
  const double g = tabulated_range(gamma);
  bool clamped;
  const double H = limited(h / sigma, patir_cheng::pressure_flow_factor_validity(g), clamped);
  const ValueAndSlope f = patir_cheng::pressure_flow_factor(H, g);
  return {f.value, clamped ? 0. : f.d_dh / sigma};
}

ValueAndSlope FlowFactors::radial_pressure_flow_factor(const double h) const
{
  if (is_smooth())
    return {1., 0.};
  // Patir & Cheng: phi_y(H, gamma) = phi_x(H, 1/gamma).
  const double g = 1. / tabulated_range(gamma);
  bool clamped;
  const double H = limited(h / sigma, patir_cheng::pressure_flow_factor_validity(g), clamped);
  const ValueAndSlope f = patir_cheng::pressure_flow_factor(H, g);
  return {f.value, clamped ? 0. : f.d_dh / sigma};
}

ValueAndSlope FlowFactors::shear_flow_factor(const double h) const
{
  if (is_smooth())
    return {0., 0.};
  // V_r1 - V_r2 with V_r1 = share (rotor) and V_r2 = 1 - share (stator).
  const double sign = 2. * rotor_share - 1.;
  bool clamped;
  const double H = limited(h / sigma, patir_cheng::shear_validity, clamped);
  const ValueAndSlope f = patir_cheng::shear_flow_factor(H, tabulated_range(gamma));
  return {sign * f.value, clamped ? 0. : sign * f.d_dh / sigma};
}

ValueAndSlope FlowFactors::expected_gap(const double h) const
{
  if (is_smooth())
    return {h, 1.};
  const ValueAndSlope g = patir_cheng::expected_gap(h / sigma);
  return {sigma * g.value, g.d_dh};
}

FlowFactors::FilmFactors FlowFactors::film_factors(const double h) const
{
  return {circumferential_pressure_flow_factor(h), radial_pressure_flow_factor(h),
          shear_flow_factor(h), expected_gap(h)};
}

FlowFactors::ShearStressFactors FlowFactors::shear_stress_factors(const double h) const
{
  if (is_smooth())
    return {{1., 0.}, {0., 0.}, {1., 0.}};
  const double g = tabulated_range(gamma);
  const double sign = 2. * rotor_share - 1.;
  bool clamped;
  const double H = limited(h / sigma, patir_cheng::shear_validity, clamped);
  const ValueAndSlope f = patir_cheng::couette_shear_factor(H);
  const ValueAndSlope fs = patir_cheng::roughness_shear_factor(H, g);
  const ValueAndSlope fp = patir_cheng::poiseuille_shear_factor(H, g);
  const double k = clamped ? 0. : 1. / sigma;
  return {{f.value, k * f.d_dh}, {sign * fs.value, sign * k * fs.d_dh}, {fp.value, k * fp.d_dh}};
}

double FlowFactors::rotor_shear_stress(const double h, const double viscosity, const double u_rotor,
                                       const double u_stator, const double dp_dx) const
{
  const ShearStressFactors f = shear_stress_factors(h);
  return viscosity * (u_stator - u_rotor) / h * (f.phi_f.value - f.phi_fs.value) -
         f.phi_fp.value * 0.5 * h * dp_dx;
}

double FlowFactors::stator_shear_stress(const double h, const double viscosity,
                                        const double u_rotor, const double u_stator,
                                        const double dp_dx) const
{
  const ShearStressFactors f = shear_stress_factors(h);
  return viscosity * (u_rotor - u_stator) / h * (f.phi_f.value + f.phi_fs.value) -
         f.phi_fp.value * 0.5 * h * dp_dx;
}

void FlowFactors::reset_clamp_record() const
{
  n_clamped = 0;
  lowest_clamped = std::numeric_limits<double>::infinity();
}

void FlowFactors::rearm_clamp_warning()
{
  clamp_warning_given = false;
}

} // namespace sealfe
