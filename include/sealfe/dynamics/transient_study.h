// `sealfe equilibrium` and `sealfe transient`: the operating point and the start-up / run /
// shut-down transient of a flexibly mounted stator seal (Green 2002).
#pragma once

#include <deal.II/base/parameter_handler.h>

#include <nlohmann/json.hpp>

#include <string>

namespace sealfe
{
namespace equilibrium
{
/// Declares the seal case (Closing force, Stator ring, Rotor runout, Thermal coning, Ramps,
/// Face contact, Contact, Roughness, Cavitation, Narrow seal) and "Transient" (film level).
void declare_parameters(dealii::ParameterHandler &prm);
/// The axial equilibrium at the Operating conditions; summary keys: clearance, axial_offset,
/// min_film, coning, opening_force, contact_force, closing_force, leakage_inner,
/// friction_torque, stiffness, damping (film, by central differences), contact_stiffness.
nlohmann::json run(dealii::ParameterHandler &prm, const std::string &output_directory);
} // namespace equilibrium

namespace transient
{
void declare_parameters(dealii::ParameterHandler &prm);
/// Integrates the transient, writes transient.csv (atomically) and transient.png, returns the
/// summary (complete, lift-off/touch-down, max contact force, leaked volume, final state, film
/// evaluations). A run stopped early writes what it computed with complete = false, then throws.
nlohmann::json run(dealii::ParameterHandler &prm, const std::string &output_directory);
} // namespace transient
} // namespace sealfe
