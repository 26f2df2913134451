// FilmLoads: the integral results of a film solution (force, moments, leakage, friction) in SI
// units, with the sign conventions of doc/reynolds.md, conventions; LoadIntegrator: their
// integration over a ReynoldsSolver's solution and their linearisation.
#pragma once

#include <deal.II/base/tensor.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <nlohmann/json.hpp>

#include <array>
#include <functional>
#include <vector>

namespace sealfe
{
/// Loads of the film on the flexibly mounted ring.
///   force_z = int (p - p_ref) dA, moment_x = int (p - p_ref) y dA, moment_y = -int (p - p_ref) x
///   dA, moment_restoring = -int (p - p_ref) r cos(theta - psi) dA, moment_transverse = int (p -
///   p_ref) r sin(theta - psi) dA, leakage_inner/outer: volume flow (m^3/s) through r = ri / r =
///   ro, positive out of the dam, friction_torque: viscous torque resisting the rotor (N m).
struct FilmLoads
{
  double force_z = 0;
  double moment_x = 0;
  double moment_y = 0;
  double moment_restoring = 0;
  double moment_transverse = 0;
  double leakage_inner = 0;
  double leakage_outer = 0;
  double friction_torque = 0;
  double min_film = 0;
  double max_pressure = 0;
  double min_pressure = 0; ///< Pa, minimum of the interpolated p_h (quadrature points and nodes)
  /// Pa, minimum over the degrees of freedom (support points): the values the cavitation models
  /// reynolds and jfo keep at or above p_cav (to solver tolerance).
  double min_pressure_nodal = 0;
  /// Pa, >= 0 (reynolds and jfo; 0 for the others): min(p_cav, min_pressure_nodal) -
  /// min_pressure, how far a higher-order interpolant dips below its nodes at the cavity edge.
  double pressure_undershoot = 0;
  /// N, <= 0 (reynolds and jfo; 0 for the others): int min(p_h - p_cav, 0) dA, the load the
  /// undershoot removes from force_z.
  double pressure_undershoot_force = 0;
  double cavitated_fraction = 0;
  double contact_force = 0;         ///< N, part of force_z carried by the asperities
  double contact_moment_x = 0;      ///< N m, part of moment_x
  double contact_moment_y = 0;      ///< N m, part of moment_y
  double contact_area_fraction = 0; ///< real contact area / nominal area
  double min_film_over_sigma = 0;   ///< min h / composite roughness (inf when smooth)
  double squeeze_flow = 0;          ///< int s dh/dt dA (m^3/s): Q_in + Q_out + squeeze_flow = 0
  double area = 0; ///< area of the dam as integrated (m^2): the discrete domain for the FE model

  nlohmann::json to_json() const;
};

/// A perturbation direction of the film: dh/dq (m per unit q) and d(dh/dt)/d(qdot) (m/s per unit
/// qdot), as functions of (r, theta). For q = (z, tilt_x, tilt_y): dh/dq = 1, r sin(theta),
/// -r cos(theta) (film_thickness.h), and the same for the rates. The loads' cell loop calls both
/// from deal.II's threads at once: they must be safe to call concurrently (pure functions).
struct FilmPerturbation
{
  std::function<double(double, double)> dh;
  std::function<double(double, double)> dh_dt;
};

class ReynoldsSolver;

/// The loads of a full film (no cavitation model, smooth faces) are affine in the nodal pressures:
/// each sum of LoadIntegrator is its value at p = 0 plus weights . p (force and moments through p,
/// the friction torque through dp/dtheta). Both parts are gathered during the assembly
/// (ReynoldsSolver::assemble_system), which evaluates the film at every quadrature point
/// anyway, so that loads() evaluates it again only in the cells on the two circles (leakages).
struct AffineLoadSums
{
  static constexpr unsigned int linear_sums[6] = {0, 1, 2, 3, 4, 7};
  static constexpr unsigned int n_linear = 6;
  bool valid = false;
  std::vector<double> constant; ///< every sum at p = 0
  /// d(sum_m)/dp_j at [n_linear j + m], j over the locally relevant dofs, m over linear_sums
  std::vector<double> weight;
  /// The current cell's part of `weight`, [n_linear i + m] for its dof i (add_affine_point);
  /// add_cell() adds it to `weight`.
  std::vector<double> cell_weight;
  /// Zeroed sums to gather (gather) or none (memory released); not valid either way until the
  /// assembly sets `valid` after its loop.
  void reset(bool gather, std::size_t n_relevant_dofs, unsigned int dofs_per_cell);
  void add_cell(const std::vector<unsigned int> &relevant_index);
};

/// Loads of a ReynoldsSolver's last solution, and their derivatives along film perturbations
/// (ReynoldsSolver::linearized_loads). One integration routine for both, so that the
/// linearisation differentiates exactly what the loads integrate; the adjoint path's load
/// functionals (generalized_force_functionals) take add_pressure_loads' points, force and moment
/// weights and clip, and tests/validation/film_multigrid.cc holds the two paths to the CG
/// tolerance.
class LoadIntegrator
{
public:
  using VectorType = dealii::TrilinosWrappers::MPI::Vector;

