#include <sealfe/film/film_settings.h>

#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

namespace sealfe
{
using namespace dealii;

void FilmSettings::declare_parameters(ParameterHandler &prm)
{
  FilmThickness::declare_parameters(prm);
  OperatingConditions::declare_parameters(prm);
  declare_solver_parameters(prm);
}

void FilmSettings::declare_solver_parameters(ParameterHandler &prm)
{
  AnnulusMesh::declare_parameters(prm);
  CavitationSettings::declare_parameters(prm);
  FlowFactors::declare_parameters(prm);
  AsperityContact::declare_parameters(prm);
  prm.enter_subsection("Discretization");
  prm.declare_entry("Polynomial degree", "2", Patterns::Integer(1, 6),
                    "Degree k of the continuous Lagrange elements.");
  prm.declare_entry(
      "Mapping degree", "k+1", Patterns::Selection("k+1|k|1|2|3|4|5|6|7|8"),
      "Degree of the curved mapping that draws the cells on the circles: k+1 (one above the "
      "element degree k), k, or a number not below k. The mapping's share of the error of the "
      "loads falls like dtheta^(2m) around the annulus: with m = k it is of the elements' own "
      "order and on a smooth film the larger part; with m = k + 1 it is negligible from about "
      "16 cells around, and far fewer cells around reach the same accuracy (doc/reynolds.md).");
  prm.declare_entry("Linear solver", "auto", Patterns::Selection("auto|direct|cg-amg|cg-gmg"),
                    "auto: sparse direct (KLU or MUMPS) below 150000 unknowns; above, CG with "
                    "geometric multigrid on the levels of the built-in mesh (cg-gmg), or with "
                    "algebraic multigrid (cg-amg) on a mesh file; on several MPI ranks cg-gmg at "
                    "every size on the built-in mesh; direct, cg-amg or cg-gmg force one "
                    "(cavitation Newton systems: direct unless cg-amg).");
  prm.declare_entry("Solver tolerance", "1e-12", Patterns::Double(0),
                    "Relative residual tolerance of the iterative solver (the equation is scaled "
                    "by 12 mu / C0^3, so this is relative to the pressure load).");
  prm.declare_entry("Error estimate", "true", Patterns::Bool(),
                    "Estimate the discretisation error of every load by a second solve on a mesh "
                    "twice as coarse (cost about 1/4 of the main solve).");
  prm.leave_subsection();
}

void FilmSettings::parse_parameters(ParameterHandler &prm)
{
  geometry.parse_parameters(prm);
  conditions.parse_parameters(prm);
  parse_solver_parameters(prm);
}

void FilmSettings::parse_solver_parameters(ParameterHandler &prm)
{
  mesh.parse_parameters(prm);
  cavitation.parse_parameters(prm);
  flow_factors.parse_parameters(prm);
  // One roughness for both models: the contact model gets the flow factors' sigma.
  contact.parse_parameters(prm, flow_factors.composite_roughness());
  prm.enter_subsection("Discretization");
  polynomial_degree = prm.get_integer("Polynomial degree");
  const std::string m = prm.get("Mapping degree");
  mapping_degree_above_element = m == "k+1" ? 1 : 0;
  fixed_mapping_degree.reset();
  if (m != "k+1" && m != "k")
    fixed_mapping_degree = std::stoi(m);
  const std::string s = prm.get("Linear solver");
  linear_solver = (s == "direct")   ? LinearSolver::direct
                  : (s == "cg-amg") ? LinearSolver::cg_amg
                  : (s == "cg-gmg") ? LinearSolver::cg_gmg
                                    : LinearSolver::automatic;
  solver_tolerance = prm.get_double("Solver tolerance");
  estimate_error = prm.get_bool("Error estimate");
  prm.leave_subsection();
}

namespace
{
/// Accessor of one settable quantity: reads and writes it in a FilmSettings.
struct Quantity
{
  std::function<double(const FilmSettings &)> get;
  std::function<void(FilmSettings &, double)> set;
};

template <typename Member>
Quantity geometry_field(Member member)
{
  return {[member](const FilmSettings &s) { return s.geometry.*member; },
          [member](FilmSettings &s, const double v) { s.geometry.*member = v; }};
}
template <typename Member>
Quantity conditions_field(Member member)
{
  return {[member](const FilmSettings &s) { return s.conditions.*member; },
          [member](FilmSettings &s, const double v) { s.conditions.*member = v; }};
}

const std::vector<std::pair<std::string, Quantity>> &quantities()
{
  static const std::vector<std::pair<std::string, Quantity>> q = {
      {"Inner radius", geometry_field(&FilmThickness::inner_radius)},
      {"Outer radius", geometry_field(&FilmThickness::outer_radius)},
      {"Clearance", geometry_field(&FilmThickness::clearance)},
      {"Coning", geometry_field(&FilmThickness::coning)},
      {"Tilt", geometry_field(&FilmThickness::tilt)},
      {"Tilt angle", geometry_field(&FilmThickness::tilt_angle)},
      {"Wave amplitude", geometry_field(&FilmThickness::wave_amplitude)},
      {"Wave number", geometry_field(&FilmThickness::wave_number)},
      {"Wave phase", geometry_field(&FilmThickness::wave_phase)},
      {"Axial offset", geometry_field(&FilmThickness::axial_offset)},
      {"Axial velocity", geometry_field(&FilmThickness::axial_velocity)},
      {"Tilt rate x", geometry_field(&FilmThickness::tilt_rate_x)},
      {"Tilt rate y", geometry_field(&FilmThickness::tilt_rate_y)},
      {"Inner pressure", conditions_field(&OperatingConditions::inner_pressure)},
      {"Outer pressure", conditions_field(&OperatingConditions::outer_pressure)},
      {"Pressure difference",
       {[](const FilmSettings &s)
        { return s.conditions.outer_pressure - s.conditions.inner_pressure; },
        [](FilmSettings &s, const double v)
        { s.conditions.outer_pressure = s.conditions.inner_pressure + v; }}},
      {"Viscosity", conditions_field(&OperatingConditions::viscosity)},
      {"Rotor speed", conditions_field(&OperatingConditions::rotor_speed)},
      {"Stator speed", conditions_field(&OperatingConditions::stator_speed)},
      {"Reference pressure", conditions_field(&OperatingConditions::reference_pressure)},
      {"Cavitation pressure",
       {[](const FilmSettings &s) { return s.cavitation.pressure; },
        [](FilmSettings &s, const double v) { s.cavitation.pressure = v; }}}};
  return q;
}

const Quantity &quantity(const std::string &name)
{
  for (const auto &[n, q] : quantities())
    if (n == name)
      return q;
  std::string names;
  for (const auto &n : FilmSettings::settable_names())
    names += (names.empty() ? "" : ", ") + n;
  throw std::runtime_error("Film settings: unknown quantity '" + name + "' (one of " + names + ")");
}
} // namespace

void FilmSettings::set(const std::string &name, const double value)
{
  quantity(name).set(*this, value);
}

double FilmSettings::get(const std::string &name) const
{
  return quantity(name).get(*this);
}

const std::vector<std::string> &FilmSettings::settable_names()
{
  static const std::vector<std::string> names = []
  {
    std::vector<std::string> n;
    for (const auto &[name, q] : quantities())
      n.push_back(name);
    return n;
  }();
  return names;
}

bool FilmSettings::same_discretization(const FilmSettings &other, const unsigned int coarsening,
                                       const unsigned int other_coarsening) const
{
  const AnnulusMesh &a = mesh, &b = other.mesh;
  const bool same_mesh =
      a.radial_cells == b.radial_cells && a.circumferential_cells == b.circumferential_cells &&
      a.global_refinements == b.global_refinements && a.mesh_file == b.mesh_file &&
      a.mesh_size == b.mesh_size && a.radial_grading == b.radial_grading &&
      a.grading_exponent == b.grading_exponent && a.align_with_features == b.align_with_features;
  // The built-in mesh puts cell edges on the steps of surface features.
  const bool same_features = geometry.features == other.geometry.features;
  // The built-in mesh is graded by the axisymmetric film C0 + beta (r - ri) only (not by z or
  // the tilts), so that perturbed and transient solves keep their mesh.
  const bool graded = a.mesh_file.empty() && a.radial_grading;
  const bool same_grading = !graded || (geometry.clearance == other.geometry.clearance &&
                                        geometry.coning == other.geometry.coning);
  return same_mesh && same_grading && same_features && coarsening == other_coarsening &&
         polynomial_degree == other.polynomial_degree &&
         mapping_degree() == other.mapping_degree() &&
         geometry.inner_radius == other.geometry.inner_radius &&
         geometry.outer_radius == other.geometry.outer_radius;
}

double richardson_error(const double fine, const double coarse, const unsigned int degree)
{
  return std::abs(fine - coarse) * (1.0 / (std::pow(2.0, degree) - 1));
}

} // namespace sealfe
