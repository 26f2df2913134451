#include <sealfe/closed_form/narrow_seal.h>
#include <sealfe/numerics/minimisation.h>

#include <deal.II/base/quadrature_lib.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace sealfe
{
void NarrowSealQuadrature::declare_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Narrow seal");
  prm.declare_entry("Radial quadrature points", "24", dealii::Patterns::Integer(1, 4096),
                    "Gauss-Legendre points across the dam (per smooth piece of the radial "
                    "pressure profile) in the narrow-seal loads.");
  prm.declare_entry("Angular quadrature points", "512", dealii::Patterns::Integer(8, 1 << 20),
                    "Points around the circumference in the narrow-seal loads (periodic "
                    "trapezoid rule, or Gauss-Legendre between the half-Sommerfeld rupture "
                    "angles), also the number of samples used to find those angles.");
  prm.declare_entry("Curvature in loads", "kept", dealii::Patterns::Selection("kept|neglected"),
                    "kept: loads with dA = r dr dtheta and moment arms r (film_loads.h); "
                    "neglected: r -> mean radius outside the film thickness, as in Etsion's "
                    "closed forms.");
  prm.leave_subsection();
}

void NarrowSealQuadrature::parse_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Narrow seal");
  radial_points = prm.get_integer("Radial quadrature points");
  angular_points = prm.get_integer("Angular quadrature points");
  curvature = prm.get("Curvature in loads") == "neglected" ? Curvature::neglected : Curvature::kept;
  prm.leave_subsection();
}

// ------------------------------------------------------------------------------------------------
// One radial line theta = const. h is linear in r there (film_thickness.h), which is what makes the
// narrow-seal pressure, its radial flux and its cavity all closed-form on the line.
struct NarrowSealModel::RadialLine
{
  double ri, ro, W;     // radii, dam width W = ro - ri
  double hi, ho, hm, b; // film at ri, ro, r_m = (ri + ro)/2 (h_m = (h_i + h_o)/2), dh/dr
  double pi, po, dp;    // boundary pressures, dp = po - pi
  double S;             // source 12 mu (wbar dh/dtheta + dh/dt) at r_m
  double D;             // p_d = D (ro - r)(r - ri)/h^2, D = -S/(2 h_m)
  double cs;            // h^3 dp_s/dr, constant on the line

  double h(const double r) const { return hi + b * (r - ri); }
  // Varney & Green Eq. 12 rearranged: (h_o^2 - h^2)/(h_o^2 - h_i^2) = (ro - r)(h_o + h) /
  // ((ro - ri)(h_o + h_i)), which has no 0/0 on a parallel line (b = 0).
  double p_s(const double r) const
  {
    const double q = hi / h(r);
    return po - dp * q * q * (ro - r) * (ho + h(r)) / (W * (ho + hi));
  }
  double p_d(const double r) const
  {
    const double hr = h(r);
    return D * (ro - r) * (r - ri) / (hr * hr);
  }
  double p(const double r) const { return p_s(r) + p_d(r); }
  // h^3 dp_d/dr = -(S / 2 h_m) [W h_i - s (h_i + h_o)] = S (s - W h_i / (2 h_m)), s = r - ri.
  double h3_dp_dr(const double r) const { return cs + S * ((r - ri) - W * hi / (2 * hm)); }

