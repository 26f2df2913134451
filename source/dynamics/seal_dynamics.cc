#include <sealfe/closed_form/green_etsion.h>
#include <sealfe/coefficients/coefficient_table.h>
#include <sealfe/dynamics/seal_dynamics.h>

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>
#include <deal.II/sundials/arkode.h>

#include <arkode/arkode_arkstep.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
using cplx = std::complex<double>;
namespace
{
const cplx I(0.0, 1.0);

/// Dense complex Gaussian elimination with partial pivoting (the systems here have <= 8
/// unknowns; a singular matrix means the seal sits exactly on a resonance of an undamped mode).
std::vector<cplx> solve_dense(std::vector<std::vector<cplx>> A, std::vector<cplx> b)
{
  const unsigned int n = b.size();
  for (unsigned int k = 0; k < n; ++k)
  {
    unsigned int p = k;
    for (unsigned int i = k + 1; i < n; ++i)
      if (std::abs(A[i][k]) > std::abs(A[p][k]))
        p = i;
    if (std::abs(A[p][k]) == 0.0)
      throw std::runtime_error("Seal dynamics: singular dynamic stiffness (an undamped mode is "
                               "excited exactly at its natural frequency)");
    std::swap(A[k], A[p]);
    std::swap(b[k], b[p]);
    for (unsigned int i = k + 1; i < n; ++i)
    {
      const cplx f = A[i][k] / A[k][k];
      for (unsigned int j = k; j < n; ++j)
        A[i][j] -= f * A[k][j];
      b[i] -= f * b[k];
    }
  }
  std::vector<cplx> x(n);
  for (int i = n - 1; i >= 0; --i)
  {
    cplx s = b[i];
    for (unsigned int j = i + 1; j < n; ++j)
      s -= A[i][j] * x[j];
    x[i] = s / A[i][i];
  }
  return x;
}

double determinant(std::vector<std::vector<double>> A)
{
  const unsigned int n = A.size();
  double det = 1;
  for (unsigned int k = 0; k < n; ++k)
  {
    unsigned int p = k;
    for (unsigned int i = k + 1; i < n; ++i)
      if (std::abs(A[i][k]) > std::abs(A[p][k]))
        p = i;
    if (A[p][k] == 0.0)
      return 0;
    if (p != k)
    {
      std::swap(A[k], A[p]);
      det = -det;
    }
    det *= A[k][k];
    for (unsigned int i = k + 1; i < n; ++i)
    {
      const double f = A[i][k] / A[k][k];
      for (unsigned int j = k; j < n; ++j)
        A[i][j] -= f * A[k][j];
    }
  }
  return det;
}

using Poly = std::vector<cplx>; // coefficients, lowest power first
Poly multiply(const Poly &a, const Poly &b)
{
  Poly c(a.size() + b.size() - 1, 0.0);
  for (unsigned int i = 0; i < a.size(); ++i)
    for (unsigned int j = 0; j < b.size(); ++j)
      c[i + j] += a[i] * b[j];
  return c;
}
Poly add(const Poly &a, const Poly &b, const double sb = 1)
{
  Poly c(std::max(a.size(), b.size()), 0.0);
  for (unsigned int i = 0; i < a.size(); ++i)
    c[i] += a[i];
  for (unsigned int i = 0; i < b.size(); ++i)
    c[i] += sb * b[i];
  return c;
}

/// Real roots of a real polynomial (lowest power first) from the eigenvalues of its companion
/// matrix (LAPACK).
std::vector<double> real_roots(std::vector<double> p)
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
  C.compute_eigenvalues();
  for (int i = 0; i < n; ++i)
  {
    const cplx z = C.eigenvalue(i);
    if (std::abs(z.imag()) <= 1e-7 * std::max(1.0, std::abs(z)))
      roots.push_back(z.real());
  }
  std::sort(roots.begin(), roots.end());
  return roots;
}

/// The rotationally invariant tilt coefficients of a film.
struct TiltFilm
{
  double k, c, d, e;
};
TiltFilm tilt_film(const FilmCoefficients &f)
{
  return {f.tilt_direct_stiffness(), f.tilt_cross_stiffness(), f.tilt_direct_damping(),
          f.tilt_cross_damping()};
}
} // namespace

std::string to_string(const SealConfiguration c)
{
  switch (c)
  {
  case SealConfiguration::fms:
    return "FMS";
  case SealConfiguration::fmr:
    return "FMR";
  case SealConfiguration::fmrr:
    return "FMRR";
  case SealConfiguration::fms_flexible_rotor:
    return "FMS with flexible rotor";
  }
  return "";
}

SealConfiguration configuration_from_string(const std::string &name)
{
  for (const auto c : {SealConfiguration::fms, SealConfiguration::fmr, SealConfiguration::fmrr,
                       SealConfiguration::fms_flexible_rotor})
    if (to_string(c) == name)
      return c;
  throw std::runtime_error("Seal dynamics: Configuration '" + name +
                           "' is not one of FMS, FMR, FMRR, FMS with flexible rotor");
}

double ForcedResponse::max_magnitude(const std::vector<HarmonicTilt> &h)
{
  double s = 0;
  for (const auto &x : h)
    s += std::abs(x.forward) + std::abs(x.backward);
  return s;
}

HarmonicTilt ForcedResponse::at_frequency(const std::vector<HarmonicTilt> &h, const double W)
{
  for (const auto &x : h)
    if (x.frequency == W)
      return x;
  HarmonicTilt none;
  none.frequency = W;
  return none;
}

AngularSealDynamics::AngularSealDynamics(const SealConfiguration configuration,
                                         const RingProperties &rotor_ring,
                                         const RingProperties &stator_ring, FilmModel film_model)
    : config(configuration), rotor(rotor_ring), stator(stator_ring), film(std::move(film_model))
{
}

bool AngularSealDynamics::rotor_is_flexible() const
{
  return config != SealConfiguration::fms;
}

bool AngularSealDynamics::stator_is_flexible() const
{
  return config != SealConfiguration::fmr;
}

unsigned int AngularSealDynamics::n_dofs() const
{
  return 2 * (rotor_is_flexible() + stator_is_flexible());
}

