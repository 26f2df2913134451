// ThermalConing: the face coning from viscous heating with a thermal lag, Green 2002 Eq. 11–16:
// tau dbeta/dt + beta = beta_ref (h_ref / h) (omega / omega_ref)^2.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace sealfe
{
/// Subsection "Thermal coning". Model "first-order lag" makes the coning a state of the
/// transient (Eq. 11); "none" keeps it at Geometry/Coning. Which film thickness h is (the paper
/// does not say): "dissipation mean" (default) is the h for which mu (omega r)^2 / h integrated
/// over the face equals the viscous heating of the actual film, h_d = Int r^2 dA / Int r^2/h dA
/// (doc/transient.md); "minimum" and "centerline" (C0 + z) are offered for comparison.
struct ThermalConing
{
  enum class Model
  {
    none,
    first_order_lag
  };
  enum class Film
  {
    dissipation_mean,
    minimum,
    centerline
  };
  Model model = Model::first_order_lag;
  Film film = Film::dissipation_mean;
  double time_constant = 2;       ///< tau (s), >= 0; 0: quasi-static
  double reference_coning = 5e-6; ///< beta_ref (rad)
  double reference_film = 0.3e-6; ///< h_ref (m)
  double reference_speed = 500;   ///< omega_ref (rad/s)
  double initial_coning = 0;      ///< beta(0) (rad)

  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);
  /// Throws std::runtime_error on tau < 0, h_ref <= 0, omega_ref <= 0 or non-finite values.
  void validate() const;
  bool enabled() const { return model == Model::first_order_lag; }

  /// The right-hand side of Eq. 11: the coning the film would settle at (rad). h > 0 (m).
  double quasi_static(double film_thickness, double speed) const;
  /// dbeta/dt of Eq. 11 (1/s); tau must be > 0.
  double rate(double coning, double film_thickness, double speed) const;
  std::string film_name() const;
};
} // namespace sealfe