  // q(s) = h^2 (p - p_cav) is a quadratic in s = r - ri: a0 + a1 s + a2 s^2, with
  // q(0) = (pi - p_cav) h_i^2 and q(W) = (po - p_cav) h_o^2.
  void cavity_quadratic(const double pcav, double &a0, double &a1, double &a2, double &aW) const
  {
    a0 = (pi - pcav) * hi * hi;
    aW = (po - pcav) * ho * ho;
    a2 = (po - pcav) * b * b + dp * hi * hi * b / (W * (ho + hi)) - D;
    a1 = (aW - a0) / W - a2 * W;
  }
  // q = q_lin + k s (W - s) with k = -a2 and q_lin >= 0 (p_cav <= pi, po), so the line cavitates
  // iff min_s q / (s (W - s)) < 0; that minimum is (sqrt q(0) + sqrt q(W))^2 / W^2 - a2. This
  // indicator is continuous in theta and changes sign where a cavity is born.
  double cavity_indicator(const double pcav) const
  {
    double a0, a1, a2, aW;
    cavity_quadratic(pcav, a0, a1, a2, aW);
    const double s = std::sqrt(std::max(a0, 0.0)) + std::sqrt(std::max(aW, 0.0));
    return s * s / (W * W) - a2;
  }
  // The cavitated interval [r1, r2] (roots of q), if any.
  bool cavity(const double pcav, double &r1, double &r2) const
  {
    if (!(cavity_indicator(pcav) < 0))
      return false;
    double a0, a1, a2, aW;
    cavity_quadratic(pcav, a0, a1, a2, aW);
    const double disc = std::max(a1 * a1 - 4 * a2 * a0, 0.0);
    const double t = -0.5 * (a1 + std::copysign(std::sqrt(disc), a1)); // no cancellation
    if (t == 0 || a2 <= 0)
      return false;
    double s1 = t / a2, s2 = a0 / t;
    if (s1 > s2)
      std::swap(s1, s2);
    s1 = std::clamp(s1, 0.0, W);
    s2 = std::clamp(s2, 0.0, W);
    if (!(s2 > s1))
      return false;
    r1 = ri + s1;
    r2 = ri + s2;
    return true;
  }
  // Extremes of the full-film p on the line: the ends and the one root of the linear h^3 dp/dr.
  std::pair<double, double> extremes() const
  {
    double lo = std::min(pi, po), hi_p = std::max(pi, po);
    if (S != 0)
    {
      const double s = W * hi / (2 * hm) - cs / S;
      if (s > 0 && s < W)
      {
        const double v = p(ri + s);
        lo = std::min(lo, v);
        hi_p = std::max(hi_p, v);
      }
    }
    return {lo, hi_p};
  }
};

NarrowSealModel::NarrowSealModel(const FilmThickness &film, const OperatingConditions &conditions,
                                 const Cavitation cavitation, const double cavitation_pressure)
    : film_(film), conditions_(conditions), cavitation_(cavitation),
      cavitation_pressure_(cavitation_pressure)
{
  film_.validate();
  conditions_.validate();
  if (film_.features)
    throw std::runtime_error("Film model/Model = closed form: surface features (Geometry/Surface "
                             "features) need Film model/Model = finite element");
  if (!std::isfinite(cavitation_pressure))
    throw std::runtime_error("Narrow seal: the cavitation pressure is not a finite number");
  if (cavitation_ == Cavitation::reynolds || cavitation_ == Cavitation::jfo)
    throw std::runtime_error(
        "Narrow seal: Cavitation/Model = reynolds or jfo needs the finite element film model; the "
        "narrow-seal closed forms support none and half-sommerfeld only");
  if (cavitation_ == Cavitation::half_sommerfeld &&
      cavitation_pressure_ > std::min(conditions_.inner_pressure, conditions_.outer_pressure))
  {
    std::ostringstream s;
    s << "Narrow seal: the cavitation pressure (" << cavitation_pressure_
      << " Pa) exceeds a boundary pressure (pi = " << conditions_.inner_pressure
      << " Pa, po = " << conditions_.outer_pressure << " Pa)";
    throw std::runtime_error(s.str());
  }
}

NarrowSealModel::RadialLine NarrowSealModel::line(const double theta) const
{
  RadialLine l;
  l.ri = film_.inner_radius;
  l.ro = film_.outer_radius;
  l.W = l.ro - l.ri;
  const double rm = 0.5 * (l.ri + l.ro);
  l.hi = film_.value(l.ri, theta);
  l.ho = film_.value(l.ro, theta);
  l.hm = 0.5 * (l.hi + l.ho);
  l.b = (l.ho - l.hi) / l.W;
  l.pi = conditions_.inner_pressure;
  l.po = conditions_.outer_pressure;
  l.dp = l.po - l.pi;
  l.S = 12 * conditions_.viscosity *
        (conditions_.mean_speed() * film_.d_dtheta(rm, theta) + film_.d_dt(rm, theta));
  l.D = -l.S / (2 * l.hm);
  l.cs = 2 * l.dp * l.hi * l.hi * l.ho * l.ho / (l.W * (l.hi + l.ho));
  return l;
}

double NarrowSealModel::hydrostatic_pressure(const double r, const double theta) const
{
  return line(theta).p_s(r);
}

