// Annular (radial-clearance) seals: radial stiffness and leakage of straight, tapered and stepped
// high-stiffness seals (Fleming, NASA TM X-73654), their optimisation and `sealfe annular`.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sealfe::annular
{
/// Clearance distribution along the axis: constant; a uniform taper from C1 at the inlet to C2 at
/// the outlet; or C1 over the inlet length L1 = gamma L and C2 over the rest (a step).
enum class Geometry
{
  straight,
  tapered,
  stepped
};

/// What the optimiser maximises: the radial stiffness K, or K per unit leakage M.
enum class Objective
{
  stiffness,
  stiffness_per_leakage
};

Geometry geometry_from_string(const std::string &name);
std::string to_string(Geometry geometry);
std::string to_string(Objective objective);

/// The seal in Fleming's variables; every length is scaled by the outlet (minimum) clearance C2
/// and the axial coordinate by L. The model is Fleming's (Eq. 5): incompressible, turbulent
/// one-dimensional axial flow with Fanning friction, Bernoulli acceleration from upstream
/// stagnation, no rotation, and small eccentricity. Two generalisations reduce to the paper when
/// they are zero: an entrance loss xi (p drops by (1 + xi) rho V1^2 / 2 at the inlet, as in
/// Black's seal analysis) and a clearance-dependent friction factor f(h) = f2 (h / C2)^(-s)
/// (s = 0.29 is Fleming's fully-rough fit, applied locally, including around the eccentric gap).
struct DimensionlessSeal
{
  Geometry geometry = Geometry::stepped;
  double clearance_ratio = 1;   // H = C1 / C2 >= 1 (ignored for straight seals)
  double step_ratio = 1;        // gamma = L1 / L in (0, 1] (stepped seals only)
  double lambda = 1;            // Lambda = f2 L / C2, f2 the friction factor at the outlet
  double entrance_loss = 0;     // xi >= 0; the paper neglects entrance losses (xi = 0)
  double friction_exponent = 0; // s; 0: constant friction factor (the paper's analysis)
};

/// Kbar = K C2 / ((p0 - pL) L D) (Eq. 17) and Mbar = M / (pi D C2 sqrt((p0 - pL) rho)) (Eq. 20).
struct DimensionlessCoefficients
{
  double stiffness = 0;
  double leakage = 0;
};

/// Fleming's coefficients A, B, E, G (Eq. 15) for constant friction and no entrance loss:
/// the concentric pressure integral is J = -(p0 - pL) L (A + B eps cos(theta)) / (E + G eps ...).
struct FlemingCoefficients
{
  double A = 0, B = 0, E = 0, G = 0;
};

/// Eq. 15 as printed (straight seals are tapered seals with H = 1).
FlemingCoefficients fleming_coefficients(Geometry geometry, double clearance_ratio,
                                         double step_ratio, double lambda);
/// The paper's closed form: Kbar = pi (B E - A G) / (2 E^2) (Eq. 17), Mbar = sqrt(2 H^3 / E)
/// (Eq. 20). Valid only for entrance_loss = 0 and friction_exponent = 0.
DimensionlessCoefficients fleming_closed_form(Geometry geometry, double clearance_ratio,
                                              double step_ratio, double lambda);

/// The general model: Kbar and Mbar from the exact eccentricity derivative of the pressure
/// integral, with the axial integrals done by Gauss-Legendre quadrature (exact for straight and
/// stepped seals, to rounding for tapered ones). Equals fleming_closed_form when xi = s = 0.
DimensionlessCoefficients dimensionless_coefficients(const DimensionlessSeal &seal);

/// One point of the concentric axial pressure profile. At a step the profile has two points at
/// the same z: the pressure drops there by the Bernoulli acceleration into the smaller gap.
struct ProfilePoint
{
  double axial_ratio = 0;     // z / L
  double clearance_ratio = 1; // h / C2
  /// (p0 - p) / (p0 - pL): 0 upstream, 1 at the outlet.
  double pressure_drop_fraction = 0;
};

/// The profile at n_points equally spaced z (n_points >= 2), plus the two sides of a step.
std::vector<ProfilePoint> pressure_profile(const DimensionlessSeal &seal, unsigned int n_points);

struct OptimisationBounds
{
  double clearance_ratio_max = 10; // search H in [1, this]
  double step_ratio_min = 1e-3;    // gamma -> 0 is a straight seal
  double step_ratio_max = 1;       // the paper's second optimisation uses 0.8
};

struct Optimum
{
  double clearance_ratio = 1;
  double step_ratio = 1; // 1 for tapered seals (not a parameter there)
  DimensionlessCoefficients coefficients;
  bool clearance_ratio_at_bound = false;
  bool step_ratio_at_bound = false;
};

/// Maximises the objective over H (tapered) or over H and gamma (stepped) for the lambda, xi and s
/// of `seal` (its H and gamma are ignored). Global: a grid scan, then golden-section refinement,
/// because the stepped optimum jumps between the gamma = bound and interior regimes (the cusps
/// of Fleming's Figs. 3 and 6). Throws std::runtime_error for a straight seal.
Optimum optimise(const DimensionlessSeal &seal, Objective objective,
                 const OptimisationBounds &bounds = {});

/// Fanning friction factor of fully rough flow from the relative roughness e_r / d (d the
/// hydraulic diameter 2h): Fleming's fit f = 0.036 (d / e_r)^-0.29 ...
double fully_rough_friction_factor(double relative_roughness);
/// ... and the relation it approximates, 1 / sqrt(f) = 4 log10(d / e_r) + 2.28 (Knudsen & Katz).
double von_karman_friction_factor(double relative_roughness);
/// Exponent of the fit: f proportional to h^-0.29.
constexpr double fully_rough_friction_exponent = 0.29;

/// A dimensional seal (SI units).
struct AnnularSeal
{
  Geometry geometry = Geometry::stepped;
  double diameter = 0.076;          // D, m
  double length = 0.043;            // L, m
  double outlet_clearance = 1.3e-4; // C2, radial, m
  double clearance_ratio = 1.59;    // H = C1 / C2
  double step_ratio = 0.70;         // gamma = L1 / L
  double friction_factor = 0.007;   // Fanning f at the outlet clearance
  double friction_exponent = 0;     // s in f(h) = f (h / C2)^-s
  double entrance_loss = 0;         // xi
  double density = 71;              // rho, kg/m^3
  double viscosity = 1.3e-5;        // mu, Pa s (only for the Reynolds number)
  double pressure_drop = 136e5;     // p0 - pL, Pa; p0 is the upstream stagnation pressure
  double outlet_pressure = 0;       // pL, Pa

  double inlet_clearance() const;
  double lambda() const { return friction_factor * length / outlet_clearance; }
  DimensionlessSeal dimensionless() const;
  /// Throws std::runtime_error naming the first parameter that is out of range.
  void validate() const;
};

struct AnnularResults
{
  double stiffness = 0;               // K, N/m
  double stiffness_dimensionless = 0; // Kbar
  double leakage = 0;                 // M, kg/s
  double leakage_dimensionless = 0;   // Mbar
  double volumetric_leakage = 0;      // M / rho, m^3/s
  double reynolds_number = 0;         // rho V (2h) / mu = 2 m / mu, the same everywhere
};

AnnularResults evaluate(const AnnularSeal &seal);

/// Everything `sealfe annular` reads from subsection "Annular seal".
struct AnnularCase
{
  AnnularSeal seal;
  bool optimise = false;
  Objective objective = Objective::stiffness_per_leakage;
  OptimisationBounds bounds;
  std::vector<double> sweep_lambdas; // empty: no sweep
  unsigned int profile_points = 201;
};

/// Declares subsection "Annular seal" (and its subsection "Lambda sweep").
void declare_parameters(dealii::ParameterHandler &prm);
/// Reads and validates; throws std::runtime_error with one line naming the bad parameter.
AnnularCase parse_case(dealii::ParameterHandler &prm);
/// The sub-command: writes annular_pressure_profile.csv (and, with a sweep,
/// annular_lambda_sweep.csv and, if python3 with matplotlib is found, annular_lambda_sweep.png)
/// into output_directory and returns the summary (keys documented in doc/annular_seals.md).
nlohmann::json run(dealii::ParameterHandler &prm, const std::string &output_directory);

} // namespace sealfe::annular
