#include <sealfe/numerics/polynomial.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <cmath>
#include <complex>
#include <stdexcept>

namespace sealfe
{
std::vector<double> real_polynomial_roots(std::vector<double> p)
{
  while (!p.empty() && std::abs(p.back()) == 0.0)
    p.pop_back();
  const int n = static_cast<int>(p.size()) - 1;
  std::vector<double> roots;
  if (n < 1)
    return roots;
  dealii::LAPACKFullMatrix<double> C(n, n);
  for (int i = 0; i < n; ++i)
  {
    C(0, i) = -p[n - 1 - i] / p[n];
    if (i > 0)
      C(i, i - 1) = 1;
  }
  for (const double c : p)
    if (!std::isfinite(c)) // LAPACK would stop the program on a nan
      throw std::runtime_error("polynomial roots: a coefficient is not a finite number");
  C.compute_eigenvalues();
  for (int i = 0; i < n; ++i)
  {
    const std::complex<double> z = C.eigenvalue(i);
    if (std::abs(z.imag()) <= 1e-7 * std::max(1.0, std::abs(z)))
      roots.push_back(z.real());
  }
  std::sort(roots.begin(), roots.end());
  return roots;
}

} // namespace sealfe
