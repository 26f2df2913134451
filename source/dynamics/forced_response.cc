#include <sealfe/dynamics/angular_dynamics.h>
#include <sealfe/dynamics/forced_response.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <cmath>
#include <stdexcept>

namespace sealfe
{
using cplx = std::complex<double>;
namespace
{
const cplx I(0.0, 1.0);
}

std::vector<cplx> solve_dense_complex(const std::vector<std::vector<cplx>> &A,
                                      const std::vector<cplx> &b)
{
  const unsigned int n = b.size();
  for (const auto &row : A)
    for (const cplx &a : row)
      if (!std::isfinite(a.real()) || !std::isfinite(a.imag()))
        throw std::runtime_error("Seal dynamics: the dynamic stiffness is not a finite number (an "
                                 "inertia, stiffness, damping or speed is beyond what double "
                                 "precision can represent)");
  dealii::LAPACKFullMatrix<cplx> M(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      M(i, j) = A[i][j];
  dealii::Vector<cplx> x(b.begin(), b.end());
  try
  {
    M.compute_lu_factorization();
  }
  catch (const dealii::ExceptionBase &)
  {
    throw std::runtime_error("Seal dynamics: singular dynamic stiffness (an undamped mode is "
                             "excited exactly at its natural frequency)");
  }
  M.solve(x);
  for (const cplx &v : x)
    if (!std::isfinite(v.real()) || !std::isfinite(v.imag()))
      throw std::runtime_error("Seal dynamics: singular dynamic stiffness (an undamped mode is "
                               "excited exactly at its natural frequency)");
  return std::vector<cplx>(x.begin(), x.end());
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
    const std::vector<cplx> X = solve_dense_complex(Z, h.force);
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
  const TiltFilm t = TiltFilm::of(film(w, 0));
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

} // namespace sealfe
