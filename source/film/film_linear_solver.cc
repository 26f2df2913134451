#include <sealfe/film/film_linear_solver.h>
#include <sealfe/numerics/threaded_product.h>

#include <deal.II/base/mpi.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
using namespace dealii;

namespace
{
using VectorType = TrilinosWrappers::MPI::Vector;

/// The system matrix in the Krylov solvers: its products on deal.II's threads where one rank
/// holds it (numerics::threaded_product, the same bits on any number of threads), else Epetra's.
struct SystemOperator
{
  const TrilinosWrappers::SparseMatrix &matrix;
  void vmult(VectorType &dst, const VectorType &src) const
  {
    numerics::threaded_vmult(matrix, dst, src);
  }
};
} // namespace

FilmLinearSolver::Statistics &FilmLinearSolver::Statistics::operator+=(const Statistics &other)
{
  factorizations += other.factorizations;
  symbolic_reuses += other.symbolic_reuses;
  solves += other.solves;
  krylov_iterations += other.krylov_iterations;
  max_krylov_iterations = std::max(max_krylov_iterations, other.max_krylov_iterations);
  reused_preconditioners += other.reused_preconditioners;
  workspace_retries += other.workspace_retries;
  substructured_factorizations += other.substructured_factorizations;
  single_precision_factorizations += other.single_precision_factorizations;
  refinement_steps += other.refinement_steps;
  refinement_fallbacks += other.refinement_fallbacks;
  nested_dissection_analyses += other.nested_dissection_analyses;
  return *this;
}

FilmLinearSolver::Statistics FilmLinearSolver::statistics() const
{
  // the factorisation's own counts: its solves are also made by low-rank updates that go to it
  // directly (factorization())
  Statistics counted = stats;
  counted.refinement_steps = direct.refinement_steps() - refinement_steps_before;
  // (also the analyses of the solves' fallbacks to a whole or a double factorisation)
  counted.nested_dissection_analyses = direct.given_order_analyses() - given_orders_before;
  counted.refinement_fallbacks = direct.refinement_fallbacks() - refinement_fallbacks_before;
  return counted;
}

void FilmLinearSolver::reset_statistics()
{
  stats = Statistics();
  refinement_steps_before = direct.refinement_steps();
  given_orders_before = direct.given_order_analyses();
  refinement_fallbacks_before = direct.refinement_fallbacks();
}

const char *FilmLinearSolver::method_name() const
{
  switch (current_method)
  {
  case Method::direct:
    return "direct";
  case Method::cg_amg:
    return "cg-amg";
  case Method::cg_gmg:
    return "cg-gmg";
  default:
    return "gmres-amg";
  }
}

FilmLinearSolver::Method FilmLinearSolver::choose(const FilmSettings::LinearSolver choice,
                                                  const bool symmetric,
                                                  const types::global_dof_index n,
                                                  const bool multigrid_available,
                                                  const unsigned int n_ranks)
{
  // CG needs a symmetric matrix: the cavitation Newton systems never get it, whatever the
  // setting asks for.
  // `auto` factorises the nonsymmetric Newton systems at every size: GMRES with ML AMG (NSSA or
  // SA) diverged on the JFO Jacobian (33024 unknowns: residual 2e7 after 3302 iterations), whose
  // columns mix pressure-flow (P A) and void-transport (G) couplings. The geometric multigrid's
  // level operators are re-discretisations of the full film, so it preconditions only that
  // (and its linearisation); a Newton Jacobian asked for with cg-gmg is factorised like `auto`.
  using LS = FilmSettings::LinearSolver;
  if (choice == LS::direct)
    return Method::direct;
  if (choice == LS::cg_amg)
    return symmetric ? Method::cg_amg : Method::gmres_amg;
  if (!symmetric)
    return Method::direct;
  if (choice == LS::cg_gmg)
    return multigrid_available ? Method::cg_gmg : Method::cg_amg;
  // On several ranks the geometric multigrid wins at every size measured: distributed MUMPS on
  // these 2D meshes is no faster on two ranks than on one, while the multigrid's set-up, smoothing
  // and CG split (doc/performance.md, "Two ranks"). In-process on 2 ranks: 16 896 dofs 0.056 s
  // against 0.083 s direct, 66 560 dofs 0.18 against 0.30 s. The JFO coarse levels and the table
  // sweeps solve on MPI_COMM_SELF, so they count one rank and keep the direct solver.
  if (multigrid_available && n_ranks > 1)
    return Method::cg_gmg;
  if (n < direct_solver_limit)
    return Method::direct;
  return multigrid_available ? Method::cg_gmg : Method::cg_amg;
}

