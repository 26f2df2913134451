// JFOSolver: the mass-conserving (Jakobsson-Floberg-Olsson / Elrod-Adams) cavitation problem of a
// ReynoldsSolver's discretisation, by Fischer-Burmeister-Newton-Schur with active-set polishing.
#pragma once

#include <deal.II/base/point.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <Epetra_BlockMap.h>

#include <memory>
#include <utility>
#include <vector>

namespace sealfe
{
class ReynoldsSolver;

/// Solves, on the mesh, dofs and matrix of `solver` (starting from the coarse level's solution,
/// or on the coarsest level from the full film, which it solves then), for
/// the nodal a_j = (p_j - p_cav)/P >= 0 and void fraction v_j >= 0 with a_j v_j = 0 and the
/// discrete mass balance (doc/cavitation.md, and the comment above ReynoldsSolver's
/// cell_film_matrices). Leaves the pressure and void fraction, the factorised Jacobian at the
/// solution and the elimination data of the linearisation in the solver. One object per solve.
class JFOSolver
{
public:
  using VectorType = dealii::TrilinosWrappers::MPI::Vector;

  explicit JFOSolver(ReynoldsSolver &solver);
  /// Throws std::runtime_error if the iteration does not converge.
  void solve();
  /// Tests: assemble every residual, right-hand side and Jacobian cell by cell (as before the
  /// global matrices P A and G were used), to compare the two.
  static inline bool assemble_by_cells = false;
  /// Largest number of changed columns for which a global active-set round solves by a low-rank
  /// update of the held factorisation instead of a new one (low_rank_solve); 0 turns it off
  /// (tests). 64: on the tilted seal at 5.3e5 dofs the confirming round differs in 33 columns
  /// after a band start and its update costs half a factorisation (1.0 against 1.9 s). At 1.05e6
  /// dofs the confirming round differs in about 50 columns; its update costs 1.8-1.9 s against
  /// 4.8-5.8 s for a factorisation with its analysis (doc/performance.md "Sessions 18 to 20").
  static inline unsigned int low_rank_limit = 64;
  /// Whether a level started from the coarse level begins its polish with band rounds about the
  /// start's cavity boundary (JFOSolver::polish); false: with a global round (tests).
  static inline bool band_start = true;
  /// Tests: solves (not start-only levels) whose Jacobian at the solution, the one the linearised
  /// loads solve with, came from the global P A and G by columns (jacobian_by_columns: where the
  /// converged iteration assembled only the residual, i.e. it followed a polish) or from the cell
  /// loop (assemble()); counted since the program started, one of the two per solve.
  static inline unsigned int jacobians_by_columns = 0, jacobians_by_cells = 0;
  /// Tests: solves of a finest level (not start-only) that read the cell matrices in one pass
  /// without holding those of every cell (make_global_matrices), counted since the program
  /// started.
  static inline unsigned int solves_in_one_pass = 0;

