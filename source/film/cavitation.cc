#include <sealfe/film/cavitation.h>

namespace sealfe
{
void CavitationSettings::declare_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Cavitation");
  prm.declare_entry(
      "Model", "none", dealii::Patterns::Selection("none|half-sommerfeld|reynolds|jfo"),
      "none: full film (p may fall below the cavitation pressure). half-sommerfeld: full-film "
      "solve, then p < p_cav is set to p_cav in the loads (the closed forms' assumption; not "
      "mass conserving). reynolds: Swift-Stieber, p >= p_cav (obstacle problem; not mass "
      "conserving). jfo: mass-conserving JFO/Elrod-Adams with a liquid fraction; the model for "
      "real runs with tilt or waviness.");
  prm.declare_entry("Cavitation pressure", "0", dealii::Patterns::Double(),
                    "p_cav (Pa), absolute or gauge like the boundary pressures.");
  prm.declare_entry("Maximum iterations", "100", dealii::Patterns::Integer(1),
                    "Limit of the semismooth Newton iterations (reynolds, jfo); a solve that "
                    "does not converge within it stops with an error.");
  prm.declare_entry("Tolerance", "1e-10", dealii::Patterns::Double(0),
                    "Convergence tolerance (reynolds, jfo): the nodal mass residual relative to "
                    "the Couette/pressure flow scale, with an unchanged cavitated set.");
  prm.leave_subsection();
}

void CavitationSettings::parse_parameters(dealii::ParameterHandler &prm)
{
  prm.enter_subsection("Cavitation");
  const std::string m = prm.get("Model");
  model = m == "half-sommerfeld" ? Cavitation::half_sommerfeld
          : m == "reynolds"      ? Cavitation::reynolds
          : m == "jfo"           ? Cavitation::jfo
                                 : Cavitation::none;
  pressure = prm.get_double("Cavitation pressure");
  maximum_iterations = prm.get_integer("Maximum iterations");
  tolerance = prm.get_double("Tolerance");
  prm.leave_subsection();
}
} // namespace sealfe
