// FlowFactors: Patir & Cheng (1978, 1979) average-flow model of a rough film -- pressure and
// shear flow factors, expected gap and shear-stress factors as functions of the local film h.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <atomic>
#include <limits>
#include <string>

namespace sealfe
{
/// A value and its derivative with respect to the nominal film thickness h (units of value / m).
struct ValueAndSlope
{
  double value;
  double d_dh;
};

/// The published Patir & Cheng fits as plain functions of the film parameter H = h/sigma and the
/// Peklenik surface pattern gamma (correlation length along sliding / across sliding). Derivatives
/// are d/dH. No clamping here: the caller (FlowFactors) decides what to do below the validity
/// limits, which are exposed too. gamma must lie in [1/9, 9]; between the seven tabulated values
/// the fits are interpolated in ln(gamma) (pressure flow factor: see pressure_flow_factor; the
/// others: their values, linearly). The rules are symmetric in ln(gamma), which keeps
/// phi_y(H, gamma) = phi_x(H, 1/gamma) exact for every gamma.
namespace patir_cheng
{
/// The seven surface patterns of the published tables.
constexpr int n_patterns = 7;
extern const double tabulated_patterns[n_patterns]; // 1/9, 1/6, 1/3, 1, 3, 6, 9

/// Largest H of the published fits (the range of PC's simulations) and the H from which the
/// pressure flow factor is Tripp's asymptote alone.
constexpr double fits_upper_limit = 6.;
constexpr double tripp_from = 12.;

/// Tripp's (1983) second-order shape of the pressure flow factor, phi_x = 1 + T(gamma)/H^2 for
/// large H: T(gamma) = 3 (1 - 3/(1 + gamma)), zero at gamma = 2 (doc/roughness.md, 2.2).
double tripp_shape(double gamma);

/// Pressure flow factor along x (the sliding direction). For H <= 6 the PC 1978 Table 1 fits,
///   gamma <= 1: phi_x = 1 - C exp(-r H);   gamma > 1: phi_x = 1 + C H^-r,
/// exact at the tabulated gamma; in between, the departure phi_x - 1 linear in ln(gamma), except
/// between gamma = 1 and 3 (where it changes sign) the departure over T(gamma). For H >= 12
/// Tripp's 1 + T(gamma)/H^2; a C1 blend of the two for 6 < H < 12.
ValueAndSlope pressure_flow_factor(double H, double gamma);
/// Smallest H at which the pressure flow factor fit is valid (1, 1, 0.75, 0.5, 0.5, 0.5, 0.5).
double pressure_flow_factor_validity(double gamma);

/// Shear flow factor Phi_s (one face rough, PC 1979):
///   H <= 5: A1 H^a1 exp(-a2 H + a3 H^2);   H > 5: A2 exp(-0.25 H). Valid for H > 0.5.
ValueAndSlope shear_flow_factor(double H, double gamma);

/// Couette shear-stress factor phi_f = h E[1/h_T] (PC 1979), closed form for the polynomial height
/// density 35/(32c) (1 - d^2/c^2)^3, c = 3 sigma, with the local gap cut off at eps = c/300 for
/// H <= 3. Independent of gamma.
ValueAndSlope couette_shear_factor(double H);
/// Roughness shear-stress factor Phi_fs (one face rough): A3 H^a4 exp(-a5 H + a6 H^2) for
/// H < 7, 0 beyond (PC 1979). Valid for H > 0.5.
ValueAndSlope roughness_shear_factor(double H, double gamma);
/// Poiseuille shear-stress factor phi_fp = 1 - D exp(-s H) (PC 1979). Valid for H > 0.5.
ValueAndSlope poiseuille_shear_factor(double H, double gamma);

/// Lower validity limit of the shear flow and shear-stress fits.
constexpr double shear_validity = 0.5;

/// Expected gap for Gaussian heights of standard deviation sigma, in units of sigma:
///   h_T/sigma = H Phi(H) + phi(H),  d(h_T/sigma)/dH = Phi(H)
/// with phi, Phi the standard normal density and distribution. Valid for every H.
ValueAndSlope expected_gap(double H);
} // namespace patir_cheng

/// The average-flow description of the film for the Reynolds solver. Reads subsection
/// "Roughness". x is the sliding direction (circumferential, theta), y the radial direction.
///
/// The film equation this feeds (doc/reynolds.md, conventions):
///   div( diag(phi_r, phi_theta) h^3/(12 mu) grad p ) = div( h_T u_mean )
///                      + div( (u1 - u2)/2 sigma phi_s ) + d h_T/dt,
/// u1 the rotor surface velocity, u2 the stator's. With Model = none every factor is its smooth
/// value (phi = 1, phi_s = 0, h_T = h, phi_f = phi_fp = 1, phi_fs = 0).
///
/// Below the fits' validity limit (H = h/sigma < 0.5 .. 1 depending on factor and pattern) a
/// factor is evaluated at the limit, its slope is zero, the event is counted and the first one in
/// the process prints a warning to std::cerr. Ask clamp_count() after a solve to know.
class FlowFactors
{
public:
  enum class Model
  {
    none,
    patir_cheng
  };

  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);
  /// Throws std::runtime_error if sigma <= 0 (Patir-Cheng), gamma outside [1/9, 9] or the
  /// share outside [0, 1].
  void validate() const;

