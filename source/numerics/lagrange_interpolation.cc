#include <sealfe/numerics/lagrange_interpolation.h>

#include <algorithm>
#include <stdexcept>

namespace sealfe
{
unsigned int lagrange_interval(const std::vector<double> &v, const double x)
{
  const unsigned int n = v.size();
  if (n < 2)
    throw std::runtime_error("Lagrange interpolation needs at least 2 nodes");
  const unsigned int k = std::upper_bound(v.begin(), v.end(), x) - v.begin();
  return std::min(std::max(k, 1u), n - 1) - 1;
}

LagrangeStencil lagrange_stencil(const std::vector<double> &v, const double x,
                                 const unsigned int points)
{
  const unsigned int n = v.size();
  const unsigned int k = lagrange_interval(v, x);
  const unsigned int width = std::max(2u, std::min(points, n));
  LagrangeStencil s;
  if (width == 2)
  {
    // linear on the interval itself
    const double t = (x - v[k]) / (v[k + 1] - v[k]);
    s.first = k;
    s.weights = {1 - t, t};
    return s;
  }
  // The interval and (width - 2)/2 nodes on its left, shifted inwards at the ends.
  s.first = std::clamp(static_cast<int>(k) + 1 - static_cast<int>(width / 2), 0,
                       static_cast<int>(n - width));
  s.weights.assign(width, 1.0);
  for (unsigned int m = 0; m < width; ++m)
    for (unsigned int l = 0; l < width; ++l)
      if (l != m)
        s.weights[m] *= (x - v[s.first + l]) / (v[s.first + m] - v[s.first + l]);
  return s;
}

} // namespace sealfe