  /// Test hook (tests/validation/cavitation_fe.cc): on a solver set up for JFO (after a run),
  /// the flat P A and G of prepare_global_matrices next to deal.II's assembly of the same cell
  /// matrices into a copy of the system matrix (AffineConstraints::distribute_local_to_global
  /// with the homogeneous constraints), read in the same storage order (this rank's rows); all
  /// empty where the global matrices do not apply (hanging nodes).
  struct GlobalMatricesAndAssembly
  {
    std::vector<double> PA, G, assembled_PA, assembled_G;
  };
  GlobalMatricesAndAssembly global_matrices_and_assembly();
  /// Test hook (tests/validation/cavitation_fe.cc): on a solver after a JFO run, the FB-Newton
  /// Jacobian at its solution built again, by columns of the global P A and G
  /// (jacobian_by_columns) or by the cell loop (assemble()), and left for the linearised loads
  /// as solve() leaves it; returns this rank's rows' values in storage order (empty where by
  /// columns does not apply, or where the solution's a, v from its pressure do not give this
  /// rank's stored elimination: the caller agrees on it with the other ranks).
  std::vector<double> jacobian_at_solution(bool by_columns);
  /// Test hook (tests/validation/cavitation_fe.cc): on a solver after a run, this rank's owned
  /// entries of the full-film right-hand side made from the cell matrices (ReynoldsSolver::
  /// full_film_flow_scale, as solve() makes it where it keeps them; its one pass adds the same
  /// cells in the same order through add_to_full_film_rhs) and by assemble_system(), in that
  /// order; leaves
  /// the full-film system in the solver.
  std::pair<std::vector<double>, std::vector<double>> full_film_rhs_both_ways();

private:
  /// Assemble the residual (and the reduced Newton system) at (a, v); returns the merit
  /// 1/2 (|R|^2 + |phi|^2). `active_set_step`: the linear system of a fixed cavitated set.
  /// `only_rows` (by global index; a band round's rows): where the global matrices serve, only
  /// those rows of the residual, right-hand side and matrix are made (the others keep stale
  /// values, and the merit is not that of the whole system).
  double assemble(const VectorType &a, const VectorType &v, bool with_jacobian,
                  bool active_set_step = false, const std::vector<bool> *only_rows = nullptr);
  /// The global matrices P A and G in the storage order of the system matrix (each rank its own
  /// rows; only Dirichlet constraints), so that an active-set Jacobian is a column selection of
  /// the two; false (and the cell-by-cell assembly is used) otherwise.
  bool prepare_global_matrices();
  /// The residual (and, with `with_rhs`, the right-hand side of the active-set system) at (a, v)
  /// as products of the global P A and G instead of a loop over the cells; false (nothing done)
  /// (on every rank) when the global matrices are not there or a and v lack a column of some
  /// rank's rows. Collective.
  bool assemble_by_products(const VectorType &a, const VectorType &v, bool with_rhs,
                            const std::vector<bool> *only_rows = nullptr);
  /// The local values of an owned (not ghosted) vector: entry k is the k-th locally owned dof.
  double *owned_values(VectorType &x) const;
  const double *owned_values(const VectorType &x) const;
  /// The FB-Newton Jacobian at (a, v) into the system matrix (no right-hand side) as column
  /// combinations of the global P A and G, for the linearised loads at the solution; false
  /// (nothing done, on every rank) when the global matrices are not there or a and v lack a
  /// column of some rank's rows. Collective.
  bool jacobian_by_columns(const VectorType &a, const VectorType &v);
  /// Start from the converged state of the mesh twice as coarse, else the clipped full film.
  void warm_start();
  /// Start values from the mesh-sequencing solver (ReynoldsSolver::coarse_level_state); false
  /// if there is none, it fails or its mesh does not cover this one.
  bool coarse_start();
  /// Largest |phi(a_j, v_j)| over the unconstrained dofs.
  double complementarity(const VectorType &a, const VectorType &v) const;
  /// Newton direction (da, dv) of the current Jacobian: factorise, solve, recover.
  void newton_direction();
  /// (da, dv) from the reduced unknown w.
  void recover();
  /// The solution w of the active-set system just assembled (newton_rhs, the Jacobian of the set
  /// (set_a, set_v)) by a Sherman-Morrison-Woodbury update of the factorisation of an earlier
  /// global round, whose Jacobian differs in the columns of the nodes that changed set since
  /// (solve_column_update); false (nothing done) when there is no such factorisation, more than
  /// low_rank_limit columns changed (more than SparseDirect::max_shared_update_columns where the
  /// ranks share the factorisation), or the update is refused (near-singular, or its backward
  /// error above the bound).
  bool low_rank_solve(const VectorType &set_a, const VectorType &set_v);
  /// With SEALFE_JFO_KRYLOV_PROBE (one rank): the global round's system just solved directly (w)
  /// also by ActiveSetKrylov's variants `variants`, printed to stderr (jfo_krylov.h).
  void probe_krylov(const VectorType &set_a, const VectorType &set_v, double direct_seconds,
                    unsigned int round, const char *variants);
  /// After a factorisation of a global round's Jacobian: remember its set for low_rank_solve.
  void remember_factored_set(const VectorType &set_a, const VectorType &set_v);
  /// Active-set polish from the set of the current iterate; true if it found the exact solution
  /// (then it is the current iterate).
  bool polish();
  /// Watchdog bookkeeping and the step along (da, dv): projected full step or backtracking.
  void step(double merit);
  /// Pressure, void fraction and linearisation data into the solver.
  void store_solution();