double NarrowSealModel::hydrodynamic_pressure(const double r, const double theta) const
{
  return line(theta).p_d(r);
}

double NarrowSealModel::full_film_pressure(const double r, const double theta) const
{
  return line(theta).p(r);
}

double NarrowSealModel::pressure(const double r, const double theta) const
{
  const double p = full_film_pressure(r, theta);
  return cavitation_ == Cavitation::half_sommerfeld ? std::max(p, cavitation_pressure_) : p;
}

double NarrowSealModel::h3_dp_dr(const double r, const double theta) const
{
  return line(theta).h3_dp_dr(r);
}

double NarrowSealModel::source(const double theta) const
{
  return line(theta).S;
}

std::vector<double> NarrowSealModel::rupture_angles(const unsigned int samples) const
{
  std::vector<double> angles;
  if (cavitation_ != Cavitation::half_sommerfeld || samples == 0)
    return angles;
  const double pcav = cavitation_pressure_;
  auto cavitated = [&](const double t) { return line(t).cavity_indicator(pcav) < 0; };
  const double dt = 2 * M_PI / samples;
  std::vector<char> state(samples);
  for (unsigned int i = 0; i < samples; ++i)
    state[i] = cavitated(i * dt);
  for (unsigned int i = 0; i < samples; ++i)
  {
    if (state[i] == state[(i + 1) % samples])
      continue;
    double a = i * dt, b = (i + 1) * dt;
    const bool sa = state[i];
    for (unsigned int it = 0; it < 200; ++it)
    {
      const double m = 0.5 * (a + b);
      if (!(m > a && m < b))
        break;
      (cavitated(m) == sa ? a : b) = m;
    }
    angles.push_back(std::fmod(0.5 * (a + b), 2 * M_PI));
  }
  std::sort(angles.begin(), angles.end());
  return angles;
}

namespace
{
using Rule = std::pair<std::vector<double>, std::vector<double>>;
/// Gauss-Legendre rule on [0, 1]. Cached for the life of the program (guarded for threads): the
/// rule's construction costs O(n^2), far more than a whole load evaluation for n ~ 500.
const Rule &gauss_rule(const unsigned int n)
{
  static std::map<unsigned int, Rule> rules;
  static std::mutex mutex;
  std::lock_guard<std::mutex> lock(mutex);
  auto it = rules.find(n);
  if (it == rules.end())
  {
    const dealii::QGauss<1> q(n);
    Rule rule{std::vector<double>(n), std::vector<double>(n)};
    for (unsigned int i = 0; i < n; ++i)
    {
      rule.first[i] = q.point(i)[0];
      rule.second[i] = q.weight(i);
    }
    it = rules.emplace(n, std::move(rule)).first; // std::map never moves its elements
  }
  return it->second;
}
} // namespace

