// Dense polynomials as coefficient vectors, lowest power first: products, sums and the real roots.
#pragma once

#include <algorithm>
#include <vector>

namespace sealfe
{
/// a b (real or complex coefficients).
template <typename T>
std::vector<T> polynomial_product(const std::vector<T> &a, const std::vector<T> &b)
{
  std::vector<T> c(a.size() + b.size() - 1, T(0));
  for (unsigned int i = 0; i < a.size(); ++i)
    for (unsigned int j = 0; j < b.size(); ++j)
      c[i + j] += a[i] * b[j];
  return c;
}

/// a + factor b.
template <typename T>
std::vector<T> polynomial_sum(const std::vector<T> &a, const std::vector<T> &b,
                              const double factor = 1)
{
  std::vector<T> c(std::max(a.size(), b.size()), T(0));
  for (unsigned int i = 0; i < a.size(); ++i)
    c[i] += a[i];
  for (unsigned int i = 0; i < b.size(); ++i)
    c[i] += factor * b[i];
  return c;
}

/// Real roots, ascending, of a real polynomial: the eigenvalues of its companion matrix (LAPACK)
/// whose imaginary part is below 1e-7 max(1, |root|).
std::vector<double> real_polynomial_roots(std::vector<double> coefficients);

} // namespace sealfe