void FilmLinearSolver::set_multigrid(const FilmMultigrid *mg, std::function<void()> prepare_levels)
{
  multigrid = mg;
  prepare_multigrid = std::move(prepare_levels);
}

void FilmLinearSolver::clear()
{
  release_factorization();
  multigrid = nullptr; // the mesh's hierarchy goes with the mesh
  prepare_multigrid = nullptr;
}

void FilmLinearSolver::release_factorization()
{
  direct.clear();
  amg.reset();
  matrix = nullptr;
  pending = false;
  lagged = false;
}

void FilmLinearSolver::prepare(const TrilinosWrappers::SparseMatrix &matrix_in,
                               const bool symmetric_in, const FilmSettings::LinearSolver choice,
                               const unsigned int degree_in, const double tolerance_in,
                               const std::vector<double> &x, const std::vector<double> &y,
                               const bool allow_reuse, const bool deferred)
{
  const Method method = choose(choice, symmetric_in, matrix_in.m(), multigrid != nullptr,
                               Utilities::MPI::n_mpi_processes(matrix_in.get_mpi_communicator()));
  // Only an AMG hierarchy is worth keeping: the Fischer-Burmeister Jacobians change at every
  // cavitated node between Newton steps, so an old KLU factorisation made GMRES fail its
  // iteration limit in 6 of 7 steps (measured), while an AMG hierarchy of a similar matrix stays
  // a good preconditioner.
  const bool can_reuse = allow_reuse && method == Method::gmres_amg && !symmetric &&
                         method == current_method && matrix == &matrix_in && amg;
  matrix = &matrix_in;
  symmetric = symmetric_in;
  current_method = method;
  degree = degree_in;
  tolerance = tolerance_in;
  support_x = &x;
  support_y = &y;
  pending = false;
  if (can_reuse)
  {
    lagged = true;
    return;
  }
  if (deferred)
  {
    pending = true;
    return;
  }
  build_preconditioner();
}

void FilmLinearSolver::build_preconditioner()
{
  // One factorisation (or AMG hierarchy) per matrix, reused by the solve and by every linearised
  // solve of the dynamic coefficients.
  lagged = false;
  pending = false;
  ++stats.factorizations;
  if (current_method == Method::direct)
  {
    // KLU keeps its ordering while the matrix keeps its pattern (the Newton Jacobians of a
    // cavitation solve are assembled into one matrix).
    amg.reset();
    const unsigned int before = direct.numeric_only(), retries_before = direct.workspace_retries();
    direct.factorize(*matrix);
    stats.symbolic_reuses += direct.numeric_only() - before;
    stats.workspace_retries += direct.workspace_retries() - retries_before;
    stats.substructured_factorizations += direct.substructured();
    stats.single_precision_factorizations += direct.single_precision();
    return;
  }
  direct.clear();
  amg.reset();
  if (current_method == Method::cg_gmg)
  {
    prepare_multigrid();
    return;
  }
  // Smoothed aggregation. The cells of the annulus are long and thin (a dam ~45 times narrower
  // than its circumference), so the matrix couples a node far more strongly to its radial
  // neighbours than to its circumferential ones. ML's default aggregation on the matrix does
  // not see that through the higher-order stencils (170-470 CG iterations at Ntheta/Nr = 2,
  // doc/performance.md); aggregating on the distance Laplacian of the support points, with the
  // weak (long) connections dropped, makes the aggregates follow the short direction (a
  // semi-coarsening), and the smoother (below) then damps what remains. Measured:
  // 20-31 CG iterations for degrees 1-3, aspect Ntheta/Nr 1-32, 3e4-1e6 unknowns.
  TrilinosWrappers::PreconditionAMG::AdditionalData data;
  data.elliptic = symmetric;
  data.higher_order_elements = degree > 1;
  // Symmetric (CG) systems: Chebyshev of degree 3 (matrix-vector products only) instead of
  // 2 symmetric Gauss-Seidel sweeps. Measured at 1.05e6 Q2 dofs (128 x 2048): 30 instead of 28
  // CG iterations, CG time 2.5-2.7 s instead of 4.1-4.9 s; at 5.3e5 (256 x 512) 29 instead of 26,
  // 1.3 s instead of 2.1 s (doc/performance.md). Gauss-Seidel stays for the nonsymmetric systems.
  data.smoother_sweeps = symmetric ? 3 : 2;
  data.aggregation_threshold = 0.02;
  data.smoother_type = symmetric ? "Chebyshev" : "symmetric Gauss-Seidel";
  Teuchos::ParameterList list;
  std::unique_ptr<Epetra_MultiVector> constant_modes;
  data.set_parameters(list, constant_modes, *matrix);
  list.set("aggregation: aux: enable", true);
  list.set("aggregation: aux: threshold", 0.05);
  list.set("x-coordinates", const_cast<double *>(support_x->data()));
  list.set("y-coordinates", const_cast<double *>(support_y->data()));
  amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
  amg->initialize(*matrix, list);
}

