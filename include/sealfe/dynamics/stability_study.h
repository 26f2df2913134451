// `sealfe stability`: linear stability of the angular modes of an FMS/FMR/FMRR seal (or an FMS on
// a flexible rotor): eigenvalues, Routh-Hurwitz verdict and the stable range of one ring's speed.
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <nlohmann/json.hpp>

#include <string>

namespace sealfe
{
namespace stability
{
/// Declares subsections "Seal dynamics" (rings, configuration, film model) and "Stability" (the
/// speed sweep — Speed from, Speed to, Speed points as in `sealfe response`; the former names
/// Sweep from, Sweep to, Grid points are aliases — and an optional second parameter). "Geometry"
/// and "Operating conditions" are declared by the application, and so are the finite-element
/// solver's subsections (needed for Film model = finite element).
void declare_parameters(dealii::ParameterHandler &prm);

/// Reads the parsed parameters, computes, writes stability_growth_rate.csv (swept speed against
/// the largest real part of the eigenvalues) and, with a second parameter, stability_sweep.csv
/// (its values against the stable range), and returns the summary (keys in doc/dynamics.md):
///   configuration, film_model, film_model_level, film_coefficients, film_speed_dependence
///   (how the coefficients follow the swept speed; level 2: nodes and an interpolation check),
///   rotor_speed, stator_speed,
///   eigenvalues [[re, im], ...] (1/s), whirl_frequencies (rad/s), damping_ratios, growth_rate,
///   stable, stable_routh_hurwitz, swept_speed, sweep [from, to], stable_range [low, high]
///   (rad/s, null if no stable speed), stable_range_at_search_limit [bool, bool],
///   stable_intervals, undamped_thresholds (Wileman & Green Eq. 17), files.
/// Throws std::runtime_error with one line naming the parameter on bad input.
///
/// Film model = finite element needs the solver's subsections declared as well
/// (CoefficientSolver::declare_parameters); the FE solves run on MPI_COMM_SELF.
nlohmann::json run(dealii::ParameterHandler &prm, const std::string &output_directory);
} // namespace stability
} // namespace sealfe