std::vector<unsigned int> AngularSealDynamics::dof_slots() const
{
  // slots 0, 1: stator tilt x, y; slots 2, 3: rotor tilt x, y
  std::vector<unsigned int> s;
  if (stator_is_flexible())
    s.insert(s.end(), {0, 1});
  if (rotor_is_flexible())
    s.insert(s.end(), {2, 3});
  return s;
}

void AngularSealDynamics::validate() const
{
  auto check = [](const RingProperties &r, const std::string &name, const bool flexible)
  {
    std::ostringstream s;
    for (const double v :
         {r.transverse_inertia, r.polar_inertia, r.support_stiffness, r.support_damping,
          r.rotating_damping, r.support_misalignment, r.dynamic_misalignment})
      if (!std::isfinite(v))
        throw std::runtime_error("Seal dynamics: a property of the " + name +
                                 " is not a finite number");
    if (!flexible)
      return;
    if (!(r.transverse_inertia > 0))
      s << "Seal dynamics: " << name << ": Transverse inertia must be positive for a flexibly "
        << "mounted ring (got " << r.transverse_inertia << " kg m^2)";
    else if (r.polar_inertia < 0)
      s << "Seal dynamics: " << name << ": Polar inertia must not be negative (got "
        << r.polar_inertia << " kg m^2)";
    else if (r.support_stiffness < 0)
      s << "Seal dynamics: " << name << ": Support stiffness must not be negative (got "
        << r.support_stiffness << " N m/rad)";
    else if (r.support_damping < 0 || r.rotating_damping < 0)
      s << "Seal dynamics: " << name << ": Support damping and Rotating damping must not be "
        << "negative";
    if (!s.str().empty())
      throw std::runtime_error(s.str());
  };
  check(rotor, "Rotor ring", rotor_is_flexible());
  check(stator, "Stator ring", stator_is_flexible());
}

SecondOrderSystem AngularSealDynamics::matrices(const double rotor_speed,
                                                const double stator_speed) const
{
  const FilmCoefficients f = film(rotor_speed, stator_speed);
  // Full 4-slot matrices first (stator x, y, rotor x, y), then keep the flexible rings' rows.
  dealii::FullMatrix<double> M(4, 4), C(4, 4), K(4, 4);
  // Film on the stator face: -K_t q - D_t q_dot with q = t_stator - t_rotor; on the rotor face the
  // opposite. Blocks [[+, -], [-, +]].
  for (unsigned int a = 0; a < 2; ++a)
    for (unsigned int b = 0; b < 2; ++b)
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int j = 0; j < 2; ++j)
        {
          const double sign = (a == b) ? 1.0 : -1.0;
          K(2 * a + i, 2 * b + j) += sign * f.stiffness[1 + i][1 + j];
          C(2 * a + i, 2 * b + j) += sign * f.damping[1 + i][1 + j];
        }
  auto ring = [&](const RingProperties &r, const double omega, const unsigned int o)
  {
    M(o, o) = M(o + 1, o + 1) = r.transverse_inertia;
    K(o, o) += r.support_stiffness;
    K(o + 1, o + 1) += r.support_stiffness;
    C(o, o) += r.support_damping;
    C(o + 1, o + 1) += r.support_damping;
    // gyroscopic: I_t t_ddot_x + J omega t_dot_y, I_t t_ddot_y - J omega t_dot_x (Wileman & Green
    // Eq. 2)
    C(o, o + 1) += r.polar_inertia * omega;
    C(o + 1, o) -= r.polar_inertia * omega;
    // rotating support damping: + omega d_rot t_y in x, - omega d_rot t_x in y
    K(o, o + 1) += omega * r.rotating_damping;
    K(o + 1, o) -= omega * r.rotating_damping;
  };
  ring(stator, stator_speed, 0);
  ring(rotor, rotor_speed, 2);
  const auto slots = dof_slots();
  const unsigned int n = slots.size();
  SecondOrderSystem s{dealii::FullMatrix<double>(n, n), dealii::FullMatrix<double>(n, n),
                      dealii::FullMatrix<double>(n, n)};
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
    {
      s.mass(i, j) = M(slots[i], slots[j]);
      s.damping(i, j) = C(slots[i], slots[j]);
      s.stiffness(i, j) = K(slots[i], slots[j]);
    }
  return s;
}

std::vector<cplx> AngularSealDynamics::eigenvalues(const double rotor_speed,
                                                   const double stator_speed) const
{
  const SecondOrderSystem s = matrices(rotor_speed, stator_speed);
  const unsigned int n = s.mass.m();
  // First-order form y = (q, q_dot): y_dot = [[0, 1], [-M^-1 K, -M^-1 C]] y; M is diagonal.
  dealii::LAPACKFullMatrix<double> A(2 * n, 2 * n);
  for (unsigned int i = 0; i < n; ++i)
  {
    A(i, n + i) = 1;
    for (unsigned int j = 0; j < n; ++j)
    {
      A(n + i, j) = -s.stiffness(i, j) / s.mass(i, i);
      A(n + i, n + j) = -s.damping(i, j) / s.mass(i, i);
    }
  }
  A.compute_eigenvalues();
  std::vector<cplx> lambda(2 * n);
  for (unsigned int i = 0; i < 2 * n; ++i)
    lambda[i] = A.eigenvalue(i);
  std::sort(lambda.begin(), lambda.end(),
            [](const cplx &a, const cplx &b)
            { return a.real() > b.real() || (a.real() == b.real() && a.imag() > b.imag()); });
  return lambda;
}

double AngularSealDynamics::growth_rate(const double rotor_speed, const double stator_speed) const
{
  return eigenvalues(rotor_speed, stator_speed).front().real();
}

bool AngularSealDynamics::is_stable(const double rotor_speed, const double stator_speed) const
{
  const auto lambda = eigenvalues(rotor_speed, stator_speed);
  double scale = 0;
  for (const auto &l : lambda)
    scale = std::max(scale, std::abs(l));
  return lambda.front().real() < -1e-12 * scale;
}

