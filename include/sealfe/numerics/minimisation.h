// Sampled minimisation of a smooth function of one variable that may have several local minima
// (the film or the pressure around the circumference, an annular-seal design objective): the
// best of equally spaced samples, polished by Brent's method (Boost.Math) between its neighbours.
#pragma once

#include <boost/math/tools/minima.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace sealfe::numerics
{
/// A minimiser and the value there.
struct Minimum
{
  double x = 0, value = std::numeric_limits<double>::infinity();
};

/// Whether the function repeats with period b - a (the samples then cover [a, b) and the polish
/// may step outside [a, b]) or lives on the closed interval [a, b] (the samples include both
/// ends, the polish stays inside and the end points count as candidates).
enum class Domain
{
  periodic,
  interval
};

/// Minimum of f on [a, b] from n_samples >= 2 equally spaced samples, then Brent's method in the
/// bracket of the best sample's neighbours. Brent locates a minimiser only to about the square
/// root of the machine epsilon (relative), which is the accuracy a minimiser of a smooth function
/// has in floating point anyway; the minimum value is found to round-off.
template <typename Function>
Minimum sampled_minimum(Function &&f, const double a, const double b, const unsigned int n_samples,
                        const Domain domain)
{
  const unsigned int n = std::max(n_samples, 2u);
  const double dx = domain == Domain::periodic ? (b - a) / n : (b - a) / (n - 1);
  Minimum best;
  unsigned int best_i = 0;
  for (unsigned int i = 0; i < n; ++i)
  {
    const double x = a + dx * i;
    const double v = f(x);
    if (v < best.value)
    {
      best = {x, v};
      best_i = i;
    }
  }
  double lo = best.x - dx, hi = best.x + dx;
  if (domain == Domain::interval)
  {
    lo = a + dx * (best_i == 0 ? 0 : best_i - 1);
    hi = a + dx * std::min(best_i + 1, n - 1);
  }
  const auto polished =
      boost::math::tools::brent_find_minima(f, lo, hi, std::numeric_limits<double>::digits / 2);
  if (polished.second < best.value)
    best = {polished.first, polished.second};
  return best;
}

/// Maximum of f, as sampled_minimum of -f (the returned value is f's, not -f's).
template <typename Function>
Minimum sampled_maximum(Function &&f, const double a, const double b, const unsigned int n_samples,
                        const Domain domain)
{
  Minimum m = sampled_minimum([&](const double x) { return -f(x); }, a, b, n_samples, domain);
  m.value = -m.value;
  return m;
}

} // namespace sealfe::numerics
