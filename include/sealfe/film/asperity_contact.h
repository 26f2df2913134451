// AsperityContact: mean asperity contact pressure p_c(h/sigma) and real contact area of two rough
// faces, GW (elastic) / CEB (plastic) model in the closed form of Green (2002), Eq. 1-10.
#pragma once

#include <sealfe/film/flow_factors.h>

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace sealfe
{
/// The dimensionless integrals of Green (2002) Eq. 2a/2b, in units of sigma (all lengths / sigma).
/// s = sigma_s/sigma (asperity-height deviation), w = omega*_c (critical interference),
/// a = h* - y*_s (separation of the mean asperity plane from the countersurface).
namespace gw_ceb
{
/// Gaussian density of the asperity heights, Eq. 3: exp(-z^2/(2 s^2)) / (sqrt(2 pi) s).
double asperity_height_density(double z, double s);
/// Exact plastic integral, Eq. 8: I_p = Int_{a+w}^inf 2 (z - a - w/2) phi*(z) dz
///   = sqrt(2/pi) s exp(-(a+w)^2/(2 s^2)) - (a + w/2) erfc((a+w)/(sqrt(2) s)),
/// and dI_p/da = -w phi*(a+w) - erfc((a+w)/(sqrt(2) s)).
ValueAndSlope plastic_integral(double a, double s, double w);
/// Mean-value approximation of the elastic integral, Eq. 6 with the exponent corrected:
///   I_e = Int_a^{a+w} (z - a)^{3/2} phi*(z) dz ~ (1/2)^{3/2} w^{5/2} phi*(a + w/2).
/// (The printed Eq. 6/7a carry w^{9/2}.) For w -> 0 it is 5/(4 sqrt 2) = 0.884 of the exact
/// integral: the midpoint rule on (z - a)^{3/2}.
ValueAndSlope elastic_integral(double a, double s, double w);
/// Mean-value approximation of the elastic area integral, Eq. 7b:
///   Int_a^{a+w} (z - a) phi*(z) dz ~ (w^2/2) phi*(a + w/2)
/// (exact for a uniform density; relative error +(a+w/2) w/(6 s^2) to first order).
double elastic_area_integral(double a, double s, double w);
} // namespace gw_ceb

/// Parameters of the GW/CEB model; defaults are Green (2002) Table 1 (plus sigma_s = sigma,
/// y_s = 0, which the paper does not list; see doc/roughness.md).
struct AsperityContactParameters
{
  double composite_roughness = 1e-7;   // sigma (m), RMS of the combined surface heights
  double asperity_radius = 1.7e-6;     // R (m)
  double asperity_density = 4.16e11;   // eta (1/m^2)
  double plasticity_index = 6.6167;    // Psi; omega*_c = sigma*_s / Psi^2
  double elastic_modulus = 24.07e9;    // E (Pa), 1/E = (1-nu1^2)/E1 + (1-nu2^2)/E2
  double hardness = 1e9;               // H (Pa) of the softer material
  double pressure_factor = 0.6;        // K, maximum contact pressure factor (CEB)
  double asperity_deviation_ratio = 1; // sigma*_s = sigma_s/sigma
  double asperity_offset = 0;          // y*_s = y_s/sigma, mean of asperities above mean of heights
};

/// Mean contact pressure of the asperities over the nominal area, for the Reynolds loads.
/// Reads subsection "Contact"; sigma is the "Roughness" subsection's Composite roughness (one
/// roughness for both models), so FlowFactors::declare_parameters must have been called too.
///
/// h is the local nominal film thickness of Green (2002) Eq. 24 (and of doc/reynolds.md): the
/// distance between the mean planes of the two faces' surface heights, the same h the Reynolds
/// equation and the flow factors use. h* = h/sigma; asperities touch where their height above their
/// own mean exceeds h - y_s. h may be zero or negative (faces pressed into each other): the
/// formulas hold, but the model's independent-asperity assumption does not once the real contact
/// area fraction is no longer small.
class AsperityContact
{
public:
  enum class Model
  {
    none,
    gw_ceb
  };

  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);
  /// The same with sigma given (FilmSettings passes the flow factors' composite roughness, so
  /// this module does not read another module's subsection).
  void parse_parameters(dealii::ParameterHandler &prm, double composite_roughness);
  /// Throws std::runtime_error if a parameter is not positive (y_s may be any finite number).
  void validate() const;

  AsperityContact() = default;
  AsperityContact(Model model, const AsperityContactParameters &parameters);

  Model model() const { return model_; }
  bool enabled() const { return model_ != Model::none; }
  const AsperityContactParameters &parameters() const { return p; }

  /// beta = eta R sigma (Green's "beta", not the coning).
  double asperity_parameter() const;
  /// omega*_c = sigma*_s / Psi^2, the critical interference over sigma.
  double critical_interference() const;
  /// CEB plasticity index Psi = (2 E/(pi K H)) sqrt(sigma_s/R), for comparison with the input.
  static double ceb_plasticity_index(double elastic_modulus, double hardness,
                                     double pressure_factor, double asperity_radius,
                                     double asperity_height_deviation);

  /// p_c = p_ce + p_cp (Pa), Eq. 10, and dp_c/dh (Pa/m). Zero for Model = none.
  ValueAndSlope contact_pressure(double h) const;
  /// Elastic part p_ce, Eq. 7a (mean-value approximation, exponent 5/2).
  ValueAndSlope elastic_contact_pressure(double h) const;
  /// Plastic part p_cp, Eq. 9a (exact).
  ValueAndSlope plastic_contact_pressure(double h) const;

  /// Real contact area over nominal area, A_e/A_n + A_p/A_n (Eq. 7b + Eq. 9b).
  double real_contact_area_fraction(double h) const;
  double elastic_contact_area_fraction(double h) const;
  double plastic_contact_area_fraction(double h) const;

private:
  double separation(double h) const; // a = h/sigma - y*_s

  Model model_ = Model::none;
  AsperityContactParameters p;
};

} // namespace sealfe