  explicit LoadIntegrator(const ReynoldsSolver &solver);
  /// Loads of the solved state.
  FilmLoads loads() const;
  /// Whether the solver's AffineLoadSums give the loads (full film).
  bool affine_applies() const;
  /// Whether loads() takes them (they apply and the last assembly gathered them).
  bool uses_assembled_sums() const;
  /// One quadrature point of the assembly (the film f there) into `sums` (the weights into
  /// its cell_weight).
  /// `Values`: FEValues<2> or PolarCellValues.
  template <typename Values, typename Film>
  void add_affine_point(AffineLoadSums &sums, const Values &fe_values, unsigned int q,
                        const Film &f) const;
  /// Derivatives of every load along each perturbation: the Reynolds system linearised about the
  /// solved state, one solve each with the solver's factorisation.
  std::vector<FilmLoads> linearized_loads(const std::vector<FilmPerturbation> &perturbations) const;
  /// Derivatives of (force_z, moment_x, moment_y) alone along each perturbation. Where the system
  /// is solved by CG (full film or half-Sommerfeld: A symmetric to round-off, these loads linear
  /// in the nodal pressure, L_i(dp) = g_i . dp) and there are more than three directions, by
  /// its adjoint: three solves A z_i = C^T g_i, dL_i = z_i . b_k plus the direction's term at
  /// dp = 0 (asperity contact); 3 Krylov solves instead of 6 for the coefficient set. Else from
  /// linearized_loads.
  std::vector<std::array<double, 3>>
  linearized_generalized_forces(const std::vector<FilmPerturbation> &perturbations) const;

private:
  /// Whether linearized_generalized_forces takes the adjoint solves for `n_directions`.
  bool adjoint_applies(std::size_t n_directions) const;
  struct PointState;
  struct PointPerturbation;

  /// Right-hand sides -(dR/dh) dh - (dR/dh_t) dh_t of the linearised system, one per direction.
  std::vector<VectorType>
  linearized_right_hand_sides(const std::vector<FilmPerturbation> &perturbations) const;
  /// C^T g_i of the three load functionals of the nodal pressure, L_i(dp) = g_i . dp (force_z,
  /// moment_x, moment_y of a pressure change dp, the quadrature of integrate, half-Sommerfeld's
  /// clipped points left out), condensed by the homogeneous constraints (dp = C du).
  std::array<VectorType, 3> generalized_force_functionals() const;
  /// Nodal pressure and void-fraction perturbations (dp, dv) from the solution du of the
  /// linearised system (the unknown is p, u = (p - p_cav)/P, or the JFO node's kept unknown).
  void nodal_perturbations(const VectorType &du, VectorType &dp, VectorType &dv) const;
  /// Loads of the solved state (perturbations = {nullptr}) or their derivatives for perturbations
  /// whose nodal pressure and void-fraction changes are dp, dv.
  std::vector<FilmLoads> integrate(const std::vector<const FilmPerturbation *> &perturbations,
                                   const std::vector<const VectorType *> &dp,
                                   const std::vector<const VectorType *> &dv) const;
  /// loads() from the solver's AffineLoadSums, the leakages from the cells on the circles.
  FilmLoads affine_loads() const;
  /// By active cell index: whether the cell has a vertex on either circle. Only such a cell
  /// holds a dof on a circle (a dof inside a boundary edge belongs to that edge's one cell), so
  /// only its residual enters the leakages.
  std::vector<bool> leakage_cells() const;
  /// Whether the solved system was assembled with PolarCellValues (ReynoldsSolver::
  /// assembles_on_polar_rows: the full film, the JFO cell matrices and the reynolds model's
  /// system on the built-in annulus): the loads integrated cell by cell (integrate: the
  /// cavitation models, the linearised loads), the leakage residual and the linearised
  /// right-hand sides then take them too.
  bool polar_assembly() const;
  /// Adds a cell residual's entries at the dofs on the inner and outer circle to the leakage
  /// sums (sum[5], sum[6]).
  void add_leakages(const std::vector<dealii::types::global_dof_index> &dofs,
                    const dealii::Vector<double> &local_residual, std::vector<double> &sum) const;
  /// The sign of the Poiseuille shear in the torque resisting the rotor (add_friction_and_squeeze).
  double friction_face() const;
  /// Nodal cavitation indicator (1 cavitated, 0 full film) of the reynolds and jfo solutions.
  VectorType cavitation_indicator() const;
  /// Force, moments, area, cavitated area and contact sums at one quadrature point.
  void add_pressure_loads(const PointState &x, const PointPerturbation &d,
                          std::vector<double> &sum) const;
  /// Friction torque and squeeze flow sums at one quadrature point.
  void add_friction_and_squeeze(const PointState &x, const PointPerturbation &d,
                                std::vector<double> &sum) const;
  /// The point's contribution to the cell residual of the weak form (leakages).
  void add_residual(const PointState &x, const PointPerturbation &d,
                    const std::vector<dealii::Tensor<1, 2>> &shape_grad,
                    const std::vector<double> &shape_value,
                    dealii::Vector<double> &local_residual) const;
  /// Global sums into FilmLoads.
  FilmLoads finish(const std::vector<double> &sum, bool base, double p_min, double p_max,
                   double p_min_nodal) const;

  const ReynoldsSolver &solver;
  bool clip, jfo;
  double p_cav, p_ref, cos_psi, sin_psi, mu;
};

} // namespace sealfe
