#include <sealfe/dynamics/angular_dynamics.h>
#include <sealfe/dynamics/linear_time_integration.h>

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>
#include <deal.II/sundials/arkode.h>

#include <arkode/arkode_arkstep.h>

#include <algorithm>
#include <cmath>

namespace sealfe
{
using cplx = std::complex<double>;

std::vector<std::vector<double>>
integrate_linear_system(const SecondOrderSystem &s,
                        const std::function<double(double, unsigned int)> &force,
                        const double t_end, const std::vector<double> &output_times,
                        const double relative_tolerance, const double absolute_tolerance)
{
  using Vec = dealii::Vector<double>;
  const unsigned int n = s.mass.m();
  // y = (q, q_dot), y_dot = J y + (0, M^-1 f(t))
  const dealii::FullMatrix<double> J = s.first_order_matrix();

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
    dealii::LAPACKFullMatrix<double> A(2 * n, 2 * n);
    Vec e(2 * n), Ae(2 * n);
    for (unsigned int j = 0; j < 2 * n; ++j)
    {
      e = 0;
      e[j] = 1;
      op.vmult(Ae, e);
      for (unsigned int i = 0; i < 2 * n; ++i)
        A(i, j) = Ae[i];
    }
    A.compute_lu_factorization();
    x = b;
    A.solve(x);
    return 0;
  };

  // one call may have to cover many forcing periods: lift SUNDIALS' default of 500 steps
  ode.custom_setup = [](void *arkode_mem) { ARKStepSetMaxNumSteps(arkode_mem, 10000000); };

  std::vector<std::vector<double>> q;
  Vec y(2 * n);
  double t_reached = 0;
  for (const double t_out : output_times)
  {
    if (t_out > t_reached)
    {
      ode.solve_ode_incrementally(y, t_out);
      t_reached = t_out;
    }
    q.emplace_back(y.begin(), y.begin() + n);
  }
  return q;
}

std::vector<AngularSealDynamics::TimeSample>
AngularSealDynamics::integrate(const double rotor_speed, const double stator_speed,
                               const double t_end, const std::vector<double> &output_times,
                               const double relative_tolerance,
                               const double absolute_tolerance) const
{
  const auto harmonics = forcing(rotor_speed, stator_speed);
  const auto slots = dof_slots();
  const cplx I(0.0, 1.0);
  auto force = [&](const double t, const unsigned int i)
  {
    double f = 0;
    for (const auto &h : harmonics)
      f += std::real(h.force[i] * std::exp(I * (h.frequency * t)));
    return f;
  };
  std::vector<double> times = output_times;
  std::sort(times.begin(), times.end());
  const auto q = integrate_linear_system(matrices(rotor_speed, stator_speed), force, t_end, times,
                                         relative_tolerance, absolute_tolerance);
  std::vector<TimeSample> samples;
  for (unsigned int m = 0; m < times.size(); ++m)
  {
    // a rigid ring's prescribed tilt, then the flexible rings' dofs
    TimeSample sample{times[m], {{0, 0, 0, 0}}};
    for (const auto &h : harmonics)
      for (unsigned int k = 0; k < 4; ++k)
        sample.tilts[k] += std::real(h.prescribed[k] * std::exp(I * (h.frequency * times[m])));
    for (unsigned int k = 0; k < slots.size(); ++k)
      sample.tilts[slots[k]] = q[m][k];
    samples.push_back(sample);
  }
  return samples;
}

} // namespace sealfe
