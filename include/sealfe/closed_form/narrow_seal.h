// Narrow-seal film model (level 0 of doc/reynolds.md, Levels): the closed-form pressure of a narrow
// face seal (hydrostatic coned part + hydrodynamic tilt/waviness/squeeze part) and its loads, and
// Etsion's (1977) closed forms for the force and moments of a tilted flat seal.
#pragma once

#include <sealfe/film/cavitation.h>
#include <sealfe/film/film_loads.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/operating_conditions.h>

#include <deal.II/base/parameter_handler.h>

#include <vector>

namespace sealfe
{
// The Cavitation enum (none | half_sommerfeld) lives in cavitation.h.

/// How radii outside the film thickness enter the loads.
///  kept:      the definitions of film_loads.h, dA = r dr dtheta, moment arms r, speed omega r.
///  neglected: Etsion's "neglecting curvature effects": every such r is the mean radius r_m
///             (dA = r_m dr dtheta, arms r_m, Couette speed omega r_m). Etsion's closed forms are
///             the exact integrals of the narrow-seal pressure in this measure.
/// The pressure itself is the same in both; leakage always uses the length element r_m dtheta
/// (see NarrowSealModel).
enum class Curvature
{
  kept,
  neglected
};

/// Quadrature of the loads: Gauss-Legendre in r (per smooth piece of the radial profile) and, in
/// theta, the periodic trapezoid rule for a smooth film or Gauss-Legendre between the angles where
/// the half-Sommerfeld cavity appears/disappears (see NarrowSealModel::rupture_angles).
struct NarrowSealQuadrature
{
  unsigned int radial_points = 24;
  unsigned int angular_points = 512;
  Curvature curvature = Curvature::kept;

  /// Subsection "Narrow seal": "Radial quadrature points", "Angular quadrature points",
  /// "Curvature in loads" (kept | neglected). Optional: the defaults are accurate to 5e-10
  /// relative for tilts up to eps = 0.99 (4e-11 up to eps = 0.9; doc/narrow_seal.md).
  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);
};

/// The narrow-seal pressure p(r, theta) on the dam ri <= r <= ro and its loads.
///
/// Narrow seal: the circumferential pressure flow and the curvature of the dam are neglected, so
/// the Reynolds equation of doc/reynolds.md, conventions becomes, on each radial line,
///
///   d/dr( h^3 dp/dr ) = 12 mu ( wbar dh/dtheta + dh/dt ) =: S(theta),   wbar = (w1 + w2)/2,
///
/// with p(ri) = pi, p(ro) = po. The source S is read at the mean radius r_m = (ri + ro)/2 (Etsion
/// 1977 Eq. 3: dh/dtheta is "almost unaffected by the radius"); h(r, theta) keeps its full radial
/// variation, linear in r at fixed theta (h = h_i + b (r - ri)). The exact solution is
///
///   p = p_s + p_d,
///   p_s = po - (po - pi) h_i^2 (h_o^2 - h^2) / (h^2 (h_o^2 - h_i^2))            [V&G Eq. 12]
///       = po - (po - pi) (h_i/h)^2 (ro - r)(h_o + h) / ((ro - ri)(h_o + h_i))  [as coded: no
///         0/0 when the line is parallel, b = 0, where it is the linear profile],
///   p_d = -(S / 2) (ro - r)(r - ri) / (h_m h^2),   h_m = h(r_m, theta) = (h_i + h_o)/2,
///
/// since d/dr(h^3 d/dr[(ro - r)(r - ri)/h^2]) = -2 h(r_m) for any h linear in r. For one face at
/// omega, S/2 = 3 mu (omega dh/dtheta + 2 dh/dt): Varney & Green Eq. 14 with dh/dtheta, dh/dt at
/// r_m, and for the tilted flat face Etsion's Eq. 9. This is the form whose integrals (with
/// Curvature::neglected) are exactly Etsion's closed forms (namespace etsion below).
///
/// Radial flow: q_r = -h^3/(12 mu) dp/dr per unit circumferential length, with
/// h^3 dp_s/dr = 2 (po - pi) h_i^2 h_o^2 / ((ro - ri)(h_i + h_o)) (constant in r) and
/// h^3 dp_d/dr = S (r - r') (Etsion Eq. 4). The narrow equation is mass conservation in a slab of
/// circumferential length 2 pi r_m, so the leakage through r = ri and r = ro is integrated with the
/// length element r_m dtheta; with it, inflow = outflow holds exactly (using ri and ro instead
/// would create a spurious mismatch by the factor ro/ri).
///
/// Angles: theta from +x towards +y, faces moving in +theta, film thickest at theta = psi
/// (film_thickness.h). Etsion's angle is theta_E = theta - psi (his h = C + gamma r cos theta_E);
/// Varney & Green's (h ~ gamma r sin(theta_VG - psi_VG)) is theta_VG = theta, psi_VG = psi - pi/2.
class NarrowSealModel
{
public:
  /// Copies the geometry and operating point; throws std::runtime_error (one line) if either is
  /// invalid (film touch-down included) or if p_cav exceeds a boundary pressure under
  /// half-Sommerfeld (the clipping would then change the boundary values).
  NarrowSealModel(const FilmThickness &film, const OperatingConditions &conditions,
                  Cavitation cavitation = Cavitation::half_sommerfeld,
                  double cavitation_pressure = 0);

