// FilmLinearSolver: the linear solves of the film's discrete Reynolds systems (full film, the
// linearised coefficient solves, the Newton steps of the cavitation models), with one Trilinos
// back-end: sparse direct (Amesos KLU or MUMPS, sparse_direct.h) below a size, Krylov +
// multigrid above.
#pragma once

#include <sealfe/film/film_multigrid.h>
#include <sealfe/film/film_settings.h>
#include <sealfe/film/sparse_direct.h>

#include <deal.II/base/point.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace sealfe
{
/// Solves A x = b for the matrices of ReynoldsSolver. Four methods:
///  - direct: sparse LU factorisation (KLU below 2e4 unknowns, MUMPS above: sparse_direct.h);
///  - cg-gmg (symmetric A on the built-in annulus): CG + geometric multigrid on the levels of the
///    mesh (film_multigrid.h), whose level operators the owner rebuilds for each matrix;
///  - cg-amg (symmetric A: full film, linearised full film): CG + smoothed-aggregation AMG whose
///    aggregates are built on the distance Laplacian of the dof support points (ML "aux"
///    aggregation), so they follow the short direction of the long, thin cells of the annulus;
///  - gmres-amg (nonsymmetric A: the cavitation Newton systems, only with `Linear solver =
///    cg-amg`): GMRES with the same AMG, falling back to KLU when it does not converge. `auto`
///    factorises nonsymmetric systems at every size (CG is never used on them).
/// A sequence of nonsymmetric systems with one sparsity pattern (Newton iterations) solved by
/// gmres-amg keeps the AMG hierarchy of an earlier matrix as long as GMRES converges in
/// lagged_iteration_limit iterations with it. Every solve reaches the relative residual
/// tolerance, so the answers are those of a fresh preconditioner to that tolerance.
class FilmLinearSolver
{
public:
  enum class Method
  {
    direct,
    cg_amg,
    gmres_amg,
    cg_gmg
  };
  /// Work counted since construction (summary.json: linear_solver).
  struct Statistics
  {
    unsigned int factorizations = 0;  // KLU factorisations or AMG set-ups
    unsigned int symbolic_reuses = 0; // KLU factorisations that reused the ordering
    unsigned int solves = 0;
    unsigned int krylov_iterations = 0; // CG or GMRES iterations, all solves
    unsigned int max_krylov_iterations = 0;
    unsigned int reused_preconditioners = 0; // solves with an earlier matrix's factorisation
    unsigned int workspace_retries = 0; // MUMPS factorisations repeated with a larger workspace
    unsigned int substructured_factorizations = 0; // of the factorisations, those shared by ranks
    // of the factorisations, those in single precision with refined solves (SparseDirect::
    // single_precision_limit); the refinement steps of all solves; the single factorisations
    // given up for a double one
    unsigned int single_precision_factorizations = 0;
    unsigned int refinement_steps = 0;
    unsigned int refinement_fallbacks = 0;
    // MUMPS analyses in the given elimination order (set_elimination_order), not MUMPS's AMD
    unsigned int nested_dissection_analyses = 0;

    /// The work of several runs together: counts add, the largest Krylov count is the larger.
    Statistics &operator+=(const Statistics &other);
  };

  /// Below this many unknowns `auto` factorises symmetric systems on one rank (and on several
  /// without a mesh hierarchy); above it Krylov + multigrid.
  static constexpr unsigned int direct_solver_limit = 150000;
  /// A lagged preconditioner is rebuilt when GMRES needs more than this.
  static constexpr unsigned int lagged_iteration_limit = 60;
  /// gmres-amg falls back to KLU after this many iterations.
  static constexpr unsigned int gmres_iteration_limit = 200;

  /// The method `choice` gives for a matrix of `n` unknowns distributed over `n_ranks` MPI
  /// ranks: `auto` factorises every nonsymmetric matrix; a symmetric one gets cg-gmg where the
  /// mesh has a level hierarchy (`multigrid_available`) above direct_solver_limit on one rank and
  /// at every size on several ranks (where distributed MUMPS does not gain); without a hierarchy,
  /// direct below direct_solver_limit and cg-amg above, whatever the rank count.
  static Method choose(FilmSettings::LinearSolver choice, bool symmetric,
                       dealii::types::global_dof_index n, bool multigrid_available,
                       unsigned int n_ranks);
  /// The geometric multigrid of the mesh and the function that rebuilds its level operators for
  /// the prepared matrix (called where a factorisation would be). Null: no hierarchy.
  void set_multigrid(const FilmMultigrid *multigrid, std::function<void()> prepare_levels);

  /// Prepare to solve with `matrix` (kept by reference until the next prepare()). `support_x`,
  /// `support_y`: coordinates of the locally owned dofs (only used by the AMG methods).
  /// `allow_reuse`: the matrix is the next of a sequence with the same pattern (Newton).
  /// `deferred`: factorise at the first solve() only (a matrix that may never be solved with,
  /// such as the Jacobian at a JFO solution, which only the linearised loads use).
  void prepare(const dealii::TrilinosWrappers::SparseMatrix &matrix, bool symmetric,
               FilmSettings::LinearSolver choice, unsigned int degree, double tolerance,
               const std::vector<double> &support_x, const std::vector<double> &support_y,
               bool allow_reuse = false, bool deferred = false);
  /// Solve the prepared system; returns the Krylov iterations (1 for a direct solve). Throws
  /// std::runtime_error if the iteration does not converge.
  unsigned int solve(const dealii::TrilinosWrappers::MPI::Vector &rhs,
                     dealii::TrilinosWrappers::MPI::Vector &x);
  /// The ranks that each hold this solver's matrices whole and factorise them together
  /// (SparseDirect::share_with): the coarse mesh-sequencing levels of several ranks.
  void share_direct_with(MPI_Comm team)
  {
    // (another team: the factorisation is dropped, and with it the prepared matrix)
    if (team != direct.team_of_replicas())
      release_factorization();
    direct.share_with(team);
  }
  MPI_Comm direct_team() const { return direct.team_of_replicas(); }
  /// The elimination order of the direct factorisations of this mesh's matrices
  /// (SparseDirect::set_elimination_order: the nested dissection of the built-in annulus's
  /// node grid); empty: MUMPS's AMD. Kept until replaced.
  void set_elimination_order(std::vector<int> position_of_row)
  {
    direct.set_elimination_order(std::move(position_of_row));
  }
  /// Forget the factorisation (new mesh).
  void clear();
  /// Free the factorisation (or AMG hierarchy) of the prepared matrix and keep the rest (the
  /// mesh's multigrid, the statistics): a coarse level whose solution has been taken gives its
  /// memory back before the finer level factorises. The next prepare() analyses the pattern again.
  void release_factorization();

  Method method() const { return current_method; }
  const char *method_name() const;
  /// The sparse direct package of the last factorisation, "KLU", "MUMPS" or "MUMPS,
  /// substructured" (shared over several ranks) ("" if none).
  const char *direct_package() const { return direct.package_name(); }
  /// The factorisation of the last prepared matrix when it is a direct one and done (not
  /// deferred): the cavitation models' low-rank updates solve with it. Null otherwise.
  SparseDirect *factorization()
  {
    return current_method == Method::direct && !pending && direct.initialized() ? &direct : nullptr;
  }
  /// (the refinement counts include those of low-rank updates on factorization())
  Statistics statistics() const;
  void reset_statistics();

private:
  void build_preconditioner();
  unsigned int krylov_solve(const dealii::TrilinosWrappers::MPI::Vector &rhs,
                            dealii::TrilinosWrappers::MPI::Vector &x, unsigned int max_iterations,
                            bool throw_on_failure);

  const dealii::TrilinosWrappers::SparseMatrix *matrix = nullptr;
  Method current_method = Method::direct;
  bool symmetric = true;
  bool lagged = false;  // the preconditioner belongs to an earlier matrix
  bool pending = false; // prepared with `deferred`: not factorised yet
  unsigned int degree = 1;
  double tolerance = 1e-12;
  const std::vector<double> *support_x = nullptr, *support_y = nullptr;
  SparseDirect direct;
  std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG> amg;
  const FilmMultigrid *multigrid = nullptr;
  std::function<void()> prepare_multigrid;
  Statistics stats;
  unsigned int refinement_steps_before = 0, refinement_fallbacks_before = 0; // direct's, at reset
  unsigned int given_orders_before = 0;                                      // direct's, at reset
};

} // namespace sealfe
