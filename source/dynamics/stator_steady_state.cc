// StatorTransient::steady_state: the operating point with tilts — the state at which every rate
// of the transient's equations vanishes in the frame where the forcing is steady.
#include <sealfe/dynamics/stator_transient.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace sealfe
{
TransientState StatorTransient::steady_state(const double t, const TransientState &guess,
                                             unsigned int *iterations) const
{
  const bool whirl_forcing =
      seal.runout.tilt > 0 || (seal.rotor.flexible && seal.rotor.angular.dynamic_misalignment > 0);
  if (whirl_forcing && seal.stator.initial_misalignment > 0)
    throw NoSteadyState(
        "equilibrium: runout turns with the shaft while the stator misalignment is fixed in "
        "space: no steady state exists (set one of them to 0, or run `sealfe transient`)");
  if (whirl_forcing && !rotating)
    throw NoSteadyState("equilibrium: runout needs Transient/Frame = auto or rotating");
  if (!whirl_forcing && seal.stator.initial_misalignment > 0 && rotating)
    throw NoSteadyState(
        "equilibrium: a stator misalignment needs Transient/Frame = auto or inertial");

  // unknowns and the rates that must vanish with them: Z'' = 0, a'' = 0 (a' = 0), beta' = 0,
  // a_r'' = 0 (a_r' = 0)
  std::vector<std::pair<unsigned int, unsigned int>> unknowns = {{0, 1}, {2, 4}, {3, 5}};
  if (seal.thermal.enabled() && seal.thermal.time_constant > 0)
    unknowns.push_back({6, 6});
  if (seal.rotor.flexible)
  {
    unknowns.push_back({8, 10});
    unknowns.push_back({9, 11});
  }
  if (seal.rotor.axially_flexible())
    unknowns.push_back({12, 13});
  const unsigned int n = unknowns.size();
  TransientState y = guess;
  for (const unsigned int i : {1, 4, 5, 10, 11, 13})
    y[i] = 0;
  if (!seal.rotor.flexible)
    y[8] = y[9] = 0;
  if (!seal.rotor.axially_flexible())
    y[12] = 0;

  // scaled residual: each rate in units of its state's scale per ms
  auto residual = [&](const TransientState &state)
  {
    const TransientState d = rate(t, state);
    dealii::Vector<double> r(n);
    for (unsigned int k = 0; k < n; ++k)
      r[k] = d[unknowns[k].second] / scale[unknowns[k].second];
    return r;
  };
  dealii::Vector<double> r = residual(y);
  unsigned int it = 0;
  for (; it < 50; ++it)
  {
    // central-difference Jacobian in the scaled unknowns
    dealii::FullMatrix<double> J(n, n);
    const double h = 1e-6;
    for (unsigned int j = 0; j < n; ++j)
    {
      const unsigned int i = unknowns[j].first;
      TransientState up = y, down = y;
      up[i] += h * scale[i];
      down[i] -= h * scale[i];
      const dealii::Vector<double> ru = residual(up), rd = residual(down);
      for (unsigned int k = 0; k < n; ++k)
        J(k, j) = (ru[k] - rd[k]) / (2 * h);
    }
    J.gauss_jordan();
    dealii::Vector<double> step(n);
    J.vmult(step, r);
    // damped: halve the step until the residual falls
    double lambda = 1;
    TransientState next = y;
    dealii::Vector<double> r_next;
    for (int halving = 0; halving < 20; ++halving, lambda /= 2)
    {
      next = y;
      for (unsigned int j = 0; j < n; ++j)
        next[unknowns[j].first] -= lambda * step[j] * scale[unknowns[j].first];
      try
      {
        r_next = residual(next);
      }
      catch (std::exception &)
      {
        continue; // the film or contact could not be evaluated there: shorter step
      }
      if (r_next.l2_norm() < r.l2_norm() || r.l2_norm() == 0)
        break;
    }
    if (r_next.size() != n)
      throw std::runtime_error("equilibrium: the tilted state left the film's range");
    y = next;
    r = r_next;
    // converged when the full Newton step (the distance to the root), not the damped one, is
    // below 1e-10 of the state's scale
    if (step.linfty_norm() < 1e-10)
      break;
  }
  if (iterations)
    *iterations = it + 1;
  if (it == 50 || !std::isfinite(r.l2_norm()))
  {
    std::ostringstream s;
    s << "equilibrium: the tilted balance did not converge in 50 Newton iterations (scaled "
         "residual "
      << r.l2_norm() << ")";
    throw std::runtime_error(s.str());
  }
  return y;
}
} // namespace sealfe
