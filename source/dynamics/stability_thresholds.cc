#include <sealfe/dynamics/angular_dynamics.h>
#include <sealfe/dynamics/stability_thresholds.h>
#include <sealfe/numerics/polynomial.h>

#include <boost/math/tools/roots.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sealfe
{
double refine_verdict_change(const std::function<bool(double)> &verdict, const double a,
                             const double b)
{
  // The verdict as a sign, +1 where it equals the verdict at a: boost's bisection keeps the
  // bracket on which it changes. Stop at |b - a| <= 1e-10 max(1, |a|, |b|).
  const bool at_a = verdict(a);
  const auto sign = [&](const double w) { return verdict(w) == at_a ? 1.0 : -1.0; };
  const auto converged = [](const double lo, const double hi) {
    return std::abs(hi - lo) <= 1e-10 * std::max({1.0, std::abs(lo), std::abs(hi)});
  };
  std::uintmax_t max_iterations = 400;
  const std::pair<double, double> bracket =
      boost::math::tools::bisect(sign, std::min(a, b), std::max(a, b), converged, max_iterations);
  return 0.5 * (bracket.first + bracket.second);
}

std::vector<AngularSealDynamics::SpeedInterval> AngularSealDynamics::stable_speed_intervals(
    const SweptRing swept, const double fixed_speed, const double from, const double to,
    const unsigned int n_grid, const Criterion criterion) const
{
  if (!(to > from) || n_grid < 2)
    throw std::runtime_error("Seal dynamics: the speed sweep needs 'to' > 'from' and at least 2 "
                             "grid points");
  auto stable = [&](const double w)
  {
    const double wr = (swept == SweptRing::rotor) ? w : fixed_speed;
    const double ws = (swept == SweptRing::stator) ? w : fixed_speed;
    return criterion == Criterion::eigenvalues ? is_stable(wr, ws)
                                               : is_stable_routh_hurwitz(wr, ws);
  };
  std::vector<SpeedInterval> intervals;
  const double h = (to - from) / (n_grid - 1);
  bool previous = stable(from);
  SpeedInterval current{from, to, true, true};
  for (unsigned int i = 1; i < n_grid; ++i)
  {
    const double w = (i + 1 == n_grid) ? to : from + i * h, w_prev = from + (i - 1) * h;
    const bool now = stable(w);
    if (now != previous)
    {
      const double edge = refine_verdict_change(stable, w_prev, w);
      if (now)
        current = {edge, to, false, true};
      else
      {
        current.high = edge;
        current.high_at_search_limit = false;
        intervals.push_back(current);
      }
    }
    previous = now;
  }
  if (previous)
    intervals.push_back(current);
  return intervals;
}

std::vector<double> AngularSealDynamics::undamped_threshold_speeds(const SweptRing swept,
                                                                   const double fixed_speed) const
{
  const FilmCoefficients fc = film(fixed_speed, fixed_speed);
  const TiltFilm t = TiltFilm::of(fc);
  if (std::abs(t.c - fixed_speed * t.d) > 1e-9 * std::abs(fixed_speed * t.d) + 1e-300)
    throw std::runtime_error(
        "Seal dynamics: the closed-form threshold (Wileman & Green Eq. 17) needs "
        "a film with cross-coupled stiffness (omega1 + omega2)/2 d11");
  // Polynomials in psi (lowest power first); the swept speed is 2 psi - fixed_speed.
  using RPoly = std::vector<double>;
  const auto mul = polynomial_product<double>;
  const auto sum = polynomial_sum<double>;
  const RPoly omega_swept{-fixed_speed, 2.0}, omega_fixed{fixed_speed};
  const RPoly w_rotor = (swept == SweptRing::rotor) ? omega_swept : omega_fixed;
  const RPoly w_stator = (swept == SweptRing::stator) ? omega_swept : omega_fixed;
  const RPoly psi{0.0, 1.0};
  // One ring n: -I psi^2 + J omega_n psi + (k11 + k_s) = 0 (psi = (omega1 + omega2)/2).
  auto ring_term = [&](const RingProperties &r, const RPoly &w)
  {
    RPoly p =
        sum(mul({-r.transverse_inertia}, mul(psi, psi)), mul({r.polar_inertia}, mul(w, psi)), 1);
    return sum(p, {t.k + r.support_stiffness}, 1);
  };
  RPoly p;
  if (stator_is_flexible() && rotor_is_flexible())
    // Eq. 17 is the determinant of Eq. 16: ring_2 * ring_1 - k11^2
    p = sum(mul(ring_term(stator, w_stator), ring_term(rotor, w_rotor)), {t.k * t.k}, -1);
  else if (stator_is_flexible())
    p = ring_term(stator, w_stator);
  else
    p = ring_term(rotor, w_rotor);
  std::vector<double> speeds;
  for (const double r : real_polynomial_roots(p))
    speeds.push_back(2 * r - fixed_speed);
  std::sort(speeds.begin(), speeds.end());
  return speeds;
}

} // namespace sealfe
