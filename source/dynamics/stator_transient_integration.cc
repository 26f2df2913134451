// StatorTransient::run: the state of Eq. 26 (scaled) integrated by ARKode's implicit (DIRK)
// method with a finite-difference Jacobian, refreshed when ARKode asks for it.
#include <sealfe/dynamics/stator_transient.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>
#include <deal.II/sundials/arkode.h>

#include <arkode/arkode_arkstep.h>

#include <cmath>
#include <sstream>

namespace sealfe
{
using State = std::array<double, 8>;
using Vec = dealii::Vector<double>;

StatorTransient::Result StatorTransient::run() const
{
  Result result;
  constexpr unsigned int n = 8;
  auto to_state = [&](const Vec &v)
  {
    State y;
    for (unsigned int i = 0; i < n; ++i)
      y[i] = v[i] * scale[i];
    return y;
  };
  std::string failure;
  // the film and the contact throw std::runtime_error outside their range (a film that
  // touches down): ARKode is told the step failed recoverably and retries a smaller one
  auto scaled_rate = [&](const double t, const Vec &v, Vec &dv) -> int
  {
    try
    {
      const State d = rate(t, to_state(v));
      for (unsigned int i = 0; i < n; ++i)
        dv[i] = d[i] / scale[i];
      for (unsigned int i = 0; i < n; ++i)
        if (!std::isfinite(dv[i]))
          return 1;
      return 0;
    }
    catch (std::exception &e)
    {
      failure = e.what();
      return 1;
    }
  };

  const double dt0 = std::min(1e-6, settings.output_interval);
  dealii::SUNDIALS::ARKode<Vec>::AdditionalData data(
      0.0, settings.end_time, dt0, settings.output_interval, settings.minimum_step, settings.order,
      10, false, false, true, 3, settings.absolute_tolerance, settings.relative_tolerance);
  dealii::SUNDIALS::ARKode<Vec> ode(data);
  ode.implicit_function = scaled_rate;

  // Jacobian of the scaled rate by forward differences, rebuilt at ARKode's Jacobian updates
  dealii::FullMatrix<double> J(n, n), A(n, n);
  ode.jacobian_times_setup = [&](const double t, const Vec &y, const Vec &fy) -> int
  {
    ++result.jacobian_setups;
    Vec yp(y), fp(n);
    for (unsigned int j = 0; j < n; ++j)
    {
      const double h = 1e-7 * std::max(1.0, std::abs(y[j]));
      yp[j] = y[j] + h;
      if (scaled_rate(t, yp, fp) != 0)
        return 1;
      for (unsigned int i = 0; i < n; ++i)
        J(i, j) = (fp[i] - fy[i]) / h;
      yp[j] = y[j];
    }
    return 0;
  };
  ode.jacobian_times_vector = [&](const Vec &v, Vec &Jv, double, const Vec &, const Vec &) -> int
  {
    J.vmult(Jv, v);
    return 0;
  };
  ode.solve_linearized_system = [&](dealii::SUNDIALS::SundialsOperator<Vec> &op,
                                    dealii::SUNDIALS::SundialsPreconditioner<Vec> &, Vec &x,
                                    const Vec &b, double) -> int
  {
    Vec e(n), Ae(n);
    for (unsigned int j = 0; j < n; ++j)
    {
      e = 0;
      e[j] = 1;
      op.vmult(Ae, e);
      for (unsigned int i = 0; i < n; ++i)
        A(i, j) = Ae[i];
    }
    dealii::FullMatrix<double> inverse(n, n);
    inverse.invert(A);
    inverse.vmult(x, b);
    return 0;
  };
  void *memory = nullptr;
  const long max_steps = settings.maximum_steps;
  ode.custom_setup = [&](void *arkode_mem)
  {
    memory = arkode_mem;
    ARKStepSetMaxNumSteps(arkode_mem, max_steps);
  };

  const State y0 = initial_state();
  Vec v(n);
  for (unsigned int i = 0; i < n; ++i)
    v[i] = y0[i] / scale[i];
  result.samples.push_back(sample(0, y0));
  const unsigned long rows =
      std::llround(std::ceil(settings.end_time / settings.output_interval - 1e-9));
  double t_reached = 0;
  for (unsigned long k = 1; k <= rows; ++k)
  {
    const double t_out = std::min(settings.end_time, k * settings.output_interval);
    try
    {
      ode.solve_ode_incrementally(v, t_out);
    }
    catch (std::exception &e)
    {
      std::ostringstream s;
      s << "the integrator stopped at t = " << t_reached << " s (between outputs; "
        << "step size collapse or too many steps)";
      if (!failure.empty())
        s << "; last film/contact failure: " << failure;
      result.stop_reason = s.str();
      break;
    }
    t_reached = t_out;
    result.samples.push_back(sample(t_out, to_state(v)));
  }
  result.complete = result.stop_reason.empty();
  long steps = 0;
  if (memory)
    ARKStepGetNumSteps(memory, &steps);
  result.steps = steps;
  if (memory)
  {
    long fails = 0, conv = 0, setups = 0;
    ARKStepGetNumErrTestFails(memory, &fails);
    ARKStepGetNumNonlinSolvConvFails(memory, &conv);
    ARKStepGetNumLinSolvSetups(memory, &setups);
    result.error_test_failures = fails;
    result.convergence_failures = conv;
    (void)setups;
  }
  result.film_evaluations = evaluations;
  return result;
}
} // namespace sealfe
