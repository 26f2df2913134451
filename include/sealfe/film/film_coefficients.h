// FilmCoefficients: the linearised stiffness K and damping D of the fluid film about an operating
// point, in the degrees of freedom q = (z, tilt_x, tilt_y) — the interface every film level fills.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <string>

namespace sealfe
{
/// Dynamic coefficients of the film (doc/reynolds.md, conventions):
///   K_ij = -dF_i/dq_j,  D_ij = -dF_i/dq_dot_j,  F = (F_z, M_x, M_y),  q = (z, tilt_x, tilt_y)
/// with q the displacement of the flexible ring relative to its mate (conventions of
/// film/film_thickness.h: the face moves axially by w = z + tilt_x y - tilt_y x).
/// Units: K_zz N/m, K_z,tilt N/rad, K_tilt,z N m/m, K_tilt,tilt N m/rad; D likewise per unit rate.
///
/// The moments of the film on the two faces are equal and opposite and the relative tilt changes
/// sign when the roles of the rings are swapped, so K and D do not depend on which ring is called
/// the flexible one.
///
/// For an axisymmetric equilibrium (no tilt, no waviness) the tilt block has the rotationally
/// invariant form
///   K_tilt = [[k, c], [-c, k]],   D_tilt = [[d, e], [-e, d]]
/// with k the direct angular stiffness, c the cross-coupled stiffness of the rotating film
/// (c = (omega1 + omega2)/2 d for the narrow seal) and e a cross-coupled damping (zero for the
/// narrow seal). The dynamics module uses the tilt block only: at such an equilibrium the axial
/// and angular modes decouple (Wileman & Green 1991).
struct FilmCoefficients
{
  using Matrix3 = std::array<std::array<double, 3>, 3>;

  Matrix3 stiffness{};    // K
  Matrix3 damping{};      // D
  int level = 0;          // 0 closed form, 1 table, 2 finite element (doc/reynolds.md, Levels)
  std::string model;      // which producer, for the summary
  double rotor_speed = 0; // rad/s, the speeds the coefficients belong to
  double stator_speed = 0;

  /// Rotationally invariant parts of the tilt block (the averages remove any anisotropy).
  double tilt_direct_stiffness() const { return 0.5 * (stiffness[1][1] + stiffness[2][2]); }
  double tilt_cross_stiffness() const { return 0.5 * (stiffness[1][2] - stiffness[2][1]); }
  double tilt_direct_damping() const { return 0.5 * (damping[1][1] + damping[2][2]); }
  double tilt_cross_damping() const { return 0.5 * (damping[1][2] - damping[2][1]); }

  /// True if the tilt blocks have the form [[a, b], [-b, a]] to within rel_tol of their largest
  /// entry: the condition under which the two real tilt equations of a ring combine into one
  /// complex equation (Wileman & Green, FMRR stability, Eq. 3: the Routh-Hurwitz route).
  bool tilt_block_is_isotropic(const double rel_tol = 1e-9) const
  {
    auto check = [rel_tol](const Matrix3 &m)
    {
      const double scale = std::max(
          {std::abs(m[1][1]), std::abs(m[1][2]), std::abs(m[2][1]), std::abs(m[2][2]), 1e-300});
      return std::abs(m[1][1] - m[2][2]) <= rel_tol * scale &&
             std::abs(m[1][2] + m[2][1]) <= rel_tol * scale;
    };
    return check(stiffness) && check(damping);
  }

  nlohmann::json to_json() const
  {
    auto rows = [](const Matrix3 &m)
    {
      nlohmann::json a = nlohmann::json::array();
      for (const auto &row : m)
        a.push_back({row[0], row[1], row[2]});
      return a;
    };
    return {{"stiffness", rows(stiffness)},
            {"damping", rows(damping)},
            {"film_model_level", level},
            {"film_model", model},
            {"angular_stiffness", tilt_direct_stiffness()},
            {"cross_coupled_stiffness", tilt_cross_stiffness()},
            {"angular_damping", tilt_direct_damping()},
            {"cross_coupled_damping", tilt_cross_damping()},
            {"rotor_speed", rotor_speed},
            {"stator_speed", stator_speed}};
  }
};

} // namespace sealfe
