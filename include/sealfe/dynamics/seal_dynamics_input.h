// SealDynamicsInput: everything a dynamics run (sealfe stability, sealfe response) reads from the
// parameter file — configuration, rings, geometry, operating point and the film level — and the
// seal dynamics built from it.
#pragma once

#include <sealfe/coefficients/coefficient_solver.h>
#include <sealfe/coefficients/coefficient_table.h>
#include <sealfe/dynamics/angular_dynamics.h>
#include <sealfe/dynamics/film_levels.h>
#include <sealfe/dynamics/ring_properties.h>
#include <sealfe/dynamics/shared_cache.h>
#include <sealfe/dynamics/speed_interpolated_film.h>
#include <sealfe/film/film_force_model.h>
#include <sealfe/film/film_settings.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/operating_conditions.h>

#include <deal.II/base/parameter_handler.h>

#include <memory>
#include <string>

namespace sealfe
{
/// Everything a dynamics run reads from a parameter file: subsection "Seal dynamics" (declared
/// here) plus "Geometry" and "Operating conditions" (declared by the application). Kept as plain
/// data so that a parameter study can change one entry and build() again.
struct SealDynamicsInput
{
  SealConfiguration configuration = SealConfiguration::fms_flexible_rotor;
  RingProperties rotor, stator;
  FilmThickness geometry;
  OperatingConditions operating;
  FilmLevel film_level = FilmLevel::closed_form; ///< prm "Film model" (film_level_from_string)
  /// Level 1: the CSV written by `sealfe table` (path as given, relative to the working
  /// directory) and its interpolation ("cubic" | "linear").
  std::string table_file;
  std::string table_interpolation = "cubic";
  /// Level 2: number of swept speeds at which the FE coefficients are computed for a sweep
  /// (SpeedInterpolatedFilm); 0 = an FE computation at every speed the sweep asks for.
  unsigned int film_speed_nodes = 9;
  /// Level 2: the finite-element solver (subsections Discretization, Cavitation, Roughness,
  /// Contact; its geometry and operating conditions are this input's) and the coefficient method
  /// (subsection Coefficients). Its solves run on MPI_COMM_SELF.
  FilmSettings film_solver;
  CoefficientSettings coefficient_method;

  /// Declares subsection "Seal dynamics" with its subsections "Rotor ring" and "Stator ring".
  /// Defaults: the FMS seal on a flexible rotor of Varney & Green (Varney & Green (2017) Tables
  /// 1-2).
  static void declare_parameters(dealii::ParameterHandler &prm);
  /// Reads "Seal dynamics", "Geometry" and "Operating conditions", and for Film model = finite
  /// element the solver's subsections (declared by CoefficientSolver::declare_parameters; a
  /// one-line error says so when they are missing).
  void parse_parameters(dealii::ParameterHandler &prm);
  /// One-line std::runtime_error naming the parameter for impossible input, for configurations
  /// whose speeds do not fit (FMS with flexible rotor: the stator does not spin), for a table
  /// that cannot be read or is not this seal's. Makes no FE solve.
  void validate() const;
  /// The FilmForceModel of the chosen level for this seal (film_levels.h): NarrowSealFilm,
  /// TableFilm (the table read once and shared by copies of this input) or the finite-element
  /// film.
  std::shared_ptr<const FilmForceModel> film_force_model() const;
  /// Its coefficients at any pair of ring speeds about this seal's equilibrium, one computation
  /// per speed pair (kept for repeated pairs).
  FilmModel film() const;
  /// The film for a sweep of one ring's speed over [from, to] (the other at fixed_speed): film()
  /// for levels 0 and 1 (level 1: both ends of the sweep are checked to lie in the table, with a
  /// one-line error otherwise); level 2 with film_speed_nodes >= 2 a SpeedInterpolatedFilm over
  /// film(), else film() itself.
  SweepFilm sweep_film(AngularSealDynamics::SweptRing swept, double fixed_speed, double from,
                       double to) const;
  AngularSealDynamics build() const;
  AngularSealDynamics build(FilmModel film_model) const;
  /// Relative tilt at which the faces touch: min(C0/ri, (C0 + beta (ro - ri))/ro), i.e. C0/ri
  /// for a seal coned open outward (Varney & Green (2017): gamma*_cr = C0/ri).
  double contact_tilt() const;
  /// Set a named scalar (a "Second parameter" of the stability sweep); see the list in
  /// parameter_names(). "Clearance" keeps beta* ro/C0 if hold_normalized_coning.
  void set(const std::string &name, double value, bool hold_normalized_coning);
  /// The value of a named scalar of parameter_names() (the operating point of a stability map).
  double get(const std::string &name) const;
  static std::string parameter_names();

private:
  /// The level-1 table, read once (by film() or validate()) and shared by copies.
  std::shared_ptr<const CoefficientTable> table() const;
  SharedCache<std::string, std::shared_ptr<const CoefficientTable>> tables;
};

/// The speed sweep of a dynamics study, in the current subsection: "Speed from", "Speed to"
/// (rad/s) and "Speed points" (at least 2), with these defaults and the documentation of the
/// points. The swept ring is chosen by the study's "Swept speed".
void declare_speed_sweep(dealii::ParameterHandler &prm, const std::string &from,
                         const std::string &to, const std::string &points,
                         const std::string &points_documentation);

} // namespace sealfe