std::vector<double>
AngularSealDynamics::hurwitz_polynomial_by_product(const double rotor_speed,
                                                   const double stator_speed) const
{
  const TiltFilm t = tilt_film(film(rotor_speed, stator_speed));
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
    P = add(multiply(ring_poly(stator, stator_speed), ring_poly(rotor, rotor_speed)),
            multiply(coupling, coupling), -1);
  }
  else if (stator_is_flexible())
    P = ring_poly(stator, stator_speed);
  else
    P = ring_poly(rotor, rotor_speed);
  Poly Pbar(P.size());
  for (unsigned int i = 0; i < P.size(); ++i)
    Pbar[i] = std::conj(P[i]);
  const Poly R = multiply(P, Pbar);
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
  const TiltFilm t = tilt_film(fc);
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
    std::vector<std::vector<double>> H(m, std::vector<double>(m));
    for (int i = 1; i <= m; ++i)
      for (int j = 1; j <= m; ++j)
        H[i - 1][j - 1] = coef(n - (2 * j - i));
    minors.push_back(determinant(H));
  }
  return minors;
}

bool AngularSealDynamics::is_stable_routh_hurwitz(const double rotor_speed,
                                                  const double stator_speed) const
{
  const std::vector<double> a = hurwitz_polynomial(rotor_speed, stator_speed);
  if (!(a.back() > 0))
    return false;
  for (const double d : hurwitz_determinants(a))
    if (!(d > 0))
      return false;
  return true;
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
  // the speed where the verdict changes between a (verdict va) and b
  auto refine = [&](double a, double b, const bool va)
  {
    while (std::abs(b - a) > 1e-10 * std::max({1.0, std::abs(a), std::abs(b)}))
    {
      const double m = 0.5 * (a + b);
      (stable(m) == va ? a : b) = m;
    }
    return 0.5 * (a + b);
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
      const double edge = refine(w_prev, w, previous);
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
  const TiltFilm t = tilt_film(fc);
  if (std::abs(t.c - fixed_speed * t.d) > 1e-9 * std::abs(fixed_speed * t.d) + 1e-300)
    throw std::runtime_error(
        "Seal dynamics: the closed-form threshold (Wileman & Green Eq. 17) needs "
        "a film with cross-coupled stiffness (omega1 + omega2)/2 d11");
  // Polynomials in psi (lowest power first); the swept speed is 2 psi - fixed_speed.
  using RPoly = std::vector<double>;
  auto mul = [](const RPoly &a, const RPoly &b)
  {
    RPoly c(a.size() + b.size() - 1, 0.0);
    for (unsigned int i = 0; i < a.size(); ++i)
      for (unsigned int j = 0; j < b.size(); ++j)
        c[i + j] += a[i] * b[j];
    return c;
  };
  auto sum = [](const RPoly &a, const RPoly &b, const double sb)
  {
    RPoly c(std::max(a.size(), b.size()), 0.0);
    for (unsigned int i = 0; i < a.size(); ++i)
      c[i] += a[i];
    for (unsigned int i = 0; i < b.size(); ++i)
      c[i] += sb * b[i];
    return c;
  };
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
  for (const double r : real_roots(p))
    speeds.push_back(2 * r - fixed_speed);
  std::sort(speeds.begin(), speeds.end());
  return speeds;
}

std::vector<AngularSealDynamics::Harmonic>
AngularSealDynamics::forcing(const double rotor_speed, const double stator_speed) const
{
  const FilmCoefficients fc = film(rotor_speed, stator_speed);
  const auto slots = dof_slots();
  std::vector<Harmonic> harmonics;
  auto harmonic_at = [&](const double W) -> Harmonic &
  {
    for (auto &h : harmonics)
      if (h.frequency == W)
        return h;
    harmonics.push_back({W, std::vector<cplx>(slots.size(), 0.0), {}});
    return harmonics.back();
  };
  // A forward circular moment or tilt m e^{i W t} has components (Re, Im) = Re((m, -i m) e^{iWt}).
  auto add_ring = [&](const RingProperties &r, const double omega, const unsigned int slot0,
                      const bool flexible)
  {
    const double W = std::abs(omega);
    // a ring spinning in -theta drags its misalignment backward: e^{-i W t}, i.e. conj.
    auto circular = [&](const double m) {
      return (omega >= 0) ? std::array<cplx, 2>{{m, -I * m}} : std::array<cplx, 2>{{m, I * m}};
    };
    if (flexible)
    {
      const double amplitude =
          r.support_stiffness * r.support_misalignment +
          (r.transverse_inertia - r.polar_inertia) * r.dynamic_misalignment * omega * omega;
      if (amplitude == 0.0)
        return;
      Harmonic &h = harmonic_at(W);
      const auto m = circular(amplitude);
      for (unsigned int k = 0; k < slots.size(); ++k)
        for (unsigned int c = 0; c < 2; ++c)
          if (slots[k] == slot0 + c)
            h.force[k] += m[c];
    }
    else
    {
      if (r.support_misalignment == 0.0)
        return;
      // rigid ring: its tilt is prescribed, the film passes (K_t + i W D_t) t to the other ring
      Harmonic &h = harmonic_at(W);
      const auto t = circular(r.support_misalignment);
      h.prescribed[slot0] += t[0];
      h.prescribed[slot0 + 1] += t[1];
      const unsigned int other0 = (slot0 == 0) ? 2 : 0;
      for (unsigned int k = 0; k < slots.size(); ++k)
        for (unsigned int i = 0; i < 2; ++i)
          if (slots[k] == other0 + i)
            for (unsigned int j = 0; j < 2; ++j)
              h.force[k] += (fc.stiffness[1 + i][1 + j] + I * W * fc.damping[1 + i][1 + j]) * t[j];
    }
  };
  add_ring(stator, stator_speed, 0, stator_is_flexible());
  add_ring(rotor, rotor_speed, 2, rotor_is_flexible());
  return harmonics;
}

ForcedResponse AngularSealDynamics::forced_response(const double rotor_speed,
                                                    const double stator_speed) const
{
  const SecondOrderSystem s = matrices(rotor_speed, stator_speed);
  const auto slots = dof_slots();
  const unsigned int n = slots.size();
  ForcedResponse result;
  result.rotor_speed = rotor_speed;
  result.stator_speed = stator_speed;
  for (const Harmonic &h : forcing(rotor_speed, stator_speed))
  {
    const double W = h.frequency;
    std::vector<std::vector<cplx>> Z(n, std::vector<cplx>(n));
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        Z[i][j] = s.stiffness(i, j) + I * W * s.damping(i, j) - W * W * s.mass(i, j);
    const std::vector<cplx> X = solve_dense(Z, h.force);
    std::array<cplx, 4> slot = h.prescribed;
    for (unsigned int k = 0; k < n; ++k)
      slot[slots[k]] = X[k];
    // (x, y) = Re((X, Y) e^{iWt})  =>  x + i y = (X + iY)/2 e^{iWt} + conj(X + i conj... )
    auto harmonic = [W](const cplx X, const cplx Y)
    {
      HarmonicTilt t;
      t.frequency = W;
      if (W == 0.0)
        t.forward = cplx(X.real(), Y.real());
      else
      {
        t.forward = 0.5 * (X + I * Y);
        t.backward = 0.5 * (std::conj(X) + I * std::conj(Y));
      }
      return t;
    };
    result.stator_tilt.push_back(harmonic(slot[0], slot[1]));
    result.rotor_tilt.push_back(harmonic(slot[2], slot[3]));
    result.relative_tilt.push_back(harmonic(slot[0] - slot[2], slot[1] - slot[3]));
  }
  return result;
}

std::array<cplx, 4> AngularSealDynamics::varney_green_synchronous_response(const double w) const
{
  if (!(stator_is_flexible() && rotor_is_flexible()))
    throw std::runtime_error("Seal dynamics: the Varney & Green solution is for an FMS seal on a "
                             "flexible rotor");
  const TiltFilm t = tilt_film(film(w, 0));
  const double Kf = t.k, Df = t.d, Ks = stator.support_stiffness, Ds = stator.support_damping;
  const double Kr = rotor.support_stiffness, Dr = rotor.support_damping;
  const double Dwr = rotor.rotating_damping, Its = stator.transverse_inertia;
  const double Itr = rotor.transverse_inertia, Ipr = rotor.polar_inertia;
  // B5 with the sign of the whole of Delta reversed (the printed Delta is the negative of the
  // determinant that goes with the printed numerators) and -D_omega_r in S1's K_f term (the other
  // D_omega_r terms, S2, S3 and the K_s term of S1, carry D_r - D_omega_r).
  const cplx S4 = -2.0 * I * Its * (Ipr - Itr);
  const cplx S3 = -((Df + 2 * Ds) * (Ipr - Itr) + (2 * Dwr - Df - 2 * Dr) * Its);
  const cplx S2 = -I * ((Df + 2 * Ds) * (Dr - Dwr) + Df * Ds + 2 * (Kf + Ks) * (Itr - Ipr) +
                        2 * Its * (Kf + Kr));
  const cplx S1 = -((Df + 2 * Ds) * Kr + 2 * (Dr + Ds - Dwr) * Kf + (Df + 2 * Dr - 2 * Dwr) * Ks);
  const cplx S0 = 2.0 * I * (Kf * Kr + Kf * Ks + Kr * Ks);
  const cplx Delta = S4 * std::pow(w, 4) + S3 * std::pow(w, 3) + S2 * w * w + S1 * w + S0;
  // B3: the misalignment forcing of the rotor
  const double F =
      (Itr - Ipr) * rotor.dynamic_misalignment * w * w + Kr * rotor.support_misalignment;
  const cplx a = F / Delta;
  return {{a * (2.0 * I * Kf - Df * w), a * (2.0 * Kf + I * Df * w),
           a * (2.0 * I * (Kf + Ks - Its * w * w) - w * (Df + 2 * Ds)),
           a * (2.0 * (Kf + Ks - Its * w * w) + I * w * (Df + 2 * Ds))}};
}

std::vector<AngularSealDynamics::TimeSample>
AngularSealDynamics::integrate(const double rotor_speed, const double stator_speed,
                               const double t_end, const std::vector<double> &output_times,
                               const double relative_tolerance,
                               const double absolute_tolerance) const
{
  using Vec = dealii::Vector<double>;
  const SecondOrderSystem s = matrices(rotor_speed, stator_speed);
  const auto harmonics = forcing(rotor_speed, stator_speed);
  const auto slots = dof_slots();
  const unsigned int n = slots.size();
  // y = (q, q_dot), y_dot = J y + (0, M^-1 f(t)) with J = [[0, 1], [-M^-1 K, -M^-1 C]]
  dealii::FullMatrix<double> J(2 * n, 2 * n);
  for (unsigned int i = 0; i < n; ++i)
  {
    J(i, n + i) = 1;
    for (unsigned int j = 0; j < n; ++j)
    {
      J(n + i, j) = -s.stiffness(i, j) / s.mass(i, i);
      J(n + i, n + j) = -s.damping(i, j) / s.mass(i, i);
    }
  }
  auto force = [&](const double t, const unsigned int i)
  {
    double f = 0;
    for (const auto &h : harmonics)
      f += std::real(h.force[i] * std::exp(I * (h.frequency * t)));
    return f;
  };

  dealii::SUNDIALS::ARKode<Vec>::AdditionalData data(0.0, t_end, 1e-6 * t_end, t_end, 0.0, 5, 10,
                                                     true, true, true, 3, absolute_tolerance,
                                                     relative_tolerance);
  dealii::SUNDIALS::ARKode<Vec> ode(data);
  ode.implicit_function = [&](const double t, const Vec &y, Vec &ydot)
  {
    J.vmult(ydot, y);
    for (unsigned int i = 0; i < n; ++i)
      ydot[n + i] += force(t, i) / s.mass(i, i);
    return 0;
  };
  ode.jacobian_times_vector = [&](const Vec &v, Vec &Jv, double, const Vec &, const Vec &)
  {
    J.vmult(Jv, v);
    return 0;
  };
  // The linearised system (1 - gamma J) x = b is tiny: assemble it column by column through the
  // operator SUNDIALS hands over and solve it directly instead of by unpreconditioned GMRES.
  ode.solve_linearized_system = [&](dealii::SUNDIALS::SundialsOperator<Vec> &op,
                                    dealii::SUNDIALS::SundialsPreconditioner<Vec> &, Vec &x,
                                    const Vec &b, double)
  {
    std::vector<std::vector<cplx>> A(2 * n, std::vector<cplx>(2 * n));
    Vec e(2 * n), Ae(2 * n);
    for (unsigned int j = 0; j < 2 * n; ++j)
    {
      e = 0;
      e[j] = 1;
      op.vmult(Ae, e);
      for (unsigned int i = 0; i < 2 * n; ++i)
        A[i][j] = Ae[i];
    }
    std::vector<cplx> rhs(b.begin(), b.end());
    const auto sol = solve_dense(A, rhs);
    for (unsigned int i = 0; i < 2 * n; ++i)
      x[i] = sol[i].real();
    return 0;
  };

  // one call may have to cover many forcing periods: lift SUNDIALS' default of 500 steps
  ode.custom_setup = [](void *arkode_mem) { ARKStepSetMaxNumSteps(arkode_mem, 10000000); };

  std::vector<TimeSample> samples;
  auto record = [&](const double t, const Vec &y)
  {
    TimeSample sample{t, {{0, 0, 0, 0}}};
    for (const auto &h : harmonics)
      for (unsigned int k = 0; k < 4; ++k)
        sample.tilts[k] += std::real(h.prescribed[k] * std::exp(I * (h.frequency * t)));
    for (unsigned int k = 0; k < n; ++k)
      sample.tilts[slots[k]] = y[k];
    samples.push_back(sample);
  };
  Vec y(2 * n);
  double t_reached = 0;
  std::vector<double> times = output_times;
  std::sort(times.begin(), times.end());
  for (const double t_out : times)
  {
    if (t_out > t_reached)
    {
      ode.solve_ode_incrementally(y, t_out);
      t_reached = t_out;
    }
    record(t_out, y);
  }
  return samples;
}

namespace
{
void declare_ring(dealii::ParameterHandler &prm, const std::string &name, const RingProperties &d,
                  const std::string &what)
{
  using dealii::Patterns::Double;
  auto str = [](const double v)
  {
    std::ostringstream s;
    s << v;
    return s.str();
  };
  prm.enter_subsection(name);
  prm.declare_entry("Transverse inertia", str(d.transverse_inertia), Double(0),
                    "Transverse mass moment of inertia I_t (kg m^2) of the " + what +
                        " about a diameter through its centre.");
  prm.declare_entry("Polar inertia", str(d.polar_inertia), Double(0),
                    "Polar mass moment of inertia I_p (kg m^2): gyroscopic moment I_p omega "
                    "times the tilt rate. I_t/I_p < 1/2 is a short disk, > 2 a long rotor.");
  prm.declare_entry("Support stiffness", str(d.support_stiffness), Double(0),
                    "Angular stiffness (N m/rad) of the support (O-ring/springs, or the shaft "
                    "for a flexible rotor).");
  prm.declare_entry("Support damping", str(d.support_damping), Double(0),
                    "Direct angular damping (N m s/rad) of the support.");
  prm.declare_entry("Rotating damping", str(d.rotating_damping), Double(0),
                    "Part of the damping that turns with the ring (N m s/rad): adds the "
                    "circulatory stiffness speed x this. Equal to Support damping for a support "
                    "spinning with its shaft (Wileman & Green); D_omega_r of Varney & Green.");
  prm.declare_entry("Support misalignment", str(d.support_misalignment), Double(),
                    "Static misalignment (rad) of the support: the tilt it holds the ring at "
                    "(turns with the ring if it spins). Stator: gamma_si; rotor: chi_s "
                    "(run-out). For a rigidly mounted ring, the ring's own tilt.");
  prm.declare_entry("Dynamic misalignment", str(d.dynamic_misalignment), Double(),
                    "Angle chi (rad) between the principal axes and the spin axis of a "
                    "flexibly mounted spinning ring: forces (I_t - I_p) chi omega^2.");
  prm.leave_subsection();
}

RingProperties parse_ring(dealii::ParameterHandler &prm, const std::string &name)
{
  RingProperties r;
  prm.enter_subsection(name);
  r.transverse_inertia = prm.get_double("Transverse inertia");
  r.polar_inertia = prm.get_double("Polar inertia");
  r.support_stiffness = prm.get_double("Support stiffness");
  r.support_damping = prm.get_double("Support damping");
  r.rotating_damping = prm.get_double("Rotating damping");
  r.support_misalignment = prm.get_double("Support misalignment");
  r.dynamic_misalignment = prm.get_double("Dynamic misalignment");
  prm.leave_subsection();
  return r;
}
} // namespace

void SealDynamicsInput::declare_parameters(dealii::ParameterHandler &prm)
{
  // Defaults: Varney & Green (Varney & Green (2017)) Table 2 with delta = I_tr/I_pr = 2, chi = 0.5
  // mrad.
  RingProperties rotor_default, stator_default;
  rotor_default.transverse_inertia = 0.2;
  rotor_default.polar_inertia = 0.1;
  rotor_default.support_stiffness = 5e5;
  rotor_default.support_damping = 20;
  rotor_default.rotating_damping = 1;
  rotor_default.dynamic_misalignment = 0.5e-3;
  stator_default.transverse_inertia = 1.7e-3;
  stator_default.polar_inertia = 3.4e-3;
  stator_default.support_stiffness = 363.9;
  stator_default.support_damping = 0.22;
  prm.enter_subsection("Seal dynamics");
  prm.declare_entry("Configuration", "FMS with flexible rotor",
                    dealii::Patterns::Selection("FMS|FMR|FMRR|FMS with flexible rotor"),
                    "Which rings are flexibly mounted. FMS: flexible stator, rigid rotor; FMR: "
                    "rigid stator, flexible rotor; FMRR: both flexible, both may spin (speeds "
                    "from Operating conditions); FMS with flexible rotor: FMRR equations with a "
                    "non-spinning stator and the shaft + seat as the rotor ring.");
  prm.declare_entry("Film model", "closed form",
                    dealii::Patterns::Selection("closed form|table|finite element"),
                    "Film stiffness and damping. closed form = level 0: Green & Etsion narrow "
                    "seal (k11, d11, (omega1 + omega2)/2 d11), untilted coned face, full film. "
                    "table = level 1: interpolated from the CSV of `sealfe table` (Table file). "
                    "finite element = level 2: the FE Reynolds solve linearised about the "
                    "Geometry as given (subsections Discretization, Cavitation, Roughness, "
                    "Coefficients), at Film speed nodes speeds of a sweep.");
  prm.declare_entry("Table file", "", dealii::Patterns::Anything(),
                    "Film model = table only: the coefficient table (CSV of `sealfe table`), "
                    "relative to the working directory. It must hold this seal (every quantity "
                    "it did not sweep equal to the Geometry and Operating conditions here) and "
                    "cover the swept speeds: the film depends on the ring speeds through their "
                    "mean only, so a table over the rotor speed (stator at 0) serves an FMRR "
                    "sweep if its rotor speeds cover rotor speed + stator speed.");
  prm.declare_entry("Table interpolation", "cubic", dealii::Patterns::Selection("cubic|linear"),
                    "Film model = table only: cubic Lagrange on 4 nodes per axis (O(h^4)) or "
                    "multilinear (O(h^2)).");
  prm.declare_entry("Film speed nodes", "9", dealii::Patterns::Integer(0),
                    "Film model = finite element only: for a speed sweep the FE coefficients are "
                    "computed at this many equally spaced speeds of the swept ring over the "
                    "sweep and interpolated in between (cubic Lagrange; exact in full film, "
                    "where K is affine in the mean speed and D does not depend on it). 0: an FE "
                    "computation at every speed the sweep evaluates (hundreds or thousands). 1 "
                    "is not allowed.");
  declare_ring(prm, "Rotor ring", rotor_default,
               "ring spinning at Operating conditions/Rotor speed");
  declare_ring(prm, "Stator ring", stator_default,
               "ring spinning at Operating conditions/Stator speed (0 for a stator)");
  prm.leave_subsection();
}

void SealDynamicsInput::parse_parameters(dealii::ParameterHandler &prm)
{
  geometry.parse_parameters(prm);
  operating.parse_parameters(prm);
  prm.enter_subsection("Seal dynamics");
  configuration = configuration_from_string(prm.get("Configuration"));
  film_model = prm.get("Film model");
  table_file = prm.get("Table file");
  table_interpolation = prm.get("Table interpolation");
  film_speed_nodes = prm.get_integer("Film speed nodes");
  rotor = parse_ring(prm, "Rotor ring");
  stator = parse_ring(prm, "Stator ring");
  prm.leave_subsection();
}

int SealDynamicsInput::film_model_level() const
{
  if (film_model == "closed form")
    return 0;
  if (film_model == "table")
    return 1;
  if (film_model == "finite element")
    return 2;
  throw std::runtime_error("Seal dynamics: Film model '" + film_model +
                           "' is not one of closed form, table, finite element");
}

void SealDynamicsInput::validate() const
{
  const int level = film_model_level();
  geometry.validate();
  operating.validate();
  if (configuration == SealConfiguration::fms_flexible_rotor && operating.stator_speed != 0.0)
  {
    std::ostringstream s;
    s << "Seal dynamics: Configuration = FMS with flexible rotor needs Operating conditions/"
      << "Stator speed = 0 (got " << operating.stator_speed << " rad/s); use FMRR";
    throw std::runtime_error(s.str());
  }
  if (configuration == SealConfiguration::fms && operating.stator_speed != 0.0)
  {
    std::ostringstream s;
    s << "Seal dynamics: Configuration = FMS has a non-spinning stator: Operating conditions/"
      << "Stator speed must be 0 (got " << operating.stator_speed << " rad/s)";
    throw std::runtime_error(s.str());
  }
  if (level == 0)
    GreenEtsionCoefficients check(geometry, operating); // throws on an impossible narrow seal
  else if (level == 1)
    film(); // reads the table and checks that it holds this seal
  else
  {
    if (!finite_element)
      throw std::runtime_error("Seal dynamics: Film model = finite element needs the "
                               "finite-element solver, which the sealfe application supplies "
                               "(SealDynamicsInput::finite_element is empty)");
    if (film_speed_nodes == 1)
      throw std::runtime_error("Seal dynamics: Film speed nodes must be 0 (an FE computation at "
                               "every speed) or at least 2 (got 1)");
  }
  AngularSealDynamics(configuration, rotor, stator, FilmModel()).validate();
}

std::shared_ptr<const CoefficientTable> SealDynamicsInput::table() const
{
  const std::string key = table_file + "\n" + table_interpolation;
  if (table_cache && table_cache_key == key)
    return table_cache;
  if (table_file.empty())
    throw std::runtime_error("Seal dynamics: Film model = table needs a Table file (the CSV "
                             "written by sealfe table)");
  try
  {
    table_cache = std::make_shared<const CoefficientTable>(
        table_file, table_interpolation == "linear" ? CoefficientTable::Interpolation::linear
                                                    : CoefficientTable::Interpolation::cubic);
  }
  catch (const std::exception &e)
  {
    throw std::runtime_error(std::string("Seal dynamics: Table file: ") + e.what());
  }
  table_cache_key = key;
  return table_cache;
}

FilmModel SealDynamicsInput::film() const
{
  const int level = film_model_level();
  if (level == 1)
  {
    try
    {
      return table()->film_model(geometry, operating);
    }
    catch (const std::exception &e)
    {
      const std::string what = e.what();
      throw std::runtime_error(what.rfind("Seal dynamics:", 0) == 0
                                   ? what
                                   : "Seal dynamics: Film model = table: " + what);
    }
  }
  if (level == 2)
  {
    if (!finite_element)
      throw std::runtime_error("Seal dynamics: Film model = finite element needs the "
                               "finite-element solver, which the sealfe application supplies "
                               "(SealDynamicsInput::finite_element is empty)");
    auto cache = std::make_shared<std::map<std::pair<double, double>, FilmCoefficients>>();
    return [provider = finite_element, film = geometry, conditions = operating,
            cache](const double rotor_speed, const double stator_speed)
    {
      const auto key = std::make_pair(rotor_speed, stator_speed);
      const auto hit = cache->find(key);
      if (hit != cache->end())
        return hit->second;
      OperatingConditions c = conditions;
      c.rotor_speed = rotor_speed;
      c.stator_speed = stator_speed;
      FilmCoefficients k = provider(film, c);
      k.level = 2;
      k.rotor_speed = rotor_speed;
      k.stator_speed = stator_speed;
      cache->emplace(key, k);
      return k;
    };
  }
  const GreenEtsionCoefficients g(geometry, operating);
  return [g](const double rotor_speed, const double stator_speed)
  { return g.coefficients(rotor_speed, stator_speed); };
}

SweepFilm SealDynamicsInput::sweep_film(const AngularSealDynamics::SweptRing swept,
                                        const double fixed_speed, const double from,
                                        const double to) const
{
  const bool swept_rotor = swept == AngularSealDynamics::SweptRing::rotor;
  SweepFilm s;
  s.model = film();
  const int level = film_model_level();
  if (level == 0)
    s.description = {{"method",
                      "closed form (level 0) at every speed: k11 and d11 do not depend "
                      "on speed, the cross-coupled stiffness is (omega1 + omega2)/2 d11"}};
  else if (level == 1)
  {
    // Fail before the sweep, with the sweep named, if it leaves the table.
    for (const double w : {from, to})
      try
      {
        s.model(swept_rotor ? w : fixed_speed, swept_rotor ? fixed_speed : w);
      }
      catch (const std::exception &e)
      {
        std::ostringstream m;
        m << "Seal dynamics: Film model = table: the sweep of the "
          << (swept_rotor ? "rotor" : "stator") << " speed over [" << from << ", " << to
          << "] rad/s (other ring at " << fixed_speed << " rad/s) leaves the table: " << e.what();
        throw std::runtime_error(m.str());
      }
    s.description = {{"method", "table lookup (level 1) at every speed, interpolated by the "
                                "table in the mean speed and its other axes"},
                     {"table", table_file},
                     {"interpolation", table_interpolation},
                     {"table_axes", table()->axes()}};
  }
  else if (film_speed_nodes == 0)
    s.description = {{"method", "finite element (level 2) at every speed the sweep evaluates"}};
  else
  {
    auto interpolation = std::make_shared<SpeedInterpolatedFilm>(s.model, swept, fixed_speed, from,
                                                                 to, film_speed_nodes);
    s.interpolation = interpolation;
    s.model = [interpolation](const double rotor_speed, const double stator_speed)
    { return (*interpolation)(rotor_speed, stator_speed); };
    s.description = interpolation->to_json();
  }
  return s;
}

AngularSealDynamics SealDynamicsInput::build() const
{
  return build(film());
}

AngularSealDynamics SealDynamicsInput::build(FilmModel film_model) const
{
  return AngularSealDynamics(configuration, rotor, stator, std::move(film_model));
}

// ------------------------------------------------------------------------------------------------
// SpeedInterpolatedFilm

SpeedInterpolatedFilm::SpeedInterpolatedFilm(FilmModel exact,
                                             const AngularSealDynamics::SweptRing swept,
                                             const double fixed_speed, const double from,
                                             const double to, const unsigned int n_nodes)
    : state(std::make_shared<State>())
{
  if (!(to > from) || !std::isfinite(from) || !std::isfinite(to) || n_nodes < 2)
    throw std::runtime_error("Seal dynamics: the speed interpolation of the film needs 'to' > "
                             "'from' and at least 2 nodes");
  state->exact = std::move(exact);
  state->swept = swept;
  state->fixed = fixed_speed;
  state->from = from;
  state->to = to;
  state->n = n_nodes;
  state->nodes.resize(n_nodes);
}

std::vector<double> SpeedInterpolatedFilm::node_speeds() const
{
  std::vector<double> w(state->n);
  for (unsigned int i = 0; i < state->n; ++i)
    w[i] = (i + 1 == state->n) ? state->to
                               : state->from + (state->to - state->from) * i / (state->n - 1);
  return w;
}

bool SpeedInterpolatedFilm::on_line(const double rotor_speed, const double stator_speed,
                                    double &swept_speed) const
{
  const bool swept_rotor = state->swept == AngularSealDynamics::SweptRing::rotor;
  const double other = swept_rotor ? stator_speed : rotor_speed;
  swept_speed = swept_rotor ? rotor_speed : stator_speed;
  const double slack = 1e-12 * (state->to - state->from);
  return other == state->fixed && swept_speed >= state->from - slack &&
         swept_speed <= state->to + slack;
}

FilmCoefficients SpeedInterpolatedFilm::node(const unsigned int i) const
{
  if (!state->nodes[i])
  {
    const double w = node_speeds()[i];
    const bool swept_rotor = state->swept == AngularSealDynamics::SweptRing::rotor;
    state->nodes[i] = std::make_unique<FilmCoefficients>(
        state->exact(swept_rotor ? w : state->fixed, swept_rotor ? state->fixed : w));
    ++state->evaluations;
  }
  return *state->nodes[i];
}

FilmCoefficients SpeedInterpolatedFilm::interpolate(const double swept_speed) const
{
  const std::vector<double> v = node_speeds();
  const unsigned int n = v.size();
  const double x = std::clamp(swept_speed, v.front(), v.back());
  // Interval k with v[k] <= x <= v[k+1]; the stencil of (up to) 4 nodes around it shifts
  // inwards at the ends (as CoefficientTable::axis_weights).
  unsigned int k = std::upper_bound(v.begin(), v.end(), x) - v.begin();
  k = std::min(std::max(k, 1u), n - 1) - 1;
  const unsigned int width = std::min(4u, n);
  const int first = std::clamp(static_cast<int>(k) - 1, 0, static_cast<int>(n - width));
  FilmCoefficients result;
  bool have = false;
  for (unsigned int m = 0; m < width; ++m)
  {
    double weight = 1;
    for (unsigned int l = 0; l < width; ++l)
      if (l != m)
        weight *= (x - v[first + l]) / (v[first + m] - v[first + l]);
    const FilmCoefficients c = node(first + m);
    if (!have)
    {
      result = c; // level, model
      for (auto *mat : {&result.stiffness, &result.damping})
        for (auto &row : *mat)
          row.fill(0.0);
      have = true;
    }
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
      {
        result.stiffness[i][j] += weight * c.stiffness[i][j];
        result.damping[i][j] += weight * c.damping[i][j];
      }
  }
  return result;
}

FilmCoefficients SpeedInterpolatedFilm::operator()(const double rotor_speed,
                                                   const double stator_speed) const
{
  double w;
  if (!on_line(rotor_speed, stator_speed, w))
  {
    const auto key = std::make_pair(rotor_speed, stator_speed);
    const auto hit = state->off_line.find(key);
    if (hit != state->off_line.end())
      return hit->second;
    const FilmCoefficients c = state->exact(rotor_speed, stator_speed);
    ++state->evaluations;
    state->off_line.emplace(key, c);
    return c;
  }
  FilmCoefficients c = interpolate(w);
  c.rotor_speed = rotor_speed;
  c.stator_speed = stator_speed;
  return c;
}

SpeedInterpolatedFilm::Check SpeedInterpolatedFilm::check(const double swept_speed,
                                                          const double outer_radius) const
{
  const std::vector<double> v = node_speeds();
  const double x = std::clamp(swept_speed, v.front(), v.back());
  unsigned int k = std::upper_bound(v.begin(), v.end(), x) - v.begin();
  k = std::min(std::max(k, 1u), static_cast<unsigned int>(v.size()) - 1) - 1;
  Check c;
  c.speed = 0.5 * (v[k] + v[k + 1]);
  const bool swept_rotor = state->swept == AngularSealDynamics::SweptRing::rotor;
  const double wr = swept_rotor ? c.speed : state->fixed, ws = swept_rotor ? state->fixed : c.speed;
  const FilmCoefficients reference = state->exact(wr, ws);
  ++state->evaluations;
  const CoefficientTable::Error e =
      CoefficientTable::compare((*this)(wr, ws), reference, outer_radius);
  c.stiffness = e.stiffness;
  c.damping = e.damping;
  return c;
}

nlohmann::json SpeedInterpolatedFilm::check_report(const std::vector<double> &swept_speeds,
                                                   const double outer_radius) const
{
  nlohmann::json checks = nlohmann::json::array();
  std::vector<double> done;
  double worst_k = 0, worst_d = 0;
  for (const double w : swept_speeds)
  {
    const Check c = check(w, outer_radius);
    if (std::find(done.begin(), done.end(), c.speed) != done.end())
      continue;
    done.push_back(c.speed);
    checks.push_back(
        {{"swept_speed", c.speed}, {"stiffness_error", c.stiffness}, {"damping_error", c.damping}});
    worst_k = std::max(worst_k, c.stiffness);
    worst_d = std::max(worst_d, c.damping);
  }
  return {{"checks", checks},
          {"max_stiffness_error", worst_k},
          {"max_damping_error", worst_d},
          {"definition", "interpolated against computed coefficients midway between the two nodes "
                         "around each speed of interest: max_ij |K~ - K| / max_ij |K| of diag(1, "
                         "1/ro, 1/ro) K diag(1, 1/ro, 1/ro); the same for D"}};
}

nlohmann::json SpeedInterpolatedFilm::to_json() const
{
  const bool swept_rotor = state->swept == AngularSealDynamics::SweptRing::rotor;
  std::ostringstream m;
  m << "finite element (level 2) at " << state->n << " equally spaced "
    << (swept_rotor ? "rotor" : "stator") << " speeds over [" << state->from << ", " << state->to
    << "] rad/s (other ring at " << state->fixed << " rad/s), "
    << (state->n == 2   ? "linear"
        : state->n == 3 ? "quadratic"
                        : "cubic")
    << " Lagrange interpolation in between (exact in full film: K affine in the mean speed, D "
       "independent of it); an FE computation at any other speed pair";
  return {{"method", m.str()},
          {"swept_speed", swept_rotor ? "rotor" : "stator"},
          {"fixed_speed", state->fixed},
          {"node_speeds", node_speeds()},
          {"nodes", state->n}};
}

double SealDynamicsInput::contact_tilt() const
{
  const double ri = geometry.inner_radius, ro = geometry.outer_radius, C0 = geometry.clearance;
  return std::min(C0 / ri, (C0 + geometry.coning * (ro - ri)) / ro);
}

std::string SealDynamicsInput::parameter_names()
{
  return "Clearance|Coning|Inner radius|Outer radius|Inner pressure|Outer pressure|Viscosity|"
         "Rotor speed|Stator speed|"
         "Rotor ring transverse inertia|Rotor ring polar inertia|Rotor ring support stiffness|"
         "Rotor ring support damping|Rotor ring rotating damping|"
         "Stator ring transverse inertia|Stator ring polar inertia|"
         "Stator ring support stiffness|Stator ring support damping|"
         "Stator ring rotating damping";
}

void SealDynamicsInput::set(const std::string &name, const double value,
                            const bool hold_normalized_coning)
{
  auto ring = [&](RingProperties &r, const std::string &what)
  {
    if (what == "transverse inertia")
      r.transverse_inertia = value;
    else if (what == "polar inertia")
      r.polar_inertia = value;
    else if (what == "support stiffness")
      r.support_stiffness = value;
    else if (what == "support damping")
      r.support_damping = value;
    else if (what == "rotating damping")
      r.rotating_damping = value;
    else
      return false;
    return true;
  };
  if (name == "Clearance")
  {
    if (hold_normalized_coning)
      geometry.coning *= value / geometry.clearance;
    geometry.clearance = value;
  }
  else if (name == "Coning")
    geometry.coning = value;
  else if (name == "Inner radius")
    geometry.inner_radius = value;
  else if (name == "Outer radius")
    geometry.outer_radius = value;
  else if (name == "Inner pressure")
    operating.inner_pressure = value;
  else if (name == "Outer pressure")
    operating.outer_pressure = value;
  else if (name == "Viscosity")
    operating.viscosity = value;
  else if (name == "Rotor speed")
    operating.rotor_speed = value;
  else if (name == "Stator speed")
    operating.stator_speed = value;
  else if (!((name.rfind("Rotor ring ", 0) == 0 && ring(rotor, name.substr(11))) ||
             (name.rfind("Stator ring ", 0) == 0 && ring(stator, name.substr(12)))))
    throw std::runtime_error("Seal dynamics: unknown parameter '" + name + "' (one of " +
                             parameter_names() + ")");
}

} // namespace sealfe
