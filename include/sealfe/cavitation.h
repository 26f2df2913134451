// CavitationSettings: which cavitation model a film solve uses and at what pressure the film
// ruptures (prm subsection "Cavitation").
#pragma once

#include <deal.II/base/parameter_handler.h>

namespace sealfe
{
/// How sub-cavity-pressure regions are treated. `none`: full film, p may fall below p_cav.
/// `half_sommerfeld`: the full-film pressure is clipped, p < p_cav -> p_cav, in the loads (what
/// Etsion's and Varney & Green's closed forms use; not mass conserving).
enum class Cavitation
{
  none,
  half_sommerfeld
};

struct CavitationSettings
{
  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);

  Cavitation model = Cavitation::none;
  double pressure = 0; // Pa, p_cav: absolute or gauge like the boundary pressures
};

} // namespace sealfe
