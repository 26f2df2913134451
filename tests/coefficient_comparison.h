// Comparison of two 3x3 film coefficient matrices (K or D in q = (z, tilt_x, tilt_y)) entry by
// entry, after making them dimensionally uniform: shared by the coefficient validation tests.
#pragma once

#include <sealfe/film/film_coefficients.h>

#include <algorithm>
#include <cmath>

namespace sealfe::test
{
using Matrix3 = FilmCoefficients::Matrix3;

/// K or D made dimensionally uniform: diag(1, 1/ro, 1/ro) M diag(1, 1/ro, 1/ro) (a tilt times ro
/// is a displacement, a moment over ro a force), so that entries can be compared with each other.
inline Matrix3 uniform(const Matrix3 &m, const double ro)
{
  const double w[3] = {1, 1 / ro, 1 / ro};
  Matrix3 u;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      u[i][j] = m[i][j] * w[i] * w[j];
  return u;
}

inline double max_abs(const Matrix3 &m)
{
  double s = 0;
  for (const auto &r : m)
    for (const double v : r)
      s = std::max(s, std::abs(v));
  return s;
}

/// Largest entry-wise relative difference |a - b| / max(|b_ij|, floor * max|b|) of the uniform
/// matrices: relative per entry, and relative to the matrix for entries below `floor` of it.
inline double relative_difference(const Matrix3 &a, const Matrix3 &b, const double ro,
                                  const double floor = 1e-3)
{
  const Matrix3 ua = uniform(a, ro), ub = uniform(b, ro);
  const double scale = max_abs(ub);
  double worst = 0;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      worst = std::max(worst,
                       std::abs(ua[i][j] - ub[i][j]) / std::max(std::abs(ub[i][j]), floor * scale));
  return worst;
}
} // namespace sealfe::test
