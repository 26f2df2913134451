#include <sealfe/closed_form/narrow_groove.h>

#include <cmath>
#include <vector>

namespace sealfe::closed_form
{
namespace
{
struct Zone
{
  double a, b;     // radii
  double pumping;  // C1 = (12 mu / k) sigma w sin cos Delta / 4: p gains C1 (r^2 - a^2)
  double pressure; // 12 mu / (2 pi k): p loses Q times this times ln(r / a)
};

std::vector<Zone> zones(const NarrowGrooveSeal &s)
{
  const double h = s.film, hg = s.film + s.depth, f = s.groove_fraction;
  const double mean1 = f * hg + (1 - f) * h;
  const double mean3 = f * hg * hg * hg + (1 - f) * h * h * h;
  const double mean_m2 = f / (hg * hg) + (1 - f) / (h * h);
  const double mean_m3 = f / (hg * hg * hg) + (1 - f) / (h * h * h);
  const double sn = std::sin(s.spiral_angle), cs = std::cos(s.spiral_angle);
  const double k_groove = mean3 * sn * sn + cs * cs / mean_m3;
  const double delta = mean1 - mean_m2 / mean_m3;
  const double sigma = s.pump_inward ? -1.0 : 1.0;
  const double mu12 = 12 * s.viscosity;
  std::vector<Zone> z;
  if (s.rgi > s.ri)
    z.push_back({s.ri, s.rgi, 0.0, mu12 / (2 * M_PI * h * h * h)});
  z.push_back({s.rgi, s.rgo, mu12 / k_groove * sigma * s.relative_speed * sn * cs * delta / 4,
               mu12 / (2 * M_PI * k_groove)});
  if (s.rgo < s.ro)
    z.push_back({s.rgo, s.ro, 0.0, mu12 / (2 * M_PI * h * h * h)});
  return z;
}

double flow(const NarrowGrooveSeal &s, const std::vector<Zone> &z)
{
  // po - pi = sum C1 (b^2 - a^2) - Q sum C2 ln(b / a)
  double gain = 0, resistance = 0;
  for (const Zone &q : z)
  {
    gain += q.pumping * (q.b * q.b - q.a * q.a);
    resistance += q.pressure * std::log(q.b / q.a);
  }
  return (gain - (s.outer_pressure - s.inner_pressure)) / resistance;
}
} // namespace

double NarrowGrooveSeal::pressure(const double r) const
{
  const auto z = zones(*this);
  const double Q = flow(*this, z);
  double p = inner_pressure;
  for (const Zone &q : z)
  {
    const double b = std::min(r, q.b);
    if (b <= q.a)
      break;
    p += q.pumping * (b * b - q.a * q.a) - Q * q.pressure * std::log(b / q.a);
  }
  return p;
}

NarrowGrooveSeal::Result NarrowGrooveSeal::solve() const
{
  const auto z = zones(*this);
  const double Q = flow(*this, z);
  Result out{0, Q, 0, 0};
  double p_a = inner_pressure;
  for (const Zone &q : z)
  {
    // int_a^b 2 pi r (p_a - p_ref + C1 (r^2 - a^2) - Q C2 ln(r / a)) dr
    const double a = q.a, b = q.b, c1 = q.pumping, c2 = Q * q.pressure;
    const auto r_ln_r = [](const double r) { return 0.5 * r * r * std::log(r) - 0.25 * r * r; };
    out.force +=
        2 * M_PI *
        ((p_a - reference_pressure - c1 * a * a + c2 * std::log(a)) * 0.5 * (b * b - a * a) +
         c1 * 0.25 * (b * b * b * b - a * a * a * a) - c2 * (r_ln_r(b) - r_ln_r(a)));
    const double p_b = p_a + c1 * (b * b - a * a) - c2 * std::log(b / a);
    if (a == rgi)
      out.p_groove_inner = p_a;
    if (b == rgo)
      out.p_groove_outer = p_b;
    p_a = p_b;
  }
  return out;
}

} // namespace sealfe::closed_form
