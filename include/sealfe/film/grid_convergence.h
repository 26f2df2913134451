// Discretisation error of one quantity from its values on three meshes (h, 2h, 4h): the observed
// order of convergence and Roache's grid convergence index, widened and flagged when the meshes
// are not in the asymptotic range (doc/guarantees.md, "Error estimate").
#pragma once

#include <nlohmann/json.hpp>

#include <limits>
#include <optional>
#include <string>

namespace sealfe
{
/// The verdict on one quantity q computed on meshes of size h, 2h (and 4h).
struct GridConvergence
{
  double estimate = 0;          ///< bound of |q_h - q_exact| (the reported error estimate)
  double two_mesh_estimate = 0; ///< |q_h - q_2h| / (2^k - 1), the floor (the earlier estimate)
  double observed_order =
      std::numeric_limits<double>::quiet_NaN(); ///< log2(|q_4h - q_2h| / |q_2h - q_h|); NaN without
                                                ///< a third mesh
  double expected_order = 0;                    ///< the order theory predicts for this quantity
  double order_used = 0;                        ///< the order in the GCI formula
  double safety_factor = 0;                     ///< Fs of the GCI (1.25 asymptotic, 3 otherwise)
  bool asymptotic = false; ///< the observed order is within 10 % of the expected one
  std::string convergence; ///< "asymptotic", "non-asymptotic", "non-monotone", "two-mesh",
                           ///< "round-off"
  std::string reason;      ///< why this estimate, in words

  /// {"estimate", "asymptotic", "observed_order" (null without), "expected_order",
  ///  "order_used", "convergence", "two_mesh_estimate", "safety_factor", "reason"}
  nlohmann::json to_json() const;
};

/// Grid convergence index (Roache 1994, with the rule of Oberkampf & Roy 2010, Sec. 8.7, for the
/// order) of q_h = `fine` from q_2h = `coarse` and q_4h = `coarsest` (refinement ratio 2):
/// - differences e21 = q_h - q_2h and e32 = q_2h - q_4h both below `noise`: "round-off" (the
///   quantity is resolved to solver tolerance; the two-mesh estimate stands);
/// - same sign: observed order p = log2(|e32| / |e21|); within 10 % of `expected_order`:
///   "asymptotic", Fs = 1.25 with the expected order; otherwise "non-asymptotic", Fs = 3 with
///   the order clamped to [0.5, expected]. Estimate Fs |e21| / (2^p - 1);
/// - opposite signs (or one difference at noise level and not the other): "non-monotone",
///   3 max(|e21|, |e32|) / (2^0.5 - 1);
/// - no third mesh (`coarsest` empty): "two-mesh", Fs = 3 with the expected order, and
///   `why_two_mesh` as the reason.
/// The estimate is never below `two_mesh_estimate` (the earlier two-mesh figure).
GridConvergence grid_convergence(double fine, double coarse, std::optional<double> coarsest,
                                 double expected_order, double two_mesh_estimate, double noise,
                                 const std::string &why_two_mesh = "");

/// The order at which a load (linear functional of the pressure: force, moments, leakage,
/// friction torque; and the stiffness and damping coefficients) of a degree-k solve converges:
/// 2k for a smooth (full) film, 1 when a cavity is present (the pressure has a kink or a jump of
/// gradient at the cavity edge, which the mesh does not follow).
double expected_load_order(unsigned int degree, bool cavitating);

/// Relative size of differences treated as round-off (of the quantity's scale).
constexpr double grid_convergence_noise = 1e-9;

/// Whether a verdict deserves a warning on stderr: not asymptotic, not merely faster than
/// expected (then Fs = 3 at the expected order is conservative), widened above the earlier
/// two-mesh figure (or without a third mesh), and its estimate above 1e-3 of the quantity's scale
/// (a result known to 0.1 % needs no warning). The flags stay in summary.json either way. Quiet:
/// the default seal's friction torque (non-monotone, the 4h mesh of 2 x 32 cells pre-asymptotic;
/// estimate 3.5e-5 relative, true error 7e-8), the moments of the ε = 0.5 tilted seal and the
/// cross-coupled K and D of prm/coefficients.prm (observed 3.4-3.5 where 4 is expected: the
/// order-k floor is larger than the widened figure).
bool deserves_warning(const GridConvergence &verdict, double scale);

} // namespace sealfe
