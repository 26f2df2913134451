// Piecewise Lagrange interpolation on sorted nodes: the stencil of the (up to) 4 nodes around the
// interval that contains x, shifted inwards at the ends. Used by the coefficient table (per axis)
// and by the speed interpolation of the film coefficients in the dynamics.
#pragma once

#include <vector>

namespace sealfe
{
/// The nodes v[first], ..., v[first + weights.size() - 1] and their weights: f(x) ~ sum_m
/// weights[m] f(v[first + m]).
struct LagrangeStencil
{
  unsigned int first = 0;
  std::vector<double> weights;
};

/// Index k of the interval v[k] <= x <= v[k + 1] of sorted nodes v (n >= 2); x outside [v[0],
/// v[n-1]] gives the first or last interval.
unsigned int lagrange_interval(const std::vector<double> &nodes, double x);

/// Lagrange interpolation at x on min(points, n) nodes around the interval of x (points = 2:
/// linear on the interval itself, weights (1 - t, t); 4: cubic on the interval and one node on
/// each side, error O(h^4); near the ends the stencil shifts inwards, keeping the degree). The
/// nodes must be sorted and distinct, n >= 2. No clamping: x outside the nodes extrapolates.
LagrangeStencil lagrange_stencil(const std::vector<double> &nodes, double x,
                                 unsigned int points = 4);

} // namespace sealfe
