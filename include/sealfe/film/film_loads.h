// FilmLoads: the integral results of a film solution (force, moments, leakage, friction) in SI
// units, with the sign conventions of doc/reynolds.md, conventions.
#pragma once

#include <nlohmann/json.hpp>

namespace sealfe
{
/// Loads of the film on the flexibly mounted ring.
///   force_z = int (p - p_ref) dA, moment_x = int (p - p_ref) y dA, moment_y = -int (p - p_ref) x
///   dA, moment_restoring = -int (p - p_ref) r cos(theta - psi) dA, moment_transverse = int (p -
///   p_ref) r sin(theta - psi) dA, leakage_inner/outer: volume flow (m^3/s) through r = ri / r =
///   ro, positive out of the dam, friction_torque: viscous torque resisting the rotor (N m).
struct FilmLoads
{
  double force_z = 0;
  double moment_x = 0;
  double moment_y = 0;
  double moment_restoring = 0;
  double moment_transverse = 0;
  double leakage_inner = 0;
  double leakage_outer = 0;
  double friction_torque = 0;
  double min_film = 0;
  double max_pressure = 0;
  double min_pressure = 0;
  double cavitated_fraction = 0;
  double contact_force = 0;         ///< N, part of force_z carried by the asperities
  double contact_moment_x = 0;      ///< N m, part of moment_x
  double contact_moment_y = 0;      ///< N m, part of moment_y
  double contact_area_fraction = 0; ///< real contact area / nominal area
  double min_film_over_sigma = 0;   ///< min h / composite roughness (inf when smooth)
  double squeeze_flow = 0;          ///< int s dh/dt dA (m^3/s): Q_in + Q_out + squeeze_flow = 0
  double area = 0; ///< area of the dam as integrated (m^2): the discrete domain for the FE model

  nlohmann::json to_json() const;
};

} // namespace sealfe
