#include <sealfe/dynamics/thermal_coning.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
void ThermalConing::declare_parameters(dealii::ParameterHandler &prm)
{
  using namespace dealii::Patterns;
  prm.enter_subsection("Thermal coning");
  prm.declare_entry("Model", "first-order lag", Selection("first-order lag|none"),
                    "first-order lag: the coning obeys Green 2002 Eq. 11 (a state of the "
                    "transient, its quasi-static value in `sealfe equilibrium`); none: the "
                    "coning is Geometry/Coning.");
  prm.declare_entry("Time constant", "2", Double(), "tau (s), >= 0; 0 is quasi-static.");
  prm.declare_entry("Reference coning", "5e-6", Double(), "beta_ref (rad).");
  prm.declare_entry("Reference film", "0.3e-6", Double(), "h_ref (m).");
  prm.declare_entry("Reference speed", "500", Double(), "omega_ref (rad/s).");
  prm.declare_entry("Initial coning", "0", Double(), "beta(0) (rad) of the transient.");
  prm.declare_entry("Film thickness", "dissipation mean",
                    Selection("dissipation mean|minimum|centerline"),
                    "The h of Eq. 11: dissipation mean = Int r^2 dA / Int r^2/h dA (the film "
                    "whose uniform value gives the same viscous heating), minimum = min h, "
                    "centerline = C0 + Z.");
  prm.leave_subsection();
}

void ThermalConing::parse_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Thermal coning");
  model = prm.get("Model") == "none" ? Model::none : Model::first_order_lag;
  time_constant = prm.get_double("Time constant");
  reference_coning = prm.get_double("Reference coning");
  reference_film = prm.get_double("Reference film");
  reference_speed = prm.get_double("Reference speed");
  initial_coning = prm.get_double("Initial coning");
  const std::string f = prm.get("Film thickness");
  film = f == "minimum" ? Film::minimum
                        : (f == "centerline" ? Film::centerline : Film::dissipation_mean);
  prm.leave_subsection();
}

void ThermalConing::validate() const
{
  std::ostringstream s;
  if (!(time_constant >= 0) || std::isnan(time_constant))
    s << "Thermal coning: Time constant must be >= 0, got " << time_constant << " s";
  else if (!(reference_film > 0) || !(reference_speed > 0))
    s << "Thermal coning: Reference film and Reference speed must be > 0";
  else if (!std::isfinite(reference_coning) || !std::isfinite(initial_coning))
    s << "Thermal coning: Reference coning and Initial coning must be finite";
  if (!s.str().empty())
    throw std::runtime_error(s.str());
}

double ThermalConing::quasi_static(const double h, const double omega) const
{
  const double w = omega / reference_speed;
  return reference_coning * (reference_film / h) * w * w;
}

double ThermalConing::rate(const double beta, const double h, const double omega) const
{
  return (quasi_static(h, omega) - beta) / time_constant;
}

std::string ThermalConing::film_name() const
{
  return film == Film::minimum ? "minimum"
                               : (film == Film::centerline ? "centerline" : "dissipation mean");
}
} // namespace sealfe
