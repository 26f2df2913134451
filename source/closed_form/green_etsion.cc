#include <sealfe/closed_form/green_etsion.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
GreenEtsionCoefficients::GreenEtsionCoefficients(const FilmThickness &geometry,
                                                 const OperatingConditions &operating)
    : GreenEtsionCoefficients(geometry.inner_radius, geometry.outer_radius, geometry.clearance,
                              geometry.coning, operating.viscosity,
                              operating.outer_pressure - operating.inner_pressure)
{
}

GreenEtsionCoefficients::GreenEtsionCoefficients(const double inner_radius,
                                                 const double outer_radius, const double clearance,
                                                 const double coning, const double viscosity,
                                                 const double pressure_drop)
    : ri(inner_radius), ro(outer_radius), c0(clearance), beta_star(coning), mu(viscosity),
      dp(pressure_drop)
{
  validate();
}

void GreenEtsionCoefficients::validate() const
{
  std::ostringstream s;
  for (const double v : {ri, ro, c0, beta_star, mu, dp})
    if (!std::isfinite(v))
      throw std::runtime_error("Green-Etsion coefficients: a geometry or operating parameter is "
                               "not a finite number");
  if (!(ri > 0 && ro > ri))
    s << "Green-Etsion coefficients: need 0 < Inner radius < Outer radius (got ri = " << ri
      << " m, ro = " << ro << " m)";
  else if (!(c0 > 0))
    s << "Green-Etsion coefficients: Clearance must be positive (got " << c0 << " m)";
  else if (!(c0 + beta_star * (ro - ri) > 0))
    s << "Green-Etsion coefficients: the coning " << beta_star
      << " rad closes the film at the outer radius (C0 + beta (ro - ri) = "
      << c0 + beta_star * (ro - ri) << " m)";
  else if (!(mu > 0))
    s << "Green-Etsion coefficients: Viscosity must be positive (got " << mu << " Pa s)";
  if (!s.str().empty())
    throw std::runtime_error(s.str());
}

double GreenEtsionCoefficients::normalized_coning() const
{
  return beta_star * ro / c0;
}

double GreenEtsionCoefficients::radius_ratio() const
{
  return ri / ro;
}

double GreenEtsionCoefficients::stiffness_parameter() const
{
  const double Ri = radius_ratio(), Rm = 0.5 * (1 + Ri);
  return (1 - Ri) * Rm / (2 + normalized_coning() * (1 - Ri));
}

double GreenEtsionCoefficients::damping_parameter() const
{
  // G0 = f(x) / (beta^3 (1 - Ri)^2) = (1 - Ri) f(x) / x^3 with f(x) = ln(1 + x) - 2x/(2 + x)
  // and x = beta (1 - Ri). f(x) = x^3/12 - x^4/8 + ... cancels catastrophically for small x (and
  // is 0/0 for a flat face), so the series sum_{n>=3} (-1)^(n+1) (1/n - 1/2^(n-1)) x^(n-3) is
  // used there; it converges for |x| < 1 and 25 terms at |x| < 0.05 leave < 1e-30.
  const double Ri = radius_ratio();
  const double x = normalized_coning() * (1 - Ri);
  double f_over_x3 = 0;
  if (std::abs(x) < 0.05)
  {
    double xp = 1, two_pow = 4; // x^(n-3), 2^(n-1) at n = 3
    for (int n = 3; n < 28; ++n, xp *= x, two_pow *= 2)
      f_over_x3 += ((n % 2) ? 1.0 : -1.0) * (1.0 / n - 1.0 / two_pow) * xp;
  }
  else
    f_over_x3 = (std::log1p(x) - 2 * x / (2 + x)) / (x * x * x);
  return (1 - Ri) * f_over_x3;
}

double GreenEtsionCoefficients::seal_parameter(const double reference_speed) const
{
  const double Ri = radius_ratio();
  return 6 * mu * reference_speed * (ro / c0) * (ro / c0) * (1 - Ri) * (1 - Ri);
}

double GreenEtsionCoefficients::angular_stiffness() const
{
  const double E0 = stiffness_parameter();
  return M_PI * dp * (normalized_coning() * radius_ratio() - 1) * E0 * E0 * std::pow(ro, 4) / c0;
}

double GreenEtsionCoefficients::angular_damping() const
{
  // d11 = 2 pi Rm^3 G0 S ro^4 / (C0 omega_ref); S is proportional to omega_ref, so any reference
  // speed gives the same dimensional damping.
  const double Rm = 0.5 * (1 + radius_ratio());
  const double omega_ref = 1.0;
  return 2 * M_PI * Rm * Rm * Rm * damping_parameter() * seal_parameter(omega_ref) *
         std::pow(ro, 4) / (c0 * omega_ref);
}

double GreenEtsionCoefficients::axial_stiffness() const
{
  const double L = ro - ri, rm = 0.5 * (ri + ro);
  const double hsum = 2 * c0 + beta_star * L; // h_i + h_o
  return 2 * M_PI * dp * rm * L * L * beta_star / (hsum * hsum);
}

double GreenEtsionCoefficients::axial_damping() const
{
  const double rm = 0.5 * (ri + ro);
  return 2 * angular_damping() / (rm * rm);
}

double GreenEtsionCoefficients::cross_coupled_stiffness(const double rotor_speed,
                                                        const double stator_speed) const
{
  return 0.5 * (rotor_speed + stator_speed) * angular_damping();
}

FilmCoefficients GreenEtsionCoefficients::coefficients(const double rotor_speed,
                                                       const double stator_speed) const
{
  FilmCoefficients f;
  f.level = 0;
  f.model = "closed form (Green & Etsion narrow seal)";
  f.rotor_speed = rotor_speed;
  f.stator_speed = stator_speed;
  const double k = angular_stiffness(), d = angular_damping();
  const double c = cross_coupled_stiffness(rotor_speed, stator_speed);
  f.stiffness = {{{{axial_stiffness(), 0, 0}}, {{0, k, c}}, {{0, -c, k}}}};
  f.damping = {{{{axial_damping(), 0, 0}}, {{0, d, 0}}, {{0, 0, d}}}};
  return f;
}

} // namespace sealfe