  ReynoldsSolver &s;
  /// The scale of the mass residual: the size of the full-film right-hand side (set by solve():
  /// ReynoldsSolver::full_film_flow_scale, or flow_scale_of_full_film_rhs after the one pass of
  /// make_global_matrices; the test hooks do not read their merits).
  double flow_scale = 1;
  /// Cell matrices A, G, F (state independent, ReynoldsSolver::compute_cell_matrices), by active
  /// cell index. All of them where the cell-by-cell paths need them (cell_matrices_kept: several
  /// ranks, constraints that couple dofs, FB-Newton steps, the test hooks); after the one pass
  /// of solve() (one rank, Dirichlet conditions only) those of the cells with a constrained dof,
  /// the others empty, with their constant terms in interior_constant.
  std::vector<dealii::FullMatrix<double>> cell_A, cell_G;
  std::vector<dealii::Vector<double>> cell_F;
  bool cell_matrices_kept = false;
  /// All cell matrices into cell_A, cell_G, cell_F, unless they are there.
  void keep_cell_matrices();
  /// Of a cell without constrained dofs (n values per active cell index, after the one pass):
  /// its residual and active-set right-hand side at a = v = 0, F - A 1 p_cav, as
  /// assemble_by_products' constant terms compute them.
  std::vector<double> interior_constant;
  /// The global P A and G (global_PA, global_G) from the cell matrices; with `first_pass` (one
  /// rank only, called by solve() before any other use of the cell matrices) the same pass makes
  /// the cell matrices as it goes and also gives the flow scale, interior_constant and the
  /// constrained cells' matrices, so that the matrices of all cells are never held; without it
  /// the matrices are kept first (keep_cell_matrices). False if the global matrices cannot serve
  /// (then global_matrices = -1), or with `first_pass` on several ranks or with the matrices
  /// already kept (nothing done). Collective unless it returns at once.
  bool make_global_matrices(bool first_pass);
  /// Values of the assembled P A and G (row by row as the system matrix stores them), and
  /// whether they can be used (0: not tried yet, 1: yes, -1: no).
  std::vector<double> global_PA, global_G;
  int global_matrices = 0;
  /// For assemble_by_products (by global index): the residual and active-set right-hand side at
  /// a = v = 0 on the unconstrained dofs (F, the cavitation pressure and the constrained dofs'
  /// fixed values), which constrained dofs, and the constrained values they were computed with.
  std::vector<double> constant_residual, constant_rhs;
  std::vector<char> constrained;
  std::vector<double> constrained_a, constrained_v;
  /// The system matrix's rows' and local columns' global indices, listed once
  /// (list_global_indices, with `constrained`).
  std::vector<long long> row_gid, column_gid;
  bool indices_listed = false;
  void list_global_indices();
  /// Several ranks: the position in the ghosted vectors' storage (a, v, ta, tv share a's map)
  /// of each local column of the system matrix (-1: not held) and of each owned dof, found once
  /// for `ghosted_layout` instead of a map lookup per entry at every assembly (0.28 s of the
  /// JFO assembly at 1.05e6 dofs on two ranks, doc/performance.md "Session 28"), and a number
  /// of that layout (0: none yet).
  std::vector<int> column_in_ghosted, owned_in_ghosted;
  std::unique_ptr<Epetra_BlockMap> ghosted_layout;
  unsigned int ghosted_layout_id = 0;
  /// x (ghosted, or plain on one rank) at the system matrix's local columns: values[c] is x at
  /// dof column_gid[c]. False if x lacks a column.
  bool values_at_columns(const VectorType &x, std::vector<double> &values);
  /// The positions above for x's layout (made again if x's map does not share the data of the
  /// one they were found for), and that layout's number; 0 if x holds no ghosts. This rank alone
  /// (no MPI).
  unsigned int find_ghosted_positions(const VectorType &x);
  /// Set by assemble_by_products with the right-hand side: per local column of the system
  /// matrix, whether that node keeps its pressure (a_j >= v_j); assemble's column selection of the
  /// same round reads it instead of gathering a and v at the columns again.
  std::vector<char> column_keeps_pressure;

  VectorType a_owned, v_owned, a, v, residual, newton_rhs, w, da, dv, trial_a, trial_v, ta, tv;
  VectorType best_a, best_v;
  double best_merit;
  unsigned int steps_without_progress = 0;
  bool monotone = false;
  unsigned int active_set_rounds = 0; // linear solves of the polish, band rounds included
  unsigned int band_rounds = 0;
  /// MUMPS workspace retries of the band rounds' factorisations (solve_on_subset)
  unsigned int band_workspace_retries = 0;
  /// Set by a start from the coarse level: the first polish begins with band rounds about the
  /// start's cavity boundary, before any global factorisation (JFOSolver::polish).
  bool band_first = false;
  /// The set of the Jacobian whose factorisation the linear solver holds (keep-pressure flag per
  /// dof; empty: none usable) and the solver's factorisation count just after it was made (a
  /// later factorisation, e.g. of a Newton step, makes it stale).
  std::vector<char> factored_keep_pressure;
  unsigned int factored_count = 0;
  unsigned int low_rank_updates = 0;
};

} // namespace sealfe
