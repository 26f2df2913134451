// `sealfe response`: steady-state forced response of the seal's angular modes to the rings'
// static and dynamic misalignments over a speed range (tilts, relative tilt, contact margin).
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <nlohmann/json.hpp>

#include <string>

namespace sealfe
{
namespace response
{
/// Declares subsections "Seal dynamics" (rings, misalignments, configuration, film model) and
/// "Forced response" (speed range, plot). "Geometry" and "Operating conditions" are declared by
/// the application, and so are the finite-element solver's subsections (needed for Film model =
/// finite element).
void declare_parameters(dealii::ParameterHandler &prm);

/// Sweeps the chosen ring's speed, writes response.csv (speed against each ring's tilt, the
/// relative tilt gamma*, its phase and the contact margin C0/ri - gamma*) and, if python3 with
/// matplotlib is found, response.png (scripts/plot_response.py; a missing python never fails the
/// run). Returns the summary (keys in doc/dynamics.md): configuration, film_model,
/// film_model_level, film_coefficients, film_speed_dependence, swept_speed, speed_range,
/// contact_tilt, peak_relative_tilt, speed_at_peak_relative_tilt, min_contact_margin, contact,
/// contact_speed_ranges, unstable_speed_ranges, rotor_critical_speed, files, plot.
///
/// Film model = finite element needs the solver's subsections declared as well
/// (CoefficientSolver::declare_parameters); the FE solves run on MPI_COMM_SELF.
nlohmann::json run(dealii::ParameterHandler &prm, const std::string &output_directory);
} // namespace response
} // namespace sealfe
