// ReynoldsSolver: the full 2D finite-element Reynolds equation on the annular dam (level 2 of
// doc/reynolds.md), distributed over MPI ranks, in the shape of deal.II's step-40: setup (once per
// mesh), assemble, solve (with the cavitation solvers of reynolds_cavitation_solver.h and
// jfo_solver.h), loads (film_loads.h) and output (film_output.h).
#pragma once

#include <sealfe/film/film_linear_solver.h>
#include <sealfe/film/film_loads.h>
#include <sealfe/film/film_output.h>
#include <sealfe/film/film_settings.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/function.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace sealfe
{
class PolarCellValues;

/// Solves, for the pressure p(x, y) on ri <= r <= ro (Cartesian coordinates of the dam plane),
///
///   div( h^3/(12 mu) grad p ) = div( h u_mean ) + dh/dt (+ f),   u_mean = (w1 + w2)/2 * r e_theta
///
/// with p = pi on r = ri and p = po on r = ro, by continuous Q_k elements on a curved mesh
/// (MappingQ of degree FilmSettings::mapping_degree(), k + 1 by default). The equation is scaled by
/// 12 mu / C0^3 so that the matrix is O(1) and solver tolerances are relative. Leakage is the
/// consistent (residual) boundary flux, so the two leakages balance to solver tolerance. All inputs
/// are one FilmSettings. The mesh, degrees of freedom, sparsity pattern and zero-Dirichlet
/// constraints are built once and reused by every run() whose settings give the same discretisation
/// (FilmSettings::same_discretization): a transient or a sweep changing z, tilts, rates, speeds or
/// pressures only assembles and solves again.
class ReynoldsSolver
{
public:
  using LinearSolver = FilmSettings::LinearSolver;

  explicit ReynoldsSolver(MPI_Comm comm);
  ReynoldsSolver(const FilmSettings &settings, MPI_Comm comm);
  ReynoldsSolver(const ReynoldsSolver &) = delete;
  ReynoldsSolver &operator=(const ReynoldsSolver &) = delete;
  ~ReynoldsSolver();

  /// The solver part of FilmSettings (Discretization, Cavitation, Roughness, Contact).
  static void declare_parameters(dealii::ParameterHandler &prm);
  void parse_parameters(dealii::ParameterHandler &prm);

  /// Set up (if the discretisation changed), assemble and solve the problem of `settings` on the
  /// mesh `coarsening` levels coarser than asked for, and return the loads. Throws
  /// std::runtime_error on bad geometry or a linear solver failure.
  FilmLoads run(const unsigned int coarsening = 0);
  /// The same with the geometry and operating conditions replaced by these.
  FilmLoads run(const FilmThickness &film, const OperatingConditions &conditions,
                const unsigned int coarsening = 0);

  /// A perturbation direction of the film (film_loads.h).
  using FilmPerturbation = sealfe::FilmPerturbation;

  /// Derivative of every load of the last run() in the direction `perturbation`: the Reynolds
  /// system linearised about the solved pressure, A dp = -(dR/dh) dh - (dR/dh_t) dh_t, solved with
  /// the factorisation (or AMG hierarchy) of run(), so one extra linear solve. Fields of the
  /// result are derivatives (force_z: N per unit q, leakage: m^3/s per unit q, ...). With
  /// half-Sommerfeld the cavity boundary is frozen: dp counts only where p > p_cav.
  FilmLoads linearized_loads(const FilmPerturbation &perturbation) const;
  /// The same for several directions at once: one assembly loop for all right-hand sides and one
  /// solve each with the same factorisation (what the 6-direction coefficient set uses).
  std::vector<FilmLoads> linearized_loads(const std::vector<FilmPerturbation> &perturbations) const;
  /// Only the derivatives of (force_z, moment_x, moment_y) along each direction: where CG solves
  /// the (symmetric) system and there are more than three directions, by three adjoint solves
  /// (LoadIntegrator::linearized_generalized_forces); else from linearized_loads.
  std::vector<std::array<double, 3>>
  linearized_generalized_forces(const std::vector<FilmPerturbation> &perturbations) const;

  /// The film's coefficients at one point, for every term of the (average) Reynolds equation.
  struct LocalFilm
  {
    double r, theta, h;
    dealii::Tensor<2, 2> K, dK_dh; // pressure-flow tensor h^3/(12 mu) diag(phi_r, phi_theta)
    dealii::Tensor<1, 2> u;        // mean surface velocity (w1 + w2)/2 r e_theta
    dealii::Tensor<1, 2> c, dc_dh; // Couette flux h_T u + (u1 - u2)/2 sigma phi_s e_theta
    double c_div, dc_div_factor;   // div c, and d(omega_eff)/dh (div of a perturbed c)
    double squeeze, dsqueeze_dht;  // d h_T/dt = h_T'(h) dh/dt, and h_T'(h)
    double contact_pressure = 0, dcontact_dh = 0;    // asperity contact (0 without a model)
    double phi_r = 1, phi_theta = 1, phi_s = 0, h_T; // flow factors and expected gap (output)
  };
  LocalFilm local_film(const dealii::Point<2> &x) const;
  /// The same with r = |x|, theta = atan2(x) and cos, sin of the film's tilt angle given (the
  /// assembly has them per row and per cell): on the coned, tilted film (no waviness, expression
  /// or features) h, dh/dtheta and dh/dt then take no sine or cosine per point.
  LocalFilm local_film(const dealii::Point<2> &x, const double r, const double theta,
                       const double cos_tilt, const double sin_tilt) const;
  /// The pressure-flow tensor K alone (equal to local_film(x).K, at a fraction of the cost).
  dealii::Tensor<2, 2> pressure_flow(const dealii::Point<2> &x) const;
  /// The same with cos, sin of the film's tilt angle given (once per level assembly).
  dealii::Tensor<2, 2> pressure_flow(const dealii::Point<2> &x, const double cos_tilt,
                                     const double sin_tilt) const;

  /// Write pressure, film thickness and the volume flux vector (VTU per rank group + PVTU + PVD)
  /// into `directory`; returns the PVD file name (film_output.h).
  std::string write_output(const std::string &directory) const;

  /// Volume flow (m^3/s) outward through the circle r = rho, -int h^3/(12 mu) dp/dr rho dtheta
  /// (the Couette flow is circumferential and does not cross it), by the midpoint rule on
  /// `n_points` points. A direct flux integral, so it converges with the mesh only; the leakages
  /// in FilmLoads are the consistent (conservative) ones.
  double volume_flow_through_circle(const double rho, const unsigned int n_points = 2048) const;

  /// p_h (Pa) at the given points of the dam (on every rank, for all ranks' points).
  std::vector<double> pressure_at(const std::vector<dealii::Point<2>> &points) const;

  /// L2 norm of (p_h - exact) over the dam (for convergence tests).
  double l2_error(const dealii::Function<2> &exact) const;
  /// int g(p_h) dA over the dam with the given rule on every cell (for quadrature checks).
  double pressure_integral(const std::function<double(double)> &g,
                           const dealii::Quadrature<2> &cell_rule) const;

  dealii::types::global_dof_index n_dofs() const { return dof_handler.n_dofs(); }
  unsigned int degree() const { return polynomial_degree; }
  const AnnulusMesh &mesh() const { return settings.mesh; }
  AnnulusMesh &mesh() { return settings.mesh; }
  /// How often the mesh, dofs and sparsity were built (1 for a sequence of runs on one geometry).
  unsigned int n_setups() const { return setup_count; }
  /// The solver of the mesh twice as coarse that gave the last cavitation solve (jfo, reynolds)
  /// its start (mesh sequencing), or nullptr. Its settings are a copy of these (with the coarser
  /// coarsening).
  const ReynoldsSolver *coarse_level_solver() const { return coarse_solver.get(); }
  bool error_estimate_enabled() const { return estimate_error; }
  unsigned int linear_iterations() const { return last_iterations; }
  /// Factorisations, solves and Krylov iterations of the last run (and its linearised solves),
  /// or since the last reset_linear_solver_statistics() (after CoefficientSolver::compute() with
  /// the perturbation method: the coefficient set's linearised solves only).
  const FilmLinearSolver &linear_solver_statistics() const { return linear_system_solver; }
  /// Count the linear solver's work afresh from here (run() does so itself): what the
  /// linearised solves after a run cost apart from the run (the coefficient set's summary).
  void reset_linear_solver_statistics() { linear_system_solver.reset_statistics(); }
  /// Newton iterations and final relative mass residual of the cavitation solve (reynolds, jfo).
  unsigned int nonlinear_iterations() const { return cavitation_iterations; }
  /// Newton iterations spent on the coarser meshes that provided the JFO start (mesh sequencing).
  unsigned int coarse_nonlinear_iterations() const { return coarse_iterations; }
  double nonlinear_residual() const { return cavitation_residual; }
  /// JFO work of the last level: Fischer-Burmeister Newton steps and active-set rounds (their sum
  /// is nonlinear_iterations()).
  unsigned int newton_steps() const { return jfo_newton_steps; }
  unsigned int active_set_rounds() const { return jfo_active_set_rounds; }
  /// Of those, the band rounds: each a sparse direct factorisation of a principal submatrix (the
  /// dofs near the last set changes), not counted in linear_solver_statistics().
  unsigned int band_rounds() const { return jfo_band_rounds; }
  /// MUMPS factorisations of the band rounds repeated with a larger workspace margin
  /// (SparseDirect::workspace_retries), which linear_solver_statistics() does not count.
  unsigned int band_workspace_retries() const { return jfo_band_workspace_retries; }
  /// JFO: of the global rounds, those solved by a low-rank update of an earlier round's
  /// factorisation (no factorisation: JFOSolver::low_rank_solve); reynolds: of the steps, those
  /// so solved (ReynoldsCavitationSolver::low_rank_solve).
  unsigned int low_rank_updates() const { return jfo_low_rank_updates; }
  /// JFO on a sequenced mesh: whether a finer level started from this one skips the band start,
  /// because this level's first global round flipped more than a tenth of what its band rounds
  /// flipped, or this level did not take the band start (JFOSolver::polish, warm_start).
  bool band_start_failed() const { return jfo_band_start_failed; }
  /// Factorisations (or AMG set-ups) and Krylov iterations of all mesh-sequencing levels.
  unsigned int coarse_level_factorizations() const { return coarse_factorizations; }
  unsigned int coarse_level_krylov_iterations() const { return coarse_krylov_iterations; }
  /// MUMPS workspace retries of all mesh-sequencing levels (their global and band rounds).
  unsigned int coarse_level_workspace_retries() const { return coarse_workspace_retries; }
  /// Seconds spent per stage of the last run (setup, assemble, solve, loads).
  std::map<std::string, double> stage_times() const;
  /// Parts of the setup stage and of the multigrid set-up and level preparation of the last run
  /// (seconds; a run on the mesh of the previous one has no mesh set-up parts).
  std::map<std::string, double> detail_times() const;
  /// Whether the loads of the last run came from the sums gathered during the assembly
  /// (AffineLoadSums: full film, smooth faces) rather than the point-by-point integration.
  bool loads_from_assembled_sums() const;

  /// Optional manufactured-solution hooks (tests): Dirichlet data on both circles and an extra
  /// source f (m/s) on the right-hand side. Empty means the physical pi/po and no source.
  std::function<double(const dealii::Point<2> &)> boundary_pressure;
  std::function<double(const dealii::Point<2> &)> source;
  /// The assembly on the built-in annulus takes each cell's geometry from its radial row
  /// (PolarCellValues); false: FEValues on every cell of the fine-level assembly and the
  /// leakage residual (tests compare the two). The multigrid level matrices (cg-gmg) always
  /// take PolarCellValues.
  bool polar_rows = true;
  /// Whether the assemblies take each cell's geometry from its radial row (PolarCellValues): the
  /// built-in annulus's cells are rotations of one radial row (a mesh file's are not).
  bool assembles_on_polar_rows() const { return mesh_parameters.mesh_file.empty() && polar_rows; }

  /// Everything the solve depends on. Changing it between runs is allowed; the mesh is rebuilt
  /// only when the discretisation changes.
  FilmSettings settings;
  /// The same objects as settings.cavitation, ... (shorter names used by the tests and front
  /// ends). Cavitation treatment: none, half-Sommerfeld (loads clipped at p_cav), reynolds, jfo.
  CavitationSettings &cavitation = settings.cavitation;
  /// Rough faces: Patir-Cheng average flow (Model = none is the smooth Reynolds equation) and
  /// GW/CEB asperity contact, whose mean contact pressure adds to the film pressure.
  FlowFactors &flow_factors = settings.flow_factors;
  AsperityContact &contact = settings.contact;
  unsigned int &polynomial_degree = settings.polynomial_degree;
  LinearSolver &linear_solver = settings.linear_solver;
  double &solver_tolerance = settings.solver_tolerance;
  bool &estimate_error = settings.estimate_error;

private:
  friend class ReynoldsCavitationSolver;
  friend class JFOSolver;
  friend class LoadIntegrator;
  friend std::string write_film_output(const ReynoldsSolver &solver, const std::string &directory,
                                       const FieldSelection &fields);
  friend std::string write_film_fields(const ReynoldsSolver &solver, const std::string &directory,
                                       const std::string &basename, unsigned int counter,
                                       const FieldSelection &fields, double frame_angle);

  void setup_system(const unsigned int coarsening);
  /// setup_system's parts for a new mesh: the resets (and the mesh grading from the film),
  /// the mesh, mapping, dofs and zero constraints (no MPI call on one rank with the built-in
  /// mesh), and the vectors, matrix and constraints on them.
  bool same_mesh_as_set_up(unsigned int coarsening) const;
  void clear_for_new_mesh();
  void setup_mesh_and_dofs(unsigned int coarsening, unsigned int n_ranks);
  void setup_linear_algebra(unsigned int coarsening);
  /// setup_system for the JFO: on one rank with the built-in mesh, a new mesh of more than 200
  /// cells that has a coarse level, its mesh and dofs (and nested dissection) are made on a
  /// thread of their own while the coarse level is solved (solve_coarse_level), which
  /// coarse_level_state then takes; else setup_system.
  void setup_while_coarse_levels_run(unsigned int coarsening);
  void setup_constraints();
  void assemble_system();
  /// Prepare the linear solver for system_matrix. `symmetric`: full film or its linearisation
  /// (CG allowed); `newton_sequence`: the next Jacobian of a Newton iteration (the previous
  /// factorisation may serve as preconditioner); `deferred`: factorise at the first solve only.
  void factorize(bool symmetric = true, bool newton_sequence = false, bool deferred = false);
  unsigned int solve_linear_system(const dealii::TrilinosWrappers::MPI::Vector &rhs,
                                   dealii::TrilinosWrappers::MPI::Vector &x) const;
  void solve();
  void solve_cavitation();
  /// Scale of the cavitation models' pressure unknown from the full-film solution.
  double full_film_pressure_scale() const;
  /// film_matrices with the values an assembly takes for `cell`: its row's where `polar` holds
  /// the rows (made where assembles_on_polar_rows()) and the cell is a rotation of its row's
  /// first cell, else `fe_values` reinitialised on it; `at_point` or `at_polar_point` (the same
  /// callback for values of the row) sees each point's film.
  void cell_film_matrices(
      std::optional<PolarCellValues> &polar, dealii::FEValues<2> &fe_values,
      const dealii::DoFHandler<2>::active_cell_iterator &cell, const bool with_void,
      dealii::FullMatrix<double> &A, dealii::FullMatrix<double> &G, dealii::Vector<double> &F,
      const std::function<void(unsigned int, const LocalFilm &)> &at_point = {},
      const std::function<void(unsigned int, const LocalFilm &)> &at_polar_point = {}) const;
  /// cell_film_matrices on values already reinitialised on `cell` (FEValues, or the turned
  /// values of a polar row, PolarCellValues: defined and instantiated in reynolds_solver.cc).
  template <class Values>
  void film_matrices(Values &values, const dealii::DoFHandler<2>::active_cell_iterator &cell,
                     const bool with_void, dealii::FullMatrix<double> &A,
                     dealii::FullMatrix<double> &G, dealii::Vector<double> &F,
                     const std::function<void(unsigned int, const LocalFilm &)> &at_point) const;
  /// The cavitation models' film matrices A, G, F of every locally owned cell (by active cell
  /// index): they depend on the film only, so a solve that reads them at every iteration
  /// computes them once (cavitation_levels.cc; the JFO's one rank and the reynolds model read
  /// them in one pass instead, for_each_cell_film_matrices). `with_void`: G too (JFO); without it G
  /// stays empty. A and F have the full-film assembly's bits either way (full_film_flow_scale
  /// relies on it).
  void compute_cell_matrices(bool with_void, std::vector<dealii::FullMatrix<double>> &A,
                             std::vector<dealii::FullMatrix<double>> &G,
                             std::vector<dealii::Vector<double>> &F) const;
  /// Sees a locally owned cell and its film matrices A, G, F.
  using CellFilmVisit = std::function<void(
      const dealii::DoFHandler<2>::active_cell_iterator &, const dealii::FullMatrix<double> &,
      const dealii::FullMatrix<double> &, const dealii::Vector<double> &)>;
  /// The film matrices of compute_cell_matrices (the same bits), made cell by cell in active
  /// cell order and handed to `visit` without being kept: for a pass that reads each cell once
  /// (the JFO's cell matrices held whole were 0.36 GB at 1.05e6 dofs, doc/performance.md).
  void for_each_cell_film_matrices(bool with_void, const CellFilmVisit &visit) const;
  /// The cavitation models' scale of the mass residual, the size of the full-film right-hand
  /// side: system_rhs as assemble_system() makes it (the same sums in the same order), from the
  /// cell matrices `A`, `F` of compute_cell_matrices instead of a second pass over the film. run()
  /// does not assemble the full film for them; they assemble it only where they solve it.
  double full_film_flow_scale(const std::vector<dealii::FullMatrix<double>> &A,
                              const std::vector<dealii::Vector<double>> &F);
  /// full_film_flow_scale cell by cell, for a pass that makes the cell matrices as it goes:
  /// system_rhs = 0, then add_to_full_film_rhs for every locally owned cell in active cell order
  /// (`dofs` the cell's dof indices), then flow_scale_of_full_film_rhs.
  void add_to_full_film_rhs(const dealii::FullMatrix<double> &A, const dealii::Vector<double> &F,
                            const std::vector<dealii::types::global_dof_index> &dofs);
  double flow_scale_of_full_film_rhs();
  /// Mesh sequencing of the cavitation models: solves the same problem on the mesh twice as
  /// coarse (coarse_solver, itself sequenced) and gives its pressure and void fraction at this
  /// mesh's owned dofs (by owned index; the constrained dofs their boundary pressure and no
  /// void), and the coarse level's pressure_scale. False where there is no such level or it
  /// failed: the caller starts from the full film.
  bool coarse_level_state(std::vector<double> &pressure_at_dofs, std::vector<double> &void_at_dofs);
  /// coarse_level_state's solve of the coarse level (sets coarse_level_failed). `support`: where
  /// this level's owned support points go when they are made on a thread alongside (with its
  /// nested dissection from system_matrix), or null when this level's mesh is still being made.
  void solve_coarse_level(std::vector<dealii::Point<2>> *support);
  /// The coarse level's nodal pressure and void fraction at `points` when both meshes are the
  /// built-in polar grid and the coarse level is whole on this rank (one rank, or the coarse
  /// levels each rank solves by itself): cells found by (r, theta), no point search. Returns
  /// false (and leaves the outputs undefined) otherwise.
  bool coarse_values_on_polar_grid(const std::vector<dealii::Point<2>> &points,
                                   std::vector<double> &pressure,
                                   std::vector<double> &void_fraction) const;
  /// The support points of the locally owned dofs by owned index, as
  /// DoFTools::map_dofs_to_support_points computes them (the mapped unit support points of
  /// every cell that is not artificial, a later cell overwriting) without its std::map.
  std::vector<dealii::Point<2>> owned_support_points() const;
  double streamline_tau(const dealii::DoFHandler<2>::active_cell_iterator &cell) const;
  FilmLoads compute_loads() const;

  MPI_Comm mpi_communicator;
  AnnulusMesh &mesh_parameters = settings.mesh;
  FilmThickness &film = settings.geometry;
  OperatingConditions &conditions = settings.conditions;
  /// The settings and coarsening of the last setup_system (null before the first).
  std::unique_ptr<FilmSettings> setup_settings;
  unsigned int setup_coarsening = 0;
  unsigned int setup_count = 0;
  /// Mesh sequencing of the cavitation models: the solver of the mesh twice as coarse (kept, so
  /// that its mesh is reused too).
  std::unique_ptr<ReynoldsSolver> coarse_solver;
  /// The coarse level has been solved while this level's mesh was made (solve_coarse_level,
  /// setup_while_coarse_levels_run), and whether it failed; the support points of this level's
  /// owned dofs made on that thread (empty if not).
  bool coarse_level_solved_ahead = false, coarse_level_failed = false;
  std::vector<dealii::Point<2>> support_made_ahead;
  /// A mesh-sequencing level: its state only starts the finer mesh, so run() accepts the JFO
  /// active-set state of a band round without the global check and computes no loads (nor the
  /// factorisation of the linearised loads).
  bool start_only = false;
  /// Whether rank 0 of its communicator prints progress and fallback lines on stderr: not for
  /// the copies of the coarse levels that ranks other than 0 solve on their own (JFOSolver::
  /// coarse_start), whose lines would repeat once per rank.
  bool reports_progress = true;

  /// The mesh: p4est's distributed triangulation on several ranks; on one rank deal.II's serial
  /// one, whose global refinement costs a fifth of p4est's (0.19 s against 0.74-1.14 s for the
  /// 262 144 cells of 1.05e6 Q2 dofs, doc/performance.md). Its own communicator is then
  /// MPI_COMM_SELF: the linear algebra keeps mpi_communicator.
  std::unique_ptr<dealii::Triangulation<2>> triangulation_storage;
  dealii::Triangulation<2> &triangulation;
  std::unique_ptr<dealii::FE_Q<2>> fe;
  std::unique_ptr<dealii::MappingQ<2>> mapping;
  dealii::DoFHandler<2> dof_handler;
  dealii::IndexSet locally_owned_dofs, locally_relevant_dofs;
  dealii::AffineConstraints<double> constraints;
  dealii::IndexSet inner_boundary_dofs, outer_boundary_dofs;
  dealii::TrilinosWrappers::SparseMatrix system_matrix;
  /// system_matrix has CellSparsity's pattern (set by setup_system: one rank, Dirichlet
  /// constraints only), so the assembly adds the cells without constrained dofs by position.
  bool matrix_by_position = false;
  dealii::TrilinosWrappers::MPI::Vector locally_relevant_solution, system_rhs;

  /// KLU or Krylov + AMG (film_linear_solver.h); mutable: the linearised solves of a const
  /// solver count their work in it.
  mutable FilmLinearSolver linear_system_solver;
  std::vector<double> amg_support_x, amg_support_y; // owned dofs' support points (AMG)
  /// The direct factorisations of this mesh have been given the nested dissection of its polar
  /// node grid, or found that it has none (factorize(), or coarse_level_state while the coarse
  /// levels run; reset by a new mesh).
  bool elimination_order_tried = false;
  /// Whether factorisations by `method` of this mesh's matrices want the nested dissection of
  /// its polar node grid and do not have it yet: direct, MUMPS's sizes, one rank, the built-in
  /// mesh.
  bool wants_nested_dissection(FilmLinearSolver::Method method) const;
  /// Geometric multigrid on the mesh levels (cg-gmg); its smoother (benchmarks change it).
  FilmMultigrid multigrid;

public:
  FilmMultigrid::Parameters multigrid_parameters;

private:
  double equation_scale = 1; // 12 mu / C0^3

  // Zero-Dirichlet constraints of corrections and perturbations (built in setup_system).
  dealii::AffineConstraints<double> homogeneous_constraints;

  // Cavitation (reynolds, jfo) state.
  dealii::TrilinosWrappers::MPI::Vector locally_relevant_void; // v = 1 - liquid fraction
  dealii::TrilinosWrappers::MPI::Vector reynolds_diagonal;
  std::vector<dealii::types::global_dof_index> active_set; // reynolds: dofs held at p_cav
  double pressure_scale = 1;
  dealii::TrilinosWrappers::MPI::Vector jfo_keep_pressure; // 1: node kept dp, 0: kept dv
  dealii::TrilinosWrappers::MPI::Vector jfo_elimination;   // d(eliminated)/d(kept)
  unsigned int cavitation_iterations = 0;
  unsigned int coarse_iterations = 0; // Newton iterations spent on the mesh-sequencing levels
  unsigned int coarse_factorizations = 0, coarse_krylov_iterations = 0,
               coarse_workspace_retries = 0;
  unsigned int jfo_newton_steps = 0, jfo_active_set_rounds = 0, jfo_band_rounds = 0,
               jfo_low_rank_updates = 0, jfo_band_workspace_retries = 0;
  /// JFO on a sequenced mesh: whether the band rounds about the coarse start's cavity boundary
  /// left the set far from the global one (JFOSolver::polish), or were not taken (a coarser
  /// level's had failed, or the test hook JFOSolver::band_start is off); the finer level then
  /// starts with a global round.
  bool jfo_band_start_failed = false;
  unsigned int current_coarsening = 0;
  double cavitation_residual = 0;
  unsigned int last_iterations = 0;
  mutable dealii::TimerOutput timer;
  std::map<std::string, double> setup_detail;
  /// The loads of the last assembly as affine functions of p (full film; film_loads.h).
  AffineLoadSums affine_loads;
};

/// Error estimate of every load of a degree-k solve from the same solve on a mesh twice as coarse
/// (richardson_error of film_settings.h applied to each load; also used for the coefficients).
/// If a load converges like h^m, its error is |L_h - L_2h| / (2^m - 1). Asymptotically m is k + 1
/// (the L2 rate of p) or more (linear functionals), but on practical meshes the observed rate of
/// the moments was below k + 1 (1.8 for k = 1): the estimate assumes only m = k (the H1 rate),
/// |L_h - L_2h| / (2^k - 1), which bounds the true error in tests/validation/
/// reynolds_error_estimate.cc and overestimates it by about 2x (k = 2) asymptotically.
FilmLoads estimate_load_errors(const FilmLoads &fine, const FilmLoads &coarse,
                               const unsigned int degree);

} // namespace sealfe
