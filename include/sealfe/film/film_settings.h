// FilmSettings: everything that defines one finite-element film problem (geometry, operating
// conditions, discretisation, cavitation, roughness, contact), parsed once from the prm file and
// changed by name in sweeps.
#pragma once

#include <sealfe/film/annulus_mesh.h>
#include <sealfe/film/asperity_contact.h>
#include <sealfe/film/cavitation.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/flow_factors.h>
#include <sealfe/film/operating_conditions.h>

#include <deal.II/base/parameter_handler.h>

#include <optional>
#include <string>
#include <vector>

namespace sealfe
{
/// The settings aggregate of the film solvers (ReynoldsSolver, CoefficientSolver,
/// FiniteElementFilm). Sub-objects keep their own prm subsections: Geometry and Squeeze motion
/// (geometry), Operating conditions (conditions), Discretization (mesh and the fields below),
/// Cavitation, Roughness (flow_factors), Contact (contact; its sigma is the roughness's).
struct FilmSettings
{
  enum class LinearSolver
  {
    automatic,
    direct,
    cg_amg,
    cg_gmg
  };

  /// Every subsection above.
  static void declare_parameters(dealii::ParameterHandler &prm);
  /// Only the solver part (Discretization, Cavitation, Roughness, Contact), for front ends that
  /// declare Geometry and Operating conditions themselves.
  static void declare_solver_parameters(dealii::ParameterHandler &prm);
  /// Every subsection above (geometry and conditions are not validated here: a model may allow
  /// touch-down).
  void parse_parameters(dealii::ParameterHandler &prm);
  /// Only the solver part; geometry and conditions are left as they are.
  void parse_solver_parameters(dealii::ParameterHandler &prm);

  /// Change one scalar quantity by its prm entry name (SI units): "Clearance", "Coning",
  /// "Rotor speed", "Pressure difference" (po - pi at fixed pi), ... (settable_names()). Throws
  /// std::runtime_error naming the accepted names for an unknown name.
  void set(const std::string &name, double value);
  /// The value of a quantity settable_names() lists.
  double get(const std::string &name) const;
  /// The names set() and get() accept, in prm order.
  static const std::vector<std::string> &settable_names();

  /// Whether two settings give the same mesh and degrees of freedom (radii, mesh parameters,
  /// degree, and C0 and coning when the radial grading uses them).
  bool same_discretization(const FilmSettings &other, unsigned int coarsening,
                           unsigned int other_coarsening) const;

  FilmThickness geometry;
  OperatingConditions conditions;

  AnnulusMesh mesh;
  unsigned int polynomial_degree = 2;
  /// The prm's Mapping degree: a number (fixed_mapping_degree), or the element degree plus
  /// mapping_degree_above_element ("k+1": 1, "k": 0).
  std::optional<unsigned int> fixed_mapping_degree;
  unsigned int mapping_degree_above_element = 1;
  /// Degree of the mapping of the cells onto the polar geometry.
  unsigned int mapping_degree() const
  {
    return fixed_mapping_degree.value_or(polynomial_degree + mapping_degree_above_element);
  }
  LinearSolver linear_solver = LinearSolver::automatic;
  double solver_tolerance = 1e-12;
  /// Estimate the discretisation error of the loads by a second solve on a 2x coarser mesh.
  bool estimate_error = true;

  CavitationSettings cavitation;
  FlowFactors flow_factors;
  AsperityContact contact;
};

/// Error estimate of a load (or coefficient) L of a degree-k solve from the same quantity on a
/// mesh twice as coarse, assuming it converges like h^k (the H1 rate of the pressure):
/// |L_h - L_2h| / (2^k - 1). Why k and not k + 1: estimate_load_errors (reynolds_solver.h).
double richardson_error(double fine, double coarse, unsigned int degree);

} // namespace sealfe
