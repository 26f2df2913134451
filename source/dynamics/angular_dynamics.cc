#include <sealfe/dynamics/angular_dynamics.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
dealii::FullMatrix<double> SecondOrderSystem::first_order_matrix() const
{
  const unsigned int n = mass.m();
  dealii::FullMatrix<double> A(2 * n, 2 * n);
  for (unsigned int i = 0; i < n; ++i)
  {
    A(i, n + i) = 1;
    for (unsigned int j = 0; j < n; ++j)
    {
      A(n + i, j) = -stiffness(i, j) / mass(i, i);
      A(n + i, n + j) = -damping(i, j) / mass(i, i);
    }
  }
  return A;
}

using cplx = std::complex<double>;

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
  dealii::LAPACKFullMatrix<double> A(2 * n, 2 * n);
  A = s.first_order_matrix();
  // LAPACK's DGEBAL stops the program (exit 0, nothing written) on a nan: refuse it here
  for (unsigned int i = 0; i < 2 * n; ++i)
    for (unsigned int j = 0; j < 2 * n; ++j)
      if (!std::isfinite(A(i, j)))
      {
        std::ostringstream m;
        m << "Seal dynamics: the equations of motion at rotor speed " << rotor_speed
          << " rad/s, stator speed " << stator_speed
          << " rad/s are not finite numbers (a film coefficient or ring property is beyond what "
             "double precision can represent)";
        throw std::runtime_error(m.str());
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

} // namespace sealfe
