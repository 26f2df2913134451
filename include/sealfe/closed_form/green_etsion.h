// Level-0 film coefficients: Green & Etsion's narrow-seal closed forms for a coned face seal
// (direct angular stiffness k11, angular damping d11, cross-coupled (omega1 + omega2)/2 d11).
#pragma once

#include <sealfe/film/film_coefficients.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/operating_conditions.h>

namespace sealfe
{
/// Narrow-seal (ri/ro -> 1) linearised coefficients of a coned face pair about the untilted
/// equilibrium, full film (the hydrostatic pressure is assumed to suppress cavitation).
///
/// Nomenclature of Wileman & Green (Wileman & Green) with R = r/ro, beta = beta* ro/C0, x = beta
/// (1-Ri):
///   E0 = (1 - Ri) Rm / (2 + x)
///   G0 = [ln(1 + x) - 2x/(2 + x)] / (beta^3 (1 - Ri)^2)
///   S  = 6 mu omega_ref (ro/C0)^2 (1 - Ri)^2
///   k11 = pi (po - pi) (beta Ri - 1) E0^2 ro^4 / C0                 [N m/rad]
///   d11 = 2 pi Rm^3 G0 S ro^4 / (C0 omega_ref)
///       = 12 pi mu Rm^3 G0 (1 - Ri)^2 ro^6 / C0^3                   [N m s/rad]
///   cross-coupled stiffness c = (omega1 + omega2)/2 d11
///
/// S carries (1 - Ri)^2, as in Wileman & Green. Varney & Green (2017) (Varney & Green Eq. 21)
/// prints (1 - Ri^2): a typo. The narrow-seal squeeze moment of a flat face is d11 = pi mu rm^3 (ro
/// - ri)^3 / C0^3 (tilt rate gamma_dot squeezes the film by gamma_dot r cos(theta), p = -6 mu h_dot
/// (ro - r)(r - ri)/C0^3, moment arm r cos(theta)), and the G0 above tends to (1 - Ri)/12 as beta
/// -> 0, so only (1 - Ri)^2 in S gives pi mu rm^3 (ro - ri)^3 / C0^3; (1 - Ri^2) would be (1 +
/// Ri)/(1 - Ri) times too large (9x for Ri = 0.8). tests/validation/green_etsion_models.cc checks
/// this by quadrature of Varney & Green (2017)'s own pressure (Eq. 14).
///
/// Both closed forms are the exact moments of the narrow-seal pressures (Varney & Green (2017) Eq.
/// 12 and 14) with the moment arm r^2 (resp. r^3) replaced by rm^2 (rm^3): exact as Ri -> 1, with a
/// relative error O((1 - Ri)^2) otherwise. In dimensional form
///   k11 = pi (po - pi) rm^2 L^2 (beta* ri - C0) / (2 C0 + beta* L)^2,      L = ro - ri,
/// so the film restores (k11 > 0) only if beta* ri > C0 with po > pi: a flat face is
/// destabilising, because a tilt cones the dam locally and the converging side carries more
/// pressure.
///
/// Axial coefficients, derived the same way (area element r dr -> rm dr):
///   K_zz = 2 pi (po - pi) rm L^2 beta* / (2 C0 + beta* L)^2,    D_zz = 2 d11 / rm^2.
class GreenEtsionCoefficients
{
public:
  /// Uses ri, ro, C0 and beta* of the geometry (tilt, waviness and offsets are ignored: the
  /// coefficients are about the untilted axisymmetric equilibrium) and po - pi and mu of the
  /// operating point. Throws std::runtime_error if the inputs make no narrow-seal film.
  GreenEtsionCoefficients(const FilmThickness &geometry, const OperatingConditions &operating);
  GreenEtsionCoefficients(double inner_radius, double outer_radius, double clearance, double coning,
                          double viscosity, double pressure_drop);

  double normalized_coning() const;   // beta = beta* ro / C0
  double radius_ratio() const;        // Ri = ri / ro
  double stiffness_parameter() const; // E0
  double damping_parameter() const;   // G0 (series near beta = 0, where the closed form cancels)
  double seal_parameter(double reference_speed) const; // S (Pa)

  double angular_stiffness() const; // k11, N m/rad
  double angular_damping() const;   // d11, N m s/rad
  double axial_stiffness() const;   // K_zz, N/m
  double axial_damping() const;     // D_zz, N s/m
  /// (omega1 + omega2)/2 d11, N m/rad
  double cross_coupled_stiffness(double rotor_speed, double stator_speed) const;

  /// The 3x3 K and D (level 0) at the given ring speeds:
  ///   K = [[K_zz, 0, 0], [0, k11, c], [0, -c, k11]],   D = diag(D_zz, d11, d11).
  /// The sign of c: the film's hydrodynamic pressure depends on
  /// omega_mean dh/dtheta + dh/dt = z_dot + (tilt_x_dot + omega_mean tilt_y) y
  ///                                        - (tilt_y_dot - omega_mean tilt_x) x,
  /// so M_x = -d11 (tilt_x_dot + omega_mean tilt_y), M_y = -d11 (tilt_y_dot - omega_mean tilt_x).
  FilmCoefficients coefficients(double rotor_speed, double stator_speed) const;

private:
  void validate() const;
  double ri, ro, c0, beta_star, mu, dp;
};

} // namespace sealfe
