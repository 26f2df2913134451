// SparseDirect: a sparse LU factorisation (KLU through Amesos for small systems, MUMPS driven
// directly above) that keeps its symbolic analysis (ordering, block structure) across matrices of
// one sparsity pattern, as the Newton systems of the cavitation models are.
#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <mpi.h>

#include <limits>
#include <memory>
#include <utility>
#include <vector>

class Amesos_BaseSolver;
class Epetra_LinearProblem;
class Epetra_CrsMatrix;
class Epetra_Vector;

namespace sealfe
{
enum class LowRankSolve;
/// A sparse column: (row, value) pairs.
using SparseColumn = std::vector<std::pair<unsigned int, double>>;

/// KLU (Amesos) or MUMPS. factorize() of a matrix with the pattern of the previous one (the same
/// Trilinos matrix object, unchanged number of entries) repeats only the numeric factorisation.
class SparseDirect
{
public:
  /// From this many unknowns on MUMPS (multifrontal, AMD ordering) instead of KLU: the measured
  /// crossover on the annulus meshes is between 1.7e4 and 6.7e4 unknowns.
  static constexpr long long multifrontal_limit = 20000;

  /// MUMPS's workspace margin (ICNTL(14), per cent of the estimate of its analysis) for the
  /// first factorisation of a pattern; doubled up to three times where it falls short (tests).
  static inline int initial_workspace_margin = 20;

  /// From this many unknowns on, a matrix that several ranks factorise together is split over
  /// them (numerics::SubstructuredLU) instead of factorised whole by MUMPS's own parallel
  /// factorisation, which gains little on two ranks (doc/performance.md "Session 27").
  static inline long long substructured_limit = 50000;
  /// A shared factorisation's answer with a larger normwise backward error is refused: the
  /// whole matrix is factorised and solved again (solve()).
  static constexpr double max_substructured_backward_error = 1e-12;
  /// A low-rank update (solve_column_update) of a shared factorisation solves for its k + 1
  /// columns by the shared block solve, whose MUMPS Schur condensation and expansion grow with
  /// the columns: at 1.05e6 unknowns on two ranks 8 columns took 0.73 s, a third of a
  /// factorisation (2.0-2.5 s), and 35 columns 10.2-10.4 s, four factorisations
  /// (doc/performance.md "Session 28"). A guard at the largest measured case that paid (k = 7):
  /// more changed columns are left to a factorisation. Where between 8 and 35 columns the update
  /// stops paying was not measured, nor the ratio at the sizes that reach this path (the coarse
  /// levels that every rank holds whole; a distributed level makes no low-rank update).
  static constexpr unsigned int max_shared_update_columns = 7;

  /// From this many unknowns on, a matrix factorised by MUMPS on one rank is factorised in
  /// single precision and every solve refined in double (a matrix whose single factors do not
  /// refine, condition near 2^24, is factorised again in double, and its pattern stays there).
  /// Off by default (no size): on the tilted seal's JFO at 1.05e6 unknowns it halves the
  /// factors' memory (peak 3.36 -> 2.86 GB) and saves 1.7 s of factorisation, but the
  /// refinement of the low-rank update costs 1.3 s more and the whole run is unchanged within
  /// this machine's spread (doc/performance.md "Session 30"). Tests and studies set it.
  static inline long long single_precision_limit = std::numeric_limits<long long>::max();
  /// Refinement stops at this normwise backward error (2^-46, 128 u: the bound a low-rank update
  /// is accepted at), or when a step no longer halves it, or after max_refinement_steps steps;
  /// an answer then above it is not accepted (SparseDirect factorises in double instead). One
  /// step takes the JFO Jacobians' first answers (1e-10) below it (doc/performance.md "Session
  /// 30").
  static constexpr double refined_backward_error = 0x1p-46;
  static constexpr unsigned int max_refinement_steps = 10;

