// CoefficientSolver: the film stiffness K and damping D of the finite-element Reynolds solve (level
// 2 of doc/reynolds.md), by linearising the discrete Reynolds system or by central differences.
#pragma once

#include <sealfe/film/film_coefficients.h>
#include <sealfe/film/film_loads.h>
#include <sealfe/film/film_settings.h>
#include <sealfe/film/film_thickness.h>
#include <sealfe/film/grid_convergence.h>
#include <sealfe/film/operating_conditions.h>
#include <sealfe/film/reynolds_solver.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <nlohmann/json.hpp>

#include <array>
#include <functional>
#include <string>
#include <utility>

namespace sealfe
{
/// How the coefficients are computed: prm subsection "Coefficients".
struct CoefficientSettings
{
  enum class Method
  {
    /// The Reynolds system linearised about the solved pressure: one extra linear solve per
    /// degree of freedom and per rate with the factorisation of the operating-point solve, or,
    /// where CG solves it, three adjoint solves (one per load) with its preconditioner
    /// (ReynoldsSolver::linearized_generalized_forces).
    perturbation,
    /// Central differences of the nonlinear solve: two full solves per column of K and of D.
    finite_difference
  };

  static void declare_parameters(dealii::ParameterHandler &prm);
  /// Throws std::runtime_error naming the parameter if a step is not positive and finite.
  void parse_parameters(dealii::ParameterHandler &prm);

  /// Finite-difference steps for one operating point. Displacements are scaled by the film:
  /// axial C0, tilt C0/ro (the tilt at which the faces would touch is about C0/ri). Rates are
  /// scaled by the displacement step times omega_ref = max(|omega1|, |omega2|, 1 rad/s), so that
  /// the squeeze term dh/dt is of the size of the Couette term omega dh/dtheta of the displacement
  /// step. (In full film the loads are linear in the rates and any rate step is exact.)
  struct Steps
  {
    double axial;      // m
    double tilt;       // rad
    double axial_rate; // m/s
    double tilt_rate;  // rad/s
  };
  Steps steps(const FilmThickness &film, const OperatingConditions &conditions) const;

  Method method = Method::perturbation;
  double relative_step = 1e-4; // of C0 and C0/ro
  double axial_step = 0;       // m; > 0 overrides relative_step * C0
  double tilt_step = 0;        // rad; > 0 overrides relative_step * C0/ro
};

std::string to_string(CoefficientSettings::Method method);

/// Everything `sealfe coefficients` reports about one operating point.
struct CoefficientResult
{
  FilmCoefficients coefficients; // level 2
  FilmLoads loads;               // of the operating point itself

  /// Discretisation error estimate of every entry of K and D and of the loads: the grid
  /// convergence index of the same computation on meshes 2x and 4x as coarse (grid_convergence.h,
  /// the same rule as the loads of `sealfe solve`), never below the earlier two-mesh figure
  /// |X_h - X_2h| / (2^k - 1) (richardson_error).
  bool has_error_estimate = false;
  std::string no_error_estimate_reason; ///< why there is none (has_error_estimate false)
  FilmCoefficients::Matrix3 stiffness_error{}, damping_error{};
  std::array<std::array<GridConvergence, 3>, 3> stiffness_convergence{}, damping_convergence{};
  bool coefficients_asymptotic = false; ///< every entry of K and D in the asymptotic range
  bool coefficients_warning = false;    ///< an entry deserves_warning (grid_convergence.h)
  FilmLoads load_error;
  nlohmann::json load_estimate; ///< grid_convergence_of_loads (film_summary.h)
  dealii::types::global_dof_index coarse_dofs = 0;
  dealii::types::global_dof_index coarsest_dofs = 0; ///< 0: no 4x coarser mesh

  CoefficientSettings::Method method = CoefficientSettings::Method::perturbation;
  CoefficientSettings::Steps steps{}; // finite difference only
  std::string linearization;          // what the method does at the cavitation boundary
  dealii::types::global_dof_index dofs = 0;
  unsigned int degree = 0;
  unsigned int mapping_degree = 0; // of the curved mapping (Mapping degree)
  double solve_time = 0;           // s, the operating-point solve (setup, assembly, factorisation)
  double coefficient_time = 0;     // s, the linearised (or adjoint, or 12 perturbed) solves
  double error_estimate_time = 0;  // s, everything on the coarse mesh