FilmLoads NarrowSealModel::loads(const NarrowSealQuadrature &quadrature) const
{
  if (quadrature.radial_points < 1 || quadrature.angular_points < 8)
    throw std::runtime_error("Narrow seal: need at least 1 radial and 8 angular quadrature points");

  const double ri = film_.inner_radius, ro = film_.outer_radius, rm = 0.5 * (ri + ro);
  const double mu = conditions_.viscosity, pref = conditions_.reference_pressure;
  const double dw = conditions_.rotor_speed - conditions_.stator_speed;
  const double psi = film_.tilt_angle, pcav = cavitation_pressure_;
  const bool hs = cavitation_ == Cavitation::half_sommerfeld;
  const bool neglect = quadrature.curvature == Curvature::neglected;

  // Angular rule. A smooth periodic film: the trapezoid rule (spectral). Otherwise the integrand
  // has kinks at the rupture angles; between them Gauss-Legendre under theta = a + L (3x^2 - 2x^3),
  // whose vanishing slope at both ends turns the (theta - theta_c)^(3/2) or ^2 onset of a cavity
  // into an analytic integrand of x, so each piece converges spectrally too.
  std::vector<double> theta, wtheta;
  const std::vector<double> breaks = rupture_angles(quadrature.angular_points);
  if (breaks.empty())
  {
    const unsigned int n = quadrature.angular_points;
    for (unsigned int k = 0; k < n; ++k)
    {
      theta.push_back(2 * M_PI * k / n);
      wtheta.push_back(2 * M_PI / n);
    }
  }
  else
    for (std::size_t k = 0; k < breaks.size(); ++k)
    {
      const double a = breaks[k];
      const double b = (k + 1 < breaks.size()) ? breaks[k + 1] : breaks[0] + 2 * M_PI;
      const double L = b - a;
      const unsigned int n = std::max(
          16u, static_cast<unsigned int>(std::ceil(quadrature.angular_points * L / (2 * M_PI))));
      const auto &[x, w] = gauss_rule(n);
      for (unsigned int i = 0; i < n; ++i)
      {
        theta.push_back(a + L * x[i] * x[i] * (3 - 2 * x[i]));
        wtheta.push_back(L * 6 * x[i] * (1 - x[i]) * w[i]);
      }
    }

  const auto &[xr, wr] = gauss_rule(quadrature.radial_points);
  FilmLoads out;
  double cavitated_area = 0, area = 0, torque_couette = 0, torque_pressure = 0;
  for (std::size_t k = 0; k < theta.size(); ++k)
  {
    const double t = theta[k], wt = wtheta[k];
    const RadialLine ln = line(t);
    const double c = std::cos(t), s = std::sin(t), ct = std::cos(t - psi), st = std::sin(t - psi);

    // Pieces of the radial line on which the (clipped) pressure is smooth.
    double r1 = ro, r2 = ro;
    const bool cav = hs && ln.cavity(pcav, r1, r2);
    const double edges[4] = {ri, r1, r2, ro};
    for (unsigned int piece = 0; piece < 3; ++piece)
    {
      const double a = edges[piece], b = edges[piece + 1];
      if (!(b > a))
        continue;
      const bool in_cavity = cav && piece == 1;
      for (unsigned int i = 0; i < xr.size(); ++i)
      {
        const double r = a + (b - a) * xr[i];
        const double arm = neglect ? rm : r;
        const double dA = arm * (b - a) * wr[i] * wt;
        const double p = in_cavity ? pcav : (hs ? std::max(ln.p(r), pcav) : ln.p(r));
        const double pg = p - pref;
        out.force_z += pg * dA;
        out.moment_x += pg * arm * s * dA;
        out.moment_y -= pg * arm * c * dA;
        out.moment_restoring -= pg * arm * ct * dA;
        out.moment_transverse += pg * arm * st * dA;
        // Pressure-gradient shear, integrated by parts around the (periodic, continuous) film:
        // int (h/2) dp/dtheta dtheta = -int (p/2) dh/dtheta dtheta.
        torque_pressure -= 0.5 * p * film_.d_dtheta(r, t) * dA;
        if (in_cavity)
          cavitated_area += dA;
      }
    }
    for (unsigned int i = 0; i < xr.size(); ++i)
    {
      const double r = ri + (ro - ri) * xr[i];
      const double arm = neglect ? rm : r;
      const double dA = arm * (ro - ri) * wr[i] * wt;
      torque_couette += mu * dw * arm * arm / ln.h(r) * dA;
    }
    area += (neglect ? rm * (ro - ri) : 0.5 * (ro * ro - ri * ri)) * wt;

    // Leakage, positive out of the dam, length element r_m dtheta (the narrow model's own
    // conservation law). Under half-Sommerfeld a boundary held at p_cav whose full-film pressure
    // dips below p_cav just inside is cavitated there: the clipped field carries no flux.
    double out_i = ln.h3_dp_dr(ri) / (12 * mu), out_o = -ln.h3_dp_dr(ro) / (12 * mu);
    if (hs && ln.pi <= pcav && out_i < 0)
      out_i = 0;
    if (hs && ln.po <= pcav && out_o < 0)
      out_o = 0;
    out.leakage_inner += out_i * rm * wt;
    out.leakage_outer += out_o * rm * wt;
  }
  out.friction_torque = torque_couette + torque_pressure;
  out.cavitated_fraction = cavitated_area / area;
  out.min_film = film_.minimum().value;

  // Extreme pressures: exact on each radial line, sampled in theta and polished.
  {
    const unsigned int n = quadrature.angular_points;
    auto lowest = [&](const double t) { return line(t).extremes().first; };
    auto highest = [&](const double t) { return line(t).extremes().second; };
    const double p_min =
        numerics::sampled_minimum(lowest, 0, 2 * M_PI, n, numerics::Domain::periodic).value;
    const double p_max =
        numerics::sampled_maximum(highest, 0, 2 * M_PI, n, numerics::Domain::periodic).value;
    out.min_pressure = hs ? std::max(p_min, pcav) : p_min;
    out.max_pressure = p_max;
  }
  return out;
}

