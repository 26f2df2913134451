// Time integration of the linear seal equations M q_ddot + C q_dot + K q = f(t) (SUNDIALS ARKode
// through deal.II, implicit): the check of the steady-state forced response and the route to
// transients. AngularSealDynamics::integrate (angular_dynamics.h) uses it with the misalignment
// forcing.
#pragma once

#include <sealfe/dynamics/angular_dynamics.h>

#include <functional>
#include <vector>

namespace sealfe
{
/// q at each of the ascending output_times, from rest (q = q_dot = 0) at t = 0, of
/// M q_ddot + C q_dot + K q = f(t) with M diagonal; force(t, i) is f_i(t). ARKode's implicit
/// stepping with the tolerances given; its linear systems (2 n unknowns) are solved directly.
std::vector<std::vector<double>>
integrate_linear_system(const SecondOrderSystem &system,
                        const std::function<double(double t, unsigned int dof)> &force,
                        double t_end, const std::vector<double> &output_times,
                        double relative_tolerance, double absolute_tolerance);

} // namespace sealfe
