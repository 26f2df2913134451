#include <sealfe/dynamics/angular_dynamics.h>
#include <sealfe/dynamics/routh_hurwitz.h>
#include <sealfe/numerics/polynomial.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <cmath>
#include <stdexcept>

namespace sealfe
{
using cplx = std::complex<double>;
namespace
{
using Poly = std::vector<cplx>; // coefficients, lowest power first

/// det H by LU (LAPACK); 0 for a singular H.
double determinant(dealii::LAPACKFullMatrix<double> &H)
{
  try
  {
    H.compute_lu_factorization();
  }
  catch (const dealii::ExceptionBase &)
  {
    return 0; // exactly singular
  }
  return H.determinant();
}
} // namespace

std::vector<double> hurwitz_determinants(const std::vector<double> &coeffs)
{
  std::vector<double> a = coeffs;
  while (a.size() > 1 && a.back() == 0.0)
    a.pop_back();
  const int n = static_cast<int>(a.size()) - 1;
  // lambda = L s with L = (|a_0|/|a_n|)^(1/n) balances the coefficients; the Hurwitz minors of
  // the scaled polynomial are positive multiples of the original ones.
  if (a[0] != 0.0 && n > 0)
  {
    const double L = std::pow(std::abs(a[0]) / std::abs(a[n]), 1.0 / n);
    double big = 0;
    for (int k = 0; k <= n; ++k)
    {
      a[k] *= std::pow(L, k);
      big = std::max(big, std::abs(a[k]));
    }
    for (auto &v : a)
      v /= big;
  }
  auto coef = [&](int k) { return (k < 0 || k > n) ? 0.0 : a[k]; };
  // Hurwitz matrix of a_n s^n + ... + a_0: H_ij = a_{n - (2j - i)} (1-based i, j)
  std::vector<double> minors;
  for (int m = 1; m <= n; ++m)
  {
    dealii::LAPACKFullMatrix<double> H(m, m);
    for (int i = 1; i <= m; ++i)
      for (int j = 1; j <= m; ++j)
        H(i - 1, j - 1) = coef(n - (2 * j - i));
    minors.push_back(determinant(H));
  }
  return minors;
}

bool is_hurwitz_stable(const std::vector<double> &a)
{
  if (!(a.back() > 0))
    return false;
  for (const double d : hurwitz_determinants(a))
    if (!(d > 0))
      return false;
  return true;
}

std::vector<double>
AngularSealDynamics::hurwitz_polynomial_by_product(const double rotor_speed,
                                                   const double stator_speed) const
{
  const TiltFilm t = TiltFilm::of(film(rotor_speed, stator_speed));
  if (!film(rotor_speed, stator_speed).tilt_block_is_isotropic(1e-9) ||
      std::abs(t.e) > 1e-12 * std::abs(t.d))
    throw std::runtime_error("Seal dynamics: the Routh-Hurwitz route needs an isotropic film "
                             "tilt block without cross-coupled damping; use Criterion = "
                             "eigenvalues");
  // Complex equation of ring n (Wileman & Green Eq. 3): I lambda^2 + (d - i J omega) lambda + (k -
  // i D) with d = d11 + d_s, k = k11 + k_s, D = c + omega d_rot; coupling -(d11 lambda + k11 - i
  // c).
  auto ring_poly = [&](const RingProperties &r, const double omega)
  {
    return Poly{cplx(t.k + r.support_stiffness, -(t.c + omega * r.rotating_damping)),
                cplx(t.d + r.support_damping, -r.polar_inertia * omega),
                cplx(r.transverse_inertia, 0)};
  };
  Poly P;
  if (stator_is_flexible() && rotor_is_flexible())
  {
    const Poly coupling{cplx(t.k, -t.c), cplx(t.d, 0)};
    P = polynomial_sum(
        polynomial_product(ring_poly(stator, stator_speed), ring_poly(rotor, rotor_speed)),
        polynomial_product(coupling, coupling), -1);
  }
  else if (stator_is_flexible())
    P = ring_poly(stator, stator_speed);
  else
    P = ring_poly(rotor, rotor_speed);
  Poly Pbar(P.size());
  for (unsigned int i = 0; i < P.size(); ++i)
    Pbar[i] = std::conj(P[i]);
  const Poly R = polynomial_product(P, Pbar);
  std::vector<double> a(R.size());
  for (unsigned int i = 0; i < R.size(); ++i)
    a[i] = R[i].real();
  return a;
}

std::vector<double> AngularSealDynamics::hurwitz_polynomial(const double rotor_speed,
                                                            const double stator_speed) const
{
  if (!(stator_is_flexible() && rotor_is_flexible()))
    return hurwitz_polynomial_by_product(rotor_speed, stator_speed);
  const FilmCoefficients fc = film(rotor_speed, stator_speed);
  const TiltFilm t = TiltFilm::of(fc);
  if (!fc.tilt_block_is_isotropic(1e-9) || std::abs(t.e) > 1e-12 * std::abs(t.d))
    throw std::runtime_error("Seal dynamics: the Routh-Hurwitz route needs an isotropic film "
                             "tilt block without cross-coupled damping; use Criterion = "
                             "eigenvalues");
  // Wileman & Green Appendix B, element 2 = stator ring, element 1 = rotor ring. The printed a_2
  // has "d k11 D11" in its last factor where 2 k11 D11 belongs (the same factor appears correctly
  // in a_3, a_1 and a_0).
  const double I2 = stator.transverse_inertia, I1 = rotor.transverse_inertia;
  const double J2w2 = stator.polar_inertia * stator_speed, J1w1 = rotor.polar_inertia * rotor_speed;
  const double k11 = t.k, d11 = t.d, D11 = t.c;
  const double k2 = k11 + stator.support_stiffness, k1 = k11 + rotor.support_stiffness;
  const double d2 = d11 + stator.support_damping, d1 = d11 + rotor.support_damping;
  const double D2 = D11 + stator_speed * stator.rotating_damping;
  const double D1 = D11 + rotor_speed * rotor.rotating_damping;
  const double A = I2 * d1 + I1 * d2;
  const double B = I2 * J1w1 + I1 * J2w2;
  const double C = I2 * k1 + d2 * d1 - J2w2 * J1w1 + I1 * k2 - d11 * d11;
  const double E = d2 * k1 - D1 * J2w2 + d1 * k2 - D2 * J1w1 - 2 * d11 * k11;
  const double F = I2 * D1 + J2w2 * d1 + J1w1 * d2 + I1 * D2;
  const double G = J2w2 * k1 + D1 * d2 + J1w1 * k2 + D2 * d1 - 2 * d11 * D11;
  const double H = k2 * k1 - D2 * D1 - k11 * k11 + D11 * D11;
  const double P = D2 * k1 + D1 * k2 - 2 * k11 * D11;
  std::vector<double> a(9);
  a[8] = I1 * I1 * I2 * I2;
  a[7] = 2 * I1 * I2 * A;
  a[6] = A * A + B * B + 2 * I1 * I2 * C;
  a[5] = 2 * A * C + 2 * I1 * I2 * E + 2 * B * F;
  a[4] = C * C + 2 * A * E + 2 * I1 * I2 * H + F * F + 2 * B * G;
  a[3] = 2 * B * P + 2 * F * G + 2 * A * H + 2 * C * E;
  a[2] = E * E + 2 * C * H + G * G + 2 * F * P;
  a[1] = 2 * E * H + 2 * G * P;
  a[0] = H * H + P * P;
  return a;
}

std::vector<double> AngularSealDynamics::hurwitz_determinants(const std::vector<double> &coeffs)
{
  return sealfe::hurwitz_determinants(coeffs);
}

bool AngularSealDynamics::is_stable_routh_hurwitz(const double rotor_speed,
                                                  const double stator_speed) const
{
  return is_hurwitz_stable(hurwitz_polynomial(rotor_speed, stator_speed));
}

} // namespace sealfe