  SparseDirect();
  ~SparseDirect();
  /// Every rank of `team` factorises the same matrix, each holding it whole on MPI_COMM_SELF (the
  /// band solves and the coarse mesh-sequencing levels of several ranks): from
  /// substructured_limit unknowns on, the ranks share the work (numerics::SubstructuredLU), so
  /// factorize() and the solves are collective over `team`. MPI_COMM_SELF (the default): alone.
  void share_with(MPI_Comm team);
  MPI_Comm team_of_replicas() const { return team; }
  /// Factorise `matrix` (kept by reference until the next factorize() or clear()).
  void factorize(const dealii::TrilinosWrappers::SparseMatrix &matrix);
  /// A fill-reducing elimination order for MUMPS's analyses on one rank of matrices of
  /// position_of_row.size() rows (row i eliminated at position_of_row[i], 1-based; a
  /// permutation, checked), instead of MUMPS's AMD: the nested dissection of the built-in
  /// annulus's node grid (ReynoldsSolver::factorize). Kept across clear() until replaced; empty:
  /// AMD again. Any permutation solves the same system: MUMPS's threshold pivoting inside the
  /// fronts (CNTL(1)) keeps the factorisation stable in any order; on the JFO Jacobians neither
  /// order makes a column permutation (INFOG(23) = 0: the analysis has no values) nor delays a
  /// pivot (INFOG(13) = 0), measured at 1.05e6 dofs (doc/performance.md, Session 38).
  void set_elimination_order(std::vector<int> position_of_row);
  /// MUMPS analyses that took the given elimination order, since this object was made.
  unsigned int given_order_analyses() const { return given_order_count; }
  /// MUMPS's estimate of the operations of the elimination (RINFOG(1)) from the analysis behind
  /// the current factorisation (0 where MUMPS factorises no whole matrix: before any, KLU, a
  /// factorisation shared over a separator).
  double estimated_operations() const;
  /// x = A^-1 b with the last factorisation.
  void solve(const dealii::TrilinosWrappers::MPI::Vector &b,
             dealii::TrilinosWrappers::MPI::Vector &x);
  /// X = A^-1 X for `m` right-hand sides at once (one rank; X holds n x m values column by
  /// column, n the matrix size), in one call of the solver (MUMPS's triangular solves then work on
  /// blocks of columns). With single-precision factors (single_precision()) not refined: about
  /// kappa 2^-24 relative (solve_column_update refines its answer).
  void solve_block(std::vector<double> &X, unsigned int m);
  /// Selected entries of A^-1 with the last factorisation: values[c * rows.size() + p] =
  /// (A^-1)(rows[p], columns[c]). MUMPS's selected-entries solve (ICNTL(30)), which prunes
  /// both triangular solves to the paths of the elimination tree that the entries need, so a few
  /// thousand entries cost about one ordinary solve. One rank; false (values untouched) where the
  /// factorisation is not MUMPS's. With single-precision factors those factors' entries.
  bool inverse_entries(const std::vector<unsigned int> &rows,
                       const std::vector<unsigned int> &columns, std::vector<double> &values);
  void clear();
  bool initialized() const { return solver || mumps || single || shared; }
  /// The last factorisation is MUMPS's in single precision (single_precision_limit).
  bool single_precision() const { return single != nullptr; }
  /// Refinement steps of the solves with single-precision factors (solve(), solve_column_update),
  /// since this object was made.
  unsigned int refinement_steps() const { return refinement_count; }
  /// Single-precision factorisations given up for a double one (singular in single precision,
  /// or an answer that did not refine), since this object was made.
  unsigned int refinement_fallbacks() const { return fallback_count; }
  /// The last factorisation is shared over several ranks (numerics::SubstructuredLU); its
  /// package is MUMPS.
  bool substructured() const { return shared != nullptr; }
  /// Factorisations that reused the symbolic analysis of an earlier one.
  unsigned int numeric_only() const { return reused_symbolic; }
  /// MUMPS factorisations repeated with twice the workspace margin (its estimate from the
  /// analysis of the pattern fell short: numerical pivoting), since this object was made.
  unsigned int workspace_retries() const;
  /// "KLU", "MUMPS", "MUMPS, single precision refined" or "MUMPS, substructured" (shared over
  /// several ranks): the package of the last factorisation ("" before the first).
  const char *package_name() const { return package; }

private:
  /// MUMPS driven directly (sparse_direct.cc), in double or single precision
  template <class Real>
  class Mumps;
  std::unique_ptr<Mumps<double>> mumps;
  std::unique_ptr<Mumps<float>> single;
  unsigned int refinement_count = 0, fallback_count = 0;
  /// x = A^-1 b by the single factors refined in double; returns its backward error.
  double refined_solve(const Epetra_Vector &b, Epetra_Vector &x);
  /// The matrix `A` factorised by MUMPS in double, which then keeps its pattern.
  void factorize_in_double(const Epetra_CrsMatrix &A);
  friend LowRankSolve solve_column_update(SparseDirect &,
                                          const dealii::TrilinosWrappers::SparseMatrix &,
                                          const std::vector<unsigned int> &,
                                          const std::vector<SparseColumn> &, const double *,
                                          double *, double, double, double &, double &);
  /// The factorisation shared over several ranks (sparse_direct.cc)
  class Shared;
  std::unique_ptr<Shared> shared;
  /// The shared factorisation given up for MUMPS's of the whole matrix `A` (collective).
  void factorize_whole(const Epetra_CrsMatrix &A);
  MPI_Comm team = MPI_COMM_SELF;
  /// KLU through Amesos
  std::unique_ptr<Epetra_LinearProblem> problem;
  std::unique_ptr<Amesos_BaseSolver> solver;
  const Epetra_CrsMatrix *pattern_owner = nullptr;
  long long pattern_entries = -1;
  unsigned int reused_symbolic = 0, retried_workspace = 0;
  const char *package = "";
  std::vector<int> elimination_order; // set_elimination_order
  unsigned int given_order_count = 0;
  /// The given elimination order where it applies to an analysis of `A` (one rank, its size),
  /// else null (MUMPS orders).
  const std::vector<int> *order_for(const Epetra_CrsMatrix &A) const;
  /// MUMPS in precision `Real` with A's pattern analysed (in the given order where it applies),
  /// the analysis counted.
  template <class Real>
  std::unique_ptr<Mumps<Real>> analysed_by_mumps(const Epetra_CrsMatrix &A);
};

/// Outcome of solve_column_update.
enum class LowRankSolve
{
  solved,          // x is the solution, its backward error within the bound
  ill_conditioned, // the capacitance matrix is (nearly) singular: x not set
  inaccurate,      // the residual check failed: x not set
  too_many_columns // a shared factorisation and more than SparseDirect::max_shared_update_columns
                   // columns: not tried (the guard against its block solve), x not set
};

/// x = A1^-1 b by the Sherman-Morrison-Woodbury formula, where A1 differs from the factorised A0
/// in the columns `columns` only: A1 = A0 + U E^T, U (k sparse columns) the differences
/// A1(:, columns) - A0(:, columns), E those unit columns. With the capacitance system C = I + E^T
/// A0^-1 U and y = A0^-1 b, x = A0^-1 (b - U C^-1 E^T y). MUMPS: two solves, and E^T A0^-1 U from
/// the entries of A0^-1 in the rows `columns` and the columns where U has entries
/// (inverse_entries); KLU: one block solve for [b U] (k + 1 columns), x = y - Z C^-1 E^T y (Z =
/// A0^-1 U). det A1 = det A0 det C, so A1 is singular where C is: refused (ill_conditioned) when 1
/// / ((1 + |E^T Z|_1) |C^-1|_1), C's reciprocal condition number against the terms summed into it,
/// is below `min_rcond`. The answer is accepted only if its normwise backward error for A1 (given
/// as `matrix`), |b - A1 x|_inf /
/// (|A1|_inf |x|_inf + |b|_inf), is at most `max_backward_error` (else inaccurate). One rank; b, x:
/// the n values in order. `rcond`, `backward_error`: what was found (NaN where not computed).
/// A factorisation shared by the ranks (substructured()) takes the block path, collective over
/// its team, and is not tried beyond SparseDirect::max_shared_update_columns columns
/// (too_many_columns). With single-precision factors (SparseDirect::single_precision()) the
/// formula's answer is refined: the formula applied to A1's residual (in double), as
/// SparseDirect::solve refines, before the backward error is judged.
LowRankSolve solve_column_update(SparseDirect &lu,
                                 const dealii::TrilinosWrappers::SparseMatrix &matrix,
                                 const std::vector<unsigned int> &columns,
                                 const std::vector<SparseColumn> &U, const double *b, double *x,
                                 double min_rcond, double max_backward_error, double &rcond,
                                 double &backward_error);

/// The dofs of `seeds` (flags by global index, every dof) and their neighbours in the matrix
/// graph, `layers` times. On several ranks collective: the seeds and each layer are the union
/// over the ranks, so every rank returns the same flags.
std::vector<bool> grow_in_graph(const dealii::TrilinosWrappers::SparseMatrix &matrix,
                                const std::vector<bool> &seeds, unsigned int layers);

/// x_S = A_SS^-1 b_S on the dofs S with `subset` set (the others of x untouched): a sparse
/// factorisation of the principal submatrix (KLU or MUMPS by its size). On several ranks
/// collective (`subset` the same on every rank): every rank gathers A_SS and b_S, solves them
/// and sets its own entries of x; from SparseDirect::substructured_limit unknowns on they share
/// the factorisation (SparseDirect::share_with). Returns the factorisation's MUMPS workspace
/// retries (SparseDirect::workspace_retries; 0 for KLU).
/// `replicas`: where the matrix is whole on this rank (MPI_COMM_SELF), the ranks that each hold
/// it whole and solve the same subset (SparseDirect::share_with).
unsigned int solve_on_subset(const dealii::TrilinosWrappers::SparseMatrix &matrix,
                             const std::vector<bool> &subset,
                             const dealii::TrilinosWrappers::MPI::Vector &b,
                             dealii::TrilinosWrappers::MPI::Vector &x,
                             MPI_Comm replicas = MPI_COMM_SELF);

} // namespace sealfe
