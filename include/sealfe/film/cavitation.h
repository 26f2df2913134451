// CavitationSettings: which cavitation model a film solve uses, at what pressure the film
// ruptures, and how the nonlinear cavitation problem is iterated (prm subsection "Cavitation").
#pragma once

#include <deal.II/base/parameter_handler.h>

namespace sealfe
{
/// How sub-cavity-pressure regions are treated.
///  none:             full film, p may fall below p_cav.
///  half_sommerfeld:  full-film solve, then p < p_cav -> p_cav in the loads (what Etsion's and
///                    Varney & Green's closed forms use; not mass conserving).
///  reynolds:         Swift-Stieber: p >= p_cav, the Reynolds equation where p > p_cav (an
///                    obstacle problem; the rupture boundary is right, the reformation is not and
///                    mass is not conserved).
///  jfo:              Jakobsson-Floberg-Olsson / Elrod-Adams: pressure p and liquid fraction s,
///                    p > p_cav => s = 1, s < 1 => p = p_cav, mass conserved through rupture and
///                    reformation.
enum class Cavitation
{
  none,
  half_sommerfeld,
  reynolds,
  jfo
};

struct CavitationSettings
{
  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);

  /// True for the models that change the pressure solution itself (reynolds, jfo).
  bool is_nonlinear() const { return model == Cavitation::reynolds || model == Cavitation::jfo; }

  Cavitation model = Cavitation::none;
  double pressure = 0;                   // Pa, p_cav: absolute or gauge like the boundary pressures
  unsigned int maximum_iterations = 100; // semismooth Newton iterations
  double tolerance = 1e-10;              // relative residual of the discrete mass balance
};

} // namespace sealfe
