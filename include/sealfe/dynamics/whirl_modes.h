// The modes of the angular dynamics at one pair of ring speeds as a dynamics engineer reads them
// on a Campbell diagram: signed whirl frequency (forward > 0), damping ratio, which ring moves.
#pragma once

#include <sealfe/dynamics/angular_dynamics.h>

#include <complex>
#include <vector>

namespace sealfe
{
/// One free-vibration mode q = Re(v e^{lambda t}) of AngularSealDynamics. The real equations have
/// lambda and its conjugate for each whirling mode; a WhirlMode is the pair, its direction taken
/// from the eigenvector: with z = t_x + i t_y a ring's tilt, z = a e^{lambda t} + b e^{conj(lambda)
/// t}; the mode whirls forward (counter-clockwise, the sense of a positive ring speed) if
/// sum |a|^2 > sum |b|^2 over the rings.
struct WhirlMode
{
  std::complex<double> eigenvalue; ///< lambda with Im(lambda) >= 0 (1/s)
  /// Signed whirl frequency (rad/s): +Im(lambda) for a forward mode, -Im(lambda) backward, 0
  /// for a non-oscillating (real) eigenvalue.
  double whirl_frequency;
  double damping_ratio; ///< -Re(lambda)/|lambda| (< 0: the mode grows)
  double stator_share;  ///< share of the stator ring in sum |tilt|^2 of the mode (0..1)
};

/// The modes at (rotor_speed, stator_speed), by decreasing real part (least damped first): one
/// per conjugate pair of eigenvalues and one per real eigenvalue. The eigenvector of each pair
/// comes from two steps of inverse iteration (complex LU of A - sigma I, sigma next to lambda).
std::vector<WhirlMode> whirl_modes(const AngularSealDynamics &dynamics, double rotor_speed,
                                   double stator_speed);
} // namespace sealfe
