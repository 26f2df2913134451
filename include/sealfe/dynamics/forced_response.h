// Steady-state forced response of the seal's angular modes to the rings' misalignments: the
// harmonic tilts it is made of, and the dense complex solve of the dynamic stiffness. The response
// itself is AngularSealDynamics::forced_response (angular_dynamics.h; implemented in
// forced_response.cc with Varney & Green (2017) Appendix B).
#pragma once

#include <complex>
#include <vector>

namespace sealfe
{
/// Tilt (or relative tilt) of a ring in complex notation g = tilt_x + i tilt_y, as a sum of
/// harmonics g(t) = sum forward e^{i W t} + backward e^{-i W t} (W = frequency >= 0; a static
/// part has W = 0 and backward = 0). forward alone is a forward circular whirl.
struct HarmonicTilt
{
  double frequency = 0;
  std::complex<double> forward = 0, backward = 0;
};

/// Steady-state response to the misalignments at one pair of ring speeds.
struct ForcedResponse
{
  double rotor_speed = 0, stator_speed = 0;
  std::vector<HarmonicTilt> stator_tilt, rotor_tilt, relative_tilt;
  /// Largest magnitude over time (sum of |forward| + |backward| of all harmonics: reached when
  /// their frequencies are incommensurate, exact for one harmonic).
  static double max_magnitude(const std::vector<HarmonicTilt> &h);
  /// The harmonic at frequency W (zero if there is none).
  static HarmonicTilt at_frequency(const std::vector<HarmonicTilt> &h, double W);
};

/// x = A^-1 b for a small dense complex system (LAPACK LU with partial pivoting). A singular A
/// means the seal sits exactly on a resonance of an undamped mode: std::runtime_error.
std::vector<std::complex<double>>
solve_dense_complex(const std::vector<std::vector<std::complex<double>>> &A,
                    const std::vector<std::complex<double>> &b);

} // namespace sealfe
