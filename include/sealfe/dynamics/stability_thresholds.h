// Stable speed ranges of a seal: where the stability verdict changes along a swept ring speed
// (grid + bisection), and the closed-form thresholds without support damping (Wileman & Green
// 1991 Eq. 17). The seal's members are AngularSealDynamics::stable_speed_intervals and
// undamped_threshold_speeds (angular_dynamics.h), implemented in stability_thresholds.cc.
#pragma once

#include <functional>

namespace sealfe
{
/// The point between a and b where a yes/no verdict (stability) changes, given that verdict(a)
/// != verdict(b): bisection (Boost.Math) to |b - a| <= 1e-10 max(1, |a|, |b|), the midpoint of
/// the final bracket.
double refine_verdict_change(const std::function<bool(double)> &verdict, double a, double b);

} // namespace sealfe