unsigned int FilmLinearSolver::krylov_solve(const VectorType &rhs, VectorType &x,
                                            const unsigned int max_iterations,
                                            const bool throw_on_failure)
{
  const double target = std::max(tolerance * rhs.l2_norm(), std::numeric_limits<double>::min());
  SolverControl control(max_iterations, target, false, false);
  try
  {
    const SystemOperator system{*matrix};
    if (current_method == Method::cg_gmg)
      SolverCG<VectorType>(control).solve(system, x, rhs, *multigrid);
    else if (current_method == Method::cg_amg && !lagged)
      SolverCG<VectorType>(control).solve(system, x, rhs, *amg);
    else
    {
      // Right preconditioning: the tolerance applies to the true residual.
      SolverGMRES<VectorType>::AdditionalData gmres_data(50, true);
      SolverGMRES<VectorType> gmres(control, gmres_data);
      gmres.solve(system, x, rhs, *amg);
    }
  }
  catch (SolverControl::NoConvergence &e)
  {
    stats.krylov_iterations += e.last_step;
    if (!throw_on_failure)
      return std::numeric_limits<unsigned int>::max();
    std::ostringstream s;
    s << "Reynolds solver: " << method_name() << " did not converge in " << e.last_step
      << " iterations (residual " << e.last_residual << ", target " << target
      << "); try 'set Linear solver = direct'";
    throw std::runtime_error(s.str());
  }
  stats.krylov_iterations += control.last_step();
  stats.max_krylov_iterations = std::max(stats.max_krylov_iterations, control.last_step());
  return control.last_step();
}

unsigned int FilmLinearSolver::solve(const VectorType &rhs, VectorType &x)
{
  if (!matrix)
    throw std::logic_error("FilmLinearSolver: solve() without a prepared matrix");
  ++stats.solves;
  if (pending)
    build_preconditioner();
  if (lagged)
  {
    // A preconditioner of an earlier matrix: a few GMRES iterations, else rebuild it.
    VectorType start(x);
    const unsigned int its = krylov_solve(rhs, x, lagged_iteration_limit, false);
    if (its != std::numeric_limits<unsigned int>::max())
    {
      ++stats.reused_preconditioners;
      return its;
    }
    x = start;
    build_preconditioner();
  }
  if (current_method == Method::direct)
  {
    direct.solve(rhs, x);
    return 1;
  }
  if (current_method == Method::gmres_amg)
  {
    // Asked for explicitly (`cg-amg` with a cavitation model): GMRES + AMG, and the KLU
    // factorisation if that does not converge, so that every size gets an answer.
    VectorType start(x);
    const unsigned int its = krylov_solve(rhs, x, gmres_iteration_limit, false);
    if (its != std::numeric_limits<unsigned int>::max())
      return its;
    x = start;
    current_method = Method::direct;
    build_preconditioner();
    direct.solve(rhs, x);
    return 1;
  }
  return krylov_solve(rhs, x, std::max<unsigned int>(1000, matrix->m() / 10), true);
}

} // namespace sealfe
