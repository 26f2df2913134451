#include <sealfe/dynamics/whirl_modes.h>

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>

namespace sealfe
{
namespace
{
using cplx = std::complex<double>;

/// An eigenvector of the real matrix A for its eigenvalue lambda: inverse iteration with the
/// shift sigma = lambda + 1e-9 max(|lambda|, 1) (A - sigma I is then invertible but nearly
/// singular, so two solves turn any start vector into the eigenvector to round-off, unless
/// another eigenvalue lies as close).
std::vector<cplx> eigenvector(const dealii::FullMatrix<double> &A, const cplx lambda)
{
  const unsigned int m = A.m();
  const cplx sigma = lambda + 1e-9 * std::max(std::abs(lambda), 1.0);
  dealii::LAPACKFullMatrix<cplx> B(m, m);
  for (unsigned int i = 0; i < m; ++i)
    for (unsigned int j = 0; j < m; ++j)
      B(i, j) = A(i, j) - (i == j ? sigma : cplx(0));
  B.compute_lu_factorization();
  dealii::Vector<cplx> v(m);
  for (unsigned int i = 0; i < m; ++i)
    v(i) = cplx(1.0 + 0.1 * i, 0.05 * i); // no symmetry that could miss a component
  for (unsigned int step = 0; step < 2; ++step)
  {
    B.solve(v);
    double norm = 0;
    for (unsigned int i = 0; i < m; ++i)
      norm = std::max(norm, std::abs(v(i)));
    v /= cplx(norm);
  }
  return std::vector<cplx>(v.begin(), v.end());
}
} // namespace

std::vector<WhirlMode> whirl_modes(const AngularSealDynamics &dynamics, const double rotor_speed,
                                   const double stator_speed)
{
  const dealii::FullMatrix<double> A =
      dynamics.matrices(rotor_speed, stator_speed).first_order_matrix();
  const unsigned int n = A.m() / 2; // tilt dofs: (stator x, y, rotor x, y), rigid rings left out
  const bool stator_first = dynamics.stator_is_flexible();
  std::vector<WhirlMode> modes;
  for (const cplx &lambda : dynamics.eigenvalues(rotor_speed, stator_speed))
  {
    if (lambda.imag() < 0)
      continue; // the conjugate of a pair already taken
    WhirlMode mode;
    mode.eigenvalue = lambda;
    mode.damping_ratio = std::abs(lambda) > 0 ? -lambda.real() / std::abs(lambda) : 0.0;
    const std::vector<cplx> v = eigenvector(A, lambda);
    double forward = 0, backward = 0, stator = 0, total = 0;
    for (unsigned int ring = 0; ring < n / 2; ++ring)
    {
      const cplx x = v[2 * ring], y = v[2 * ring + 1];
      forward += std::norm(x + cplx(0, 1) * y);
      backward += std::norm(x - cplx(0, 1) * y);
      const double share = std::norm(x) + std::norm(y);
      total += share;
      if (ring == 0 && stator_first)
        stator += share;
    }
    mode.stator_share = total > 0 ? stator / total : 0.0;
    mode.whirl_frequency =
        lambda.imag() == 0 ? 0.0 : (forward >= backward ? lambda.imag() : -lambda.imag());
    modes.push_back(mode);
  }
  return modes;
}
} // namespace sealfe