  /// The linear solver on the fine mesh: its method and direct package, and its work for the
  /// operating-point solve (summary.json `linear_solver`, as `sealfe solve` reports it) and for
  /// the coefficient set (`coefficient_linear_solver`: the 6 linearised solves with the
  /// operating point's factorisation, the 3 adjoint solves with its CG preconditioner, or the
  /// linear solves of the 12 perturbed solves of the finite-difference method).
  std::string linear_method, direct_package;
  FilmLinearSolver::Statistics operating_point_linear, coefficient_linear;

  /// summary.json content: loads (force_z, ...), FilmCoefficients::to_json() ("stiffness",
  /// "damping", row-major SI), "error_estimate" {"stiffness", "damping", loads...}, timings.
  nlohmann::json to_json() const;
};

/// Film coefficients from the finite-element Reynolds solver. The discretisation (mesh, degree,
/// cavitation model) is that of the owned ReynoldsSolver, so whatever cavitation or roughness
/// model the solver has is linearised by the same code path.
///
///   CoefficientSolver s(comm);
///   s.parse_parameters(prm);           // Discretization, Cavitation, Coefficients
///   CoefficientResult r = s.compute(film, conditions);
///   FilmCoefficients k = r.coefficients;  // K = -dF/dq, D = -dF/dq_dot, q = (z, tilt_x, tilt_y)
class CoefficientSolver
{
public:
  explicit CoefficientSolver(MPI_Comm comm);
  /// The whole film problem and the coefficient method.
  CoefficientSolver(const FilmSettings &film_settings,
                    const CoefficientSettings &coefficient_settings, MPI_Comm comm);

  /// ReynoldsSolver's subsections and "Coefficients".
  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);

  /// The solver whose discretisation is used (mesh(), polynomial_degree, cavitation, ...). After
  /// compute() it holds the solution of the operating point on the fine mesh (for output).
  ReynoldsSolver &reynolds() { return solver; }
  const ReynoldsSolver &reynolds() const { return solver; }

  /// K, D and the loads about the operating point, with the error estimate if the solver's
  /// "Error estimate" is on and the mesh can be coarsened. Throws std::runtime_error (from the
  /// solver) on bad geometry or a failed solve.
  CoefficientResult compute(const FilmThickness &film, const OperatingConditions &conditions);
  /// The same at the geometry and conditions of the solver's settings (reynolds().settings).
  CoefficientResult compute();

  /// Only the coefficients on the mesh `coarsening` levels coarser than asked for (no estimate).
  FilmCoefficients coefficients(const FilmThickness &film, const OperatingConditions &conditions,
                                const unsigned int coarsening = 0);

  /// Level-2 film model for the dynamics module (seal_dynamics.h FilmModel): the coefficients of
  /// `film` with the ring speeds replaced by the arguments. Results are cached per speed pair.
  /// The returned function refers to this solver, which must outlive it.
  std::function<FilmCoefficients(double, double)> film_model(const FilmThickness &film,
                                                             const OperatingConditions &conditions);

  CoefficientSettings settings;

private:
  /// What one mesh's computation cost: times (s) and linear-solver work of the operating-point
  /// solve and of the coefficient set.
  struct MeshCost
  {
    double solve_time = 0, coefficient_time = 0;
    FilmLinearSolver::Statistics solve_linear, coefficient_linear;
  };
  /// The loads of the operating point and K, D on the mesh `coarsening` levels coarser.
  std::pair<FilmLoads, FilmCoefficients> compute_on_mesh(const FilmThickness &film,
                                                         const OperatingConditions &conditions,
                                                         const unsigned int coarsening,
                                                         MeshCost &cost);

  MPI_Comm comm;
  ReynoldsSolver solver;
};

} // namespace sealfe
