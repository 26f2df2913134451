// Equilibrium: the axial position at which film + asperity contact + support carry the closing
// force of Green 2002 Eq. 22, with the coning at its quasi-static thermal value (Eq. 11, d/dt = 0).
#pragma once

#include <sealfe/dynamics/stator_transient.h>

namespace sealfe
{
struct SealEquilibrium
{
  double axial_offset = 0; ///< z (m)
  double coning = 0;       ///< rad
  FilmLoads film;
  FaceContact::Loads contact;
  double closing_force = 0;
  double support_force = 0; ///< -K_sz z
  int roots_found = 0;      ///< sign changes of the balance on the clearance scan
};

/// Solves F_f(z, beta(z)) + F_c(z) - K_sz z = F_cls at the tilt-free state of `state` (speeds and
/// pressures; tilts are not solved: stator misalignment and runout are ignored here) with
/// Boost.Math toms748 on the first sign change of a geometric scan of the clearance from
/// 0.5 sigma to 1e3 C0. Throws std::runtime_error (one line, which way and by how much) if the
/// closing force exceeds what contact at 0.5 sigma carries or is below the film's force at
/// 1e3 C0 (the faces would open without bound).
SealEquilibrium solve_equilibrium(const FlexibleStatorSeal &seal, const FilmForceModel &film,
                                  const FilmState &state);

/// The operating point with tilts: a steady state of the transient's equations (see
/// StatorTransient::steady_state) for a seal whose ramps hold the conditions constant.
struct SteadyWhirl
{
  TransientState state{};
  unsigned int newton_iterations = 0;  ///< summed over the continuation steps
  unsigned int continuation_steps = 0; ///< steady states solved on the way
};

/// Continuation in the forcing from `guess` (the axisymmetric balance): runout, dynamic and
/// stator misalignment scaled by s from 0 to 1, each steady state the next one's Newton guess,
/// the increment halved on a failure. This follows the branch that grows out of the linear
/// response; a large whirl near a critical speed opens the faces and the branch can end in a
/// fold, which is refused (std::runtime_error, one line with the fraction reached).
/// NoSteadyState propagates.
SteadyWhirl solve_steady_whirl(const FlexibleStatorSeal &seal, const FilmForceModel &film,
                               const TransientSettings &settings, const TransientState &guess);

/// The quasi-static coning at film state `state` (Eq. 11 with d/dt = 0): beta = f(h(beta)),
/// solved by toms748 (beta on [0, f(h(0))]: h grows with beta, so the root is unique).
double quasi_static_coning(const FlexibleStatorSeal &seal, FilmState state);
} // namespace sealfe
