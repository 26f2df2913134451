// Routh-Hurwitz stability test of a real polynomial (Wileman & Green 1991 use it for the FMRR
// seal): the leading principal minors of its Hurwitz matrix. The seal's characteristic polynomial
// is AngularSealDynamics::hurwitz_polynomial (angular_dynamics.h; implemented in routh_hurwitz.cc
// with Wileman & Green's Appendix B).
#pragma once

#include <vector>

namespace sealfe
{
/// Leading principal minors Delta_1..Delta_n of the Hurwitz matrix of the polynomial sum a_k
/// lambda^k given low to high (after scaling lambda so that the coefficients are balanced: the
/// signs are unchanged).
std::vector<double> hurwitz_determinants(const std::vector<double> &coefficients);

/// a_n > 0 and all Hurwitz determinants > 0: every root has a negative real part.
bool is_hurwitz_stable(const std::vector<double> &coefficients);

} // namespace sealfe