FilmLoads compute(const FilmThickness &film, const OperatingConditions &conditions,
                  const Cavitation cavitation, const NarrowSealQuadrature &quadrature,
                  const double cavitation_pressure)
{
  return NarrowSealModel(film, conditions, cavitation, cavitation_pressure).loads(quadrature);
}

// ------------------------------------------------------------------------------------------------
namespace etsion
{
namespace
{
void check(const double eps, const double Ri)
{
  if (!(eps >= 0 && eps <= 1) || !(Ri >= 0 && Ri < 1))
  {
    std::ostringstream s;
    s << "Etsion closed forms: need 0 <= eps <= 1 and 0 <= Ri < 1 (got eps = " << eps
      << ", Ri = " << Ri << ")";
    throw std::invalid_argument(s.str());
  }
}

// The printed forms subtract terms of size 1/eps (force), 1 (restoring moment) or 1/eps
// (transverse moment) to leave a result of size eps or eps^2. Splitting off the leading Taylor
// terms analytically removes those cancellations; the helpers below are the remainders, each
// evaluated by its series for small arguments and directly otherwise.

// atanh(x) - x = sum_{k>=1} x^(2k+1)/(2k+1)
double atanh_minus_x(const double x)
{
  if (std::abs(x) >= 0.25)
    return std::atanh(x) - x;
  const double x2 = x * x;
  double term = x * x2, sum = 0;
  for (unsigned int k = 1; k < 60; ++k, term *= x2)
  {
    sum += term / (2 * k + 1);
    if (std::abs(term) <= 1e-18 * std::abs(sum))
      break;
  }
  return sum;
}

// ln(1 - y) + y = -sum_{n>=2} y^n / n
double log1m_plus_y(const double y)
{
  if (std::abs(y) >= 0.0625)
    return std::log1p(-y) + y;
  double term = y * y, sum = 0;
  for (unsigned int n = 2; n < 80; ++n, term *= y)
  {
    sum -= term / n;
    if (std::abs(term) <= 1e-18 * std::abs(sum))
      break;
  }
  return sum;
}

// asin(x) - x = sum_{n>=1} a_n x^(2n+1), a_1 = 1/6, a_n / a_(n-1) = (2n-1)^2 / (2n (2n+1))
double asin_minus_x(const double x)
{
  if (std::abs(x) >= 0.25)
    return std::asin(x) - x;
  const double x2 = x * x;
  double a = 1.0 / 6, term = x * x2, sum = 0;
  for (unsigned int n = 1; n < 60; ++n)
  {
    sum += a * term;
    if (std::abs(a * term) <= 1e-18 * std::abs(sum))
      break;
    term *= x2;
    a *= (2.0 * n + 1) * (2.0 * n + 1) / ((2.0 * n + 2) * (2.0 * n + 3));
  }
  return sum;
}

// sqrt(1 - x^2) - 1
double sqrt1m_minus_1(const double x)
{
  return -x * x / (1 + std::sqrt(1 - x * x));
}

// (1 - eps^2)(atanh(eps) - eps) / eps^2, -> 0 as eps -> 1 (x ln x -> 0).
double force_eps_term(const double eps)
{
  if (eps == 1)
    return 0;
  return (1 - eps) * (1 + eps) * atanh_minus_x(eps) / (eps * eps);
}

// [ln(1 - eps^2) + eps^2]/eps^2 + 2 (atanh(eps) - eps)/eps
//   = [(1 - eps) ln(1 - eps) + (1 + eps) ln(1 + eps)]/eps^2 - 1
//   = sum_{k>=1} eps^(2k) / ((k + 1)(2k + 1)),   finite (2 ln 2 - 1) at eps = 1.
double moment_eps_term(const double eps)
{
  if (eps >= 0.25)
  {
    const double a = (eps == 1) ? 0.0 : (1 - eps) * std::log1p(-eps);
    return (a + (1 + eps) * std::log1p(eps)) / (eps * eps) - 1;
  }
  const double e2 = eps * eps;
  double term = e2, sum = 0;
  for (unsigned int k = 1; k < 60; ++k, term *= e2)
  {
    const double add = term / ((k + 1.0) * (2.0 * k + 1));
    sum += add;
    if (add <= 1e-18 * sum)
      break;
  }
  return sum;
}
} // namespace

// Eq. 29 as printed has 1/(2 eps) where the derivation (J1 of Eq. 27 between theta = 0 and pi)
// gives 1/(2 eps^2):
//   Fbar = Rm^2 [ (1-Ri)/eps - (atanh eps - atanh eps Ri)/eps^2 + (atanh eps - atanh eps Rm)
//                 + Ri^2 (atanh eps Rm - atanh eps Ri) ].
// With atanh x = x + phi(x) the 1/eps terms cancel exactly and leave
//   Fbar = Rm^2 [ eps (1-Ri)(1+Ri^2)/2 - (1-eps^2) phi(eps)/eps^2 + phi(eps Ri)/eps^2
//                 - phi(eps Rm) + Ri^2 (phi(eps Rm) - phi(eps Ri)) ].
double force(const double eps, const double Ri)
{
  check(eps, Ri);
  if (eps == 0)
    return 0;
  const double Rm = 0.5 * (1 + Ri), e2 = eps * eps;
  return Rm * Rm *
         (0.5 * eps * (1 - Ri) * (1 + Ri * Ri) - force_eps_term(eps) +
          atanh_minus_x(eps * Ri) / e2 - atanh_minus_x(eps * Rm) +
          Ri * Ri * (atanh_minus_x(eps * Rm) - atanh_minus_x(eps * Ri)));
}

// Eq. 43 as printed has (1/2) ln[(1-eps^2)/(1-eps Ri^2)]; the derivation (J2 of Eq. 42) gives
// (1/eps^2) ln[(1-eps^2)/(1-eps^2 Ri^2)]:
//   Mbar_x = Rm^3 [ ln((1-eps^2)/(1-eps^2 Ri^2))/eps^2 + 2 (atanh eps - atanh eps Rm)/eps
//                   + 2 Ri (atanh eps Rm - atanh eps Ri)/eps ],
// whose O(1) terms cancel exactly; with lambda(y) = ln(1-y) + y:
//   Mbar_x = Rm^3 [ K(eps) - lambda(eps^2 Ri^2)/eps^2 - 2 (1-Ri) phi(eps Rm)/eps
//                   - 2 Ri phi(eps Ri)/eps ].
double restoring_moment(const double eps, const double Ri)
{
  check(eps, Ri);
  if (eps == 0)
    return 0;
  const double Rm = 0.5 * (1 + Ri), e2 = eps * eps;
  return Rm * Rm * Rm *
         (moment_eps_term(eps) - log1m_plus_y(e2 * Ri * Ri) / e2 -
          2 * (1 - Ri) * atanh_minus_x(eps * Rm) / eps - 2 * Ri * atanh_minus_x(eps * Ri) / eps);
}

// Eq. 56 as printed has pi/(2 eps) in front of the arcsines; Eqs. 52-55 give pi/(2 eps^2) (and
// Eq. 52 needs +Ri^2 where it prints -Ri^2):
//   Mbar_z = Rm^3 { pi/(2 eps^2) (asin eps Ri - asin eps) + pi/eps (1-Ri) sqrt(1 - eps^2 Rm^2)
//                   + pi/(2 eps) (Ri sqrt(1 - eps^2 Ri^2) - sqrt(1 - eps^2)) }.
// With asin x = x + alpha(x), sqrt(1 - x^2) = 1 + sigma(x) the 1/eps terms cancel exactly:
//   Mbar_z = pi Rm^3 { (alpha(eps Ri) - alpha(eps))/(2 eps^2) + (1-Ri) sigma(eps Rm)/eps
//                      + (Ri sigma(eps Ri) - sigma(eps))/(2 eps) }.
double transverse_moment(const double eps, const double Ri)
{
  check(eps, Ri);
  if (eps == 0)
    return 0;
  const double Rm = 0.5 * (1 + Ri);
  return M_PI * Rm * Rm * Rm *
         ((asin_minus_x(eps * Ri) - asin_minus_x(eps)) / (2 * eps * eps) +
          (1 - Ri) * sqrt1m_minus_1(eps * Rm) / eps +
          (Ri * sqrt1m_minus_1(eps * Ri) - sqrt1m_minus_1(eps)) / (2 * eps));
}

// Full film: the hydrodynamic pressure is antisymmetric about the tilt line, p sin(theta_E) is
// symmetric, so Mz doubles (Etsion p. 17). Eq. 58 as printed has pi/2 (for pi/eps^2) in front of
// the arcsines and (1 - eps^2) for sqrt(1 - eps^2).
double transverse_moment_full_film(const double eps, const double Ri)
{
  return 2 * transverse_moment(eps, Ri);
}

double force_small_tilt(const double eps, const double Ri)
{
  check(eps, Ri);
  const double Rm = 0.5 * (1 + Ri);
  return eps * std::pow(1 - Ri, 3) * Rm * Rm / 6;
}

double restoring_moment_small_tilt(const double eps, const double Ri)
{
  check(eps, Ri);
  const double Rm = 0.5 * (1 + Ri);
  return eps * eps * std::pow(1 - Ri, 3) * std::pow(Rm, 4) / 6;
}

double transverse_moment_small_tilt(const double eps, const double Ri)
{
  check(eps, Ri);
  const double Rm = 0.5 * (1 + Ri);
  return M_PI * eps * std::pow(1 - Ri, 3) * std::pow(Rm, 3) / 24;
}

double transverse_moment_full_film_small_tilt(const double eps, const double Ri)
{
  return 2 * transverse_moment_small_tilt(eps, Ri);
}

double force_scale(const double viscosity, const double omega, const double clearance,
                   const double outer_radius)
{
  const double a = outer_radius / clearance;
  return 6 * viscosity * omega * a * a * outer_radius * outer_radius;
}

double moment_scale(const double viscosity, const double omega, const double clearance,
                    const double outer_radius)
{
  return force_scale(viscosity, omega, clearance, outer_radius) * outer_radius;
}

TiltLoads loads(const FilmThickness &film, const OperatingConditions &conditions,
                const Cavitation cavitation)
{
  if (film.coning != 0 || film.wave_amplitude != 0 || film.axial_velocity != 0 ||
      film.tilt_rate_x != 0 || film.tilt_rate_y != 0)
    throw std::invalid_argument("Etsion closed forms: need a flat (no coning), non-wavy, "
                                "non-squeezing film");
  // With beta = 0, h = (C0 + z) + gamma r cos(theta - psi): Etsion's C is C0 + z and his
  // theta_E = theta - psi.
  const double C = film.clearance + film.axial_offset;
  const double ro = film.outer_radius, Ri = film.inner_radius / ro;
  TiltLoads out;
  out.eps = film.tilt * ro / C;
  if (out.eps > 1 && out.eps <= 1 + 1e-12) // touch-down set up as gamma = C/ro: round-off only
    out.eps = 1;
  if (!(C > 0) || !(out.eps <= 1))
  {
    std::ostringstream s;
    s << "Etsion closed forms: the film touches down (eps = gamma ro / C = " << out.eps << ")";
    throw std::invalid_argument(s.str());
  }
  // Etsion's omega is the speed of the one moving face: twice the mean surface speed.
  const double omega = conditions.rotor_speed + conditions.stator_speed;
  const double sign = (omega > 0) - (omega < 0);
  const double fs = force_scale(conditions.viscosity, std::abs(omega), C, ro);
  const double ms = fs * ro;
  if (cavitation == Cavitation::half_sommerfeld)
  {
    out.force_z = fs * force(out.eps, Ri);
    out.moment_restoring = ms * restoring_moment(out.eps, Ri);
    out.moment_transverse = sign * ms * transverse_moment(out.eps, Ri);
  }
  else
    out.moment_transverse = sign * ms * transverse_moment_full_film(out.eps, Ri);
  // y = r sin(psi + theta_E), x = r cos(psi + theta_E) (film_loads.h definitions).
  const double cp = std::cos(film.tilt_angle), sp = std::sin(film.tilt_angle);
  out.moment_x = -sp * out.moment_restoring + cp * out.moment_transverse;
  out.moment_y = cp * out.moment_restoring + sp * out.moment_transverse;
  return out;
}
} // namespace etsion

} // namespace sealfe