  /// Hydrostatic coned-face pressure p_s (Pa).
  double hydrostatic_pressure(double r, double theta) const;
  /// Hydrodynamic pressure p_d (Pa) from the wedge (mean speed) and squeeze terms.
  double hydrodynamic_pressure(double r, double theta) const;
  /// p_s + p_d, no cavitation.
  double full_film_pressure(double r, double theta) const;
  /// The model's pressure: full film, or clipped at p_cav under half-Sommerfeld.
  double pressure(double r, double theta) const;
  /// h^3 dp/dr of the full-film field (Pa m^2); linear in r on each radial line.
  double h3_dp_dr(double r, double theta) const;
  /// Source S(theta) = 12 mu (wbar dh/dtheta + dh/dt), read at r_m (Pa m).
  double source(double theta) const;

  /// Angles in [0, 2 pi) where a half-Sommerfeld cavity appears or disappears on the radial lines
  /// (sign changes of min_r h^2 (p - p_cav) / ((ro - r)(r - ri)), found on `samples` uniform angles
  /// and refined by bisection to round-off). Empty for Cavitation::none or an uncavitated film.
  /// Cavities narrower than 2 pi / samples can be missed.
  std::vector<double> rupture_angles(unsigned int samples) const;

  /// Force, moments, leakage, friction, extremes and cavitated fraction (film_loads.h; the
  /// fraction is 0 without a cavitation model). Under half-Sommerfeld the leakage is that of the
  /// clipped field, so inflow and outflow need not balance.
  FilmLoads loads(const NarrowSealQuadrature &quadrature = {}) const;

  const FilmThickness &film() const { return film_; }
  const OperatingConditions &conditions() const { return conditions_; }

private:
  struct RadialLine;
  RadialLine line(double theta) const;

  FilmThickness film_;
  OperatingConditions conditions_;
  Cavitation cavitation_;
  double cavitation_pressure_;
};

/// The narrow-seal loads in one call (what `sealfe solve` uses for "Film model = narrow seal").
FilmLoads compute(const FilmThickness &film, const OperatingConditions &conditions,
                  Cavitation cavitation = Cavitation::half_sommerfeld,
                  const NarrowSealQuadrature &quadrature = {}, double cavitation_pressure = 0);

/// Etsion, "Hydrodynamic effects in a misaligned radial face seal", NASA CR-135228 (1977): the
/// hydrodynamic loads of a flat seal (no coning) tilted by gamma, h = C (1 + eps R cos theta_E),
/// eps = gamma ro / C, R = r/ro, Ri = ri/ro, one face at omega, integrated with curvature
/// neglected. Dimensionless as in his nomenclature: F = Fbar * 6 mu omega (ro/C)^2 ro^2, M = Mbar *
/// 6 mu omega (ro/C)^2 ro^3. The printed Eqs. 29, 43, 52, 56, 58 carry typos; these are re-derived
/// from the pressure (Eq. 9) and reproduce Table I (doc/narrow_seal.md). They are evaluated in a
/// form free of the 1/eps^2 cancellations of the printed ones, so they stay accurate as eps -> 0
/// (relative round-off ~ 1e-16 / (1 - Ri)^2), and hold up to eps = 1.
namespace etsion
{
/// Fbar, half-Sommerfeld (Eq. 29 corrected; Eq. 34 at eps = 1). 0 <= eps <= 1, 0 <= Ri < 1.
double force(double eps, double Ri);
/// Restoring moment Mbar_x, half-Sommerfeld (Eq. 43 corrected; Eq. 46 at eps = 1).
double restoring_moment(double eps, double Ri);
/// Transverse moment Mbar_z, half-Sommerfeld (Eq. 56 corrected).
double transverse_moment(double eps, double Ri);
/// Transverse moment Mbar_z, full film (Eq. 58 corrected) = 2 x the half-Sommerfeld value; the
/// full-film hydrodynamic force and restoring moment vanish (antisymmetric pressure).
double transverse_moment_full_film(double eps, double Ri);

/// Small-tilt limits (Eqs. 33, 45, 57, 59): eps (1-Ri)^3 Rm^2 / 6, eps^2 (1-Ri)^3 Rm^4 / 6,
/// pi eps (1-Ri)^3 Rm^3 / 24 and pi eps (1-Ri)^3 Rm^3 / 12. Their relative errors are
/// c eps^2 with c = (11 + 18 Ri + 11 Ri^2)/20, (13 + 14 Ri + 13 Ri^2)/20,
/// (33 + 54 Ri + 33 Ri^2)/80 (both moments' c) respectively.
double force_small_tilt(double eps, double Ri);
double restoring_moment_small_tilt(double eps, double Ri);
double transverse_moment_small_tilt(double eps, double Ri);
double transverse_moment_full_film_small_tilt(double eps, double Ri);

/// 6 mu omega (ro/C)^2 ro^2 (N) and its product with ro (N m): Etsion's load scales.
double force_scale(double viscosity, double omega, double clearance, double outer_radius);
double moment_scale(double viscosity, double omega, double clearance, double outer_radius);

/// Dimensional hydrodynamic loads of Etsion's closed forms for a FilmThickness/OperatingConditions
/// pair, in the sign conventions of film_loads.h (moment_x/y rotated from the tilt frame by psi).
struct TiltLoads
{
  double eps = 0;
  double force_z = 0;
  double moment_restoring = 0;
  double moment_transverse = 0;
  double moment_x = 0;
  double moment_y = 0;
};
/// Requires a flat, non-wavy, non-squeezing film (coning, waviness and squeeze rates zero; throws
/// std::invalid_argument otherwise) and eps = gamma ro / (C0 + z) <= 1. omega = w1 + w2 (twice
/// the mean speed: only the mean surface speed enters); a negative omega mirrors the film, which
/// keeps force and restoring moment and reverses the transverse moment. The hydrostatic part
/// (pi, po) is not included: under half-Sommerfeld Etsion's forms assume pi = po = p_cav.
TiltLoads loads(const FilmThickness &film, const OperatingConditions &conditions,
                Cavitation cavitation);
} // namespace etsion

} // namespace sealfe