  FlowFactors() = default;
  FlowFactors(Model model, double composite_roughness, double surface_pattern = 1.,
              double rotor_roughness_share = 0.5);
  FlowFactors(const FlowFactors &other);
  FlowFactors &operator=(const FlowFactors &other);

  Model model() const { return model_; }
  bool is_smooth() const { return model_ == Model::none; }
  /// sigma = sqrt(sigma_rotor^2 + sigma_stator^2) (m); it multiplies phi_s in the film equation.
  double composite_roughness() const { return sigma; }
  double surface_pattern() const { return gamma; }
  double rotor_roughness_share() const { return rotor_share; }
  double film_parameter(const double h) const { return h / sigma; }

  /// Pressure flow factor along sliding, phi_theta = phi_x(H, gamma).
  ValueAndSlope circumferential_pressure_flow_factor(double h) const;
  /// Pressure flow factor across sliding, phi_r = phi_y(H, gamma) = phi_x(H, 1/gamma). This one
  /// sets the leakage.
  ValueAndSlope radial_pressure_flow_factor(double h) const;
  /// Signed shear flow factor phi_s = (V_r1 - V_r2) Phi_s with V_r1 = share (rotor),
  /// V_r2 = 1 - share (stator); it multiplies (u1 - u2)/2 sigma.
  ValueAndSlope shear_flow_factor(double h) const;
  /// Expected gap h_T (m) and d h_T/dh (the probability that the faces are apart locally).
  ValueAndSlope expected_gap(double h) const;

  /// Everything the Reynolds assembly needs at one point, in one call.
  struct FilmFactors
  {
    ValueAndSlope phi_theta, phi_r, phi_s, h_T;
  };
  FilmFactors film_factors(double h) const;

  /// Shear-stress factors for the friction torque (PC 1979); phi_fs is signed like phi_s.
  struct ShearStressFactors
  {
    ValueAndSlope phi_f, phi_fs, phi_fp;
  };
  ShearStressFactors shear_stress_factors(double h) const;

  /// Mean viscous shear stress (Pa) the film exerts on the rotor face (face 1) along the sliding
  /// direction, for surface speeds u1 (rotor), u2 (stator) and mean pressure gradient dp/dx:
  ///   tau_1 = mu (u2 - u1)/h (phi_f - phi_fs) - phi_fp h/2 dp/dx.
  /// Smooth: the Couette + Poiseuille wall stress at z = 0 of a film with face 1 at z = 0.
  double rotor_shear_stress(double h, double viscosity, double u_rotor, double u_stator,
                            double dp_dx) const;
  /// The same on the stator face (face 2):
  ///   tau_2 = mu (u1 - u2)/h (phi_f + phi_fs) - phi_fp h/2 dp/dx.
  double stator_shear_stress(double h, double viscosity, double u_rotor, double u_stator,
                             double dp_dx) const;

  /// Number of evaluations clamped at a validity limit since construction / the last reset.
  unsigned long clamp_count() const { return n_clamped.load(std::memory_order_relaxed); }
  /// Smallest H seen in a clamped evaluation (+inf if none).
  double lowest_clamped_film_parameter() const
  {
    return lowest_clamped.load(std::memory_order_relaxed);
  }
  void reset_clamp_record() const;
  /// Re-arm the once-per-process warning (for tests).
  static void rearm_clamp_warning();

private:
  /// H raised to `limit` if below it (recording the event); `clamped` tells the caller.
  double limited(double H, double limit, bool &clamped) const;

  Model model_ = Model::none;
  double sigma = 1e-7;
  double gamma = 1;
  double rotor_share = 0.5;

  mutable std::atomic<unsigned long> n_clamped{0};
  mutable std::atomic<double> lowest_clamped{std::numeric_limits<double>::infinity()};
};

} // namespace sealfe
