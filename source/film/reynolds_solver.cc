#include <sealfe/film/cell_sparsity.h>
#include <sealfe/film/film_output.h>
#include <sealfe/film/jfo_solver.h>
#include <sealfe/film/lap_timer.h>
#include <sealfe/film/polar_cell_values.h>
#include <sealfe/film/polar_node_grid.h>
#include <sealfe/film/reynolds_cavitation_solver.h>
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/film/round_off.h>
#include <sealfe/film/surface_features.h>
#include <sealfe/numerics/ordered_batches.h>

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/thread_local_storage.h>
#include <deal.II/base/thread_management.h>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q_cache.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>
#include <deal.II/numerics/vector_tools.h>
#include <deal.II/numerics/vector_tools_evaluate.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <fstream>
#include <future>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>

namespace sealfe
{
using namespace dealii;

namespace
{
/// The levels of the globally refined annulus are the geometric multigrid's hierarchy: p4est
/// keeps them on several ranks, a serial triangulation always has them.
std::unique_ptr<Triangulation<2>> make_film_triangulation(const MPI_Comm comm)
{
  if (Utilities::MPI::n_mpi_processes(comm) == 1)
    return std::make_unique<Triangulation<2>>(Triangulation<2>::limit_level_difference_at_vertices);
  return std::make_unique<parallel::distributed::Triangulation<2>>(
      comm, Triangulation<2>::limit_level_difference_at_vertices,
      parallel::distributed::Triangulation<2>::construct_multigrid_hierarchy);
}
} // namespace

ReynoldsSolver::ReynoldsSolver(MPI_Comm comm) : ReynoldsSolver(FilmSettings(), comm) {}

ReynoldsSolver::ReynoldsSolver(const FilmSettings &settings_in, MPI_Comm comm)
    : settings(settings_in), mpi_communicator(comm),
      triangulation_storage(make_film_triangulation(comm)), triangulation(*triangulation_storage),
      dof_handler(triangulation), timer(std::cerr, TimerOutput::never, TimerOutput::wall_times)
{
}

ReynoldsSolver::~ReynoldsSolver() = default;

void ReynoldsSolver::declare_parameters(ParameterHandler &prm)
{
  FilmSettings::declare_solver_parameters(prm);
}

void ReynoldsSolver::parse_parameters(ParameterHandler &prm)
{
  settings.parse_solver_parameters(prm);
}

void ReynoldsSolver::setup_system(const unsigned int coarsening)
{
  TimerOutput::Scope t(timer, "setup");
  if (same_mesh_as_set_up(coarsening))
  {
    // Same mesh and dofs: only the Dirichlet data (boundary pressures) may have changed. (The
    // matrix and right-hand side are made from zero by whoever fills them: assemble_system,
    // full_film_flow_scale or add_to_full_film_rhs, the cavitation models.)
    setup_constraints();
    return;
  }
  clear_for_new_mesh();
  setup_mesh_and_dofs(coarsening, Utilities::MPI::n_mpi_processes(mpi_communicator));
  setup_linear_algebra(coarsening);
}

bool ReynoldsSolver::same_mesh_as_set_up(const unsigned int coarsening) const
{
  return setup_settings &&
         settings.same_discretization(*setup_settings, coarsening, setup_coarsening);
}

void ReynoldsSolver::clear_for_new_mesh()
{
  dof_handler.clear();
  triangulation.clear();
  linear_system_solver.clear();
  linear_system_solver.set_elimination_order({});
  elimination_order_tried = false;
  multigrid.clear();
  amg_support_x.clear();
  amg_support_y.clear();
  // Grading from C0 and coning only, so that perturbing z or the tilts (finite-difference
  // coefficients, transients) keeps the same mesh.
  mesh_parameters.grading_clearance = film.clearance;
  mesh_parameters.grading_coning = film.coning;
  mesh_parameters.alignment =
      film.features ? film.features->mesh_alignment() : AnnulusMesh::Alignment();
}

void ReynoldsSolver::setup_mesh_and_dofs(const unsigned int coarsening, const unsigned int n_ranks)
{
  // (no MPI call on one rank with the built-in mesh: setup_while_coarse_levels_run runs this on
  // a thread of its own)
  LapTimer lap(setup_detail);
  mesh_parameters.create(triangulation, film.inner_radius, film.outer_radius, coarsening);
  lap("setup: mesh");

  fe = std::make_unique<FE_Q<2>>(polynomial_degree);
  // The mapping's support points come from the polar manifold (a pull-back and push-forward per
  // point): computed once per mesh and shared by the assembly, the loads, the support points of
  // the AMG and the field output, instead of once per cell in each of them. The same points as
  // MappingQ's, so the same geometry.
  auto cached = std::make_unique<MappingQCache<2>>(settings.mapping_degree());
  cached->initialize(MappingQ<2>(settings.mapping_degree()), triangulation);
  mapping = std::move(cached);
  lap("setup: mapping cache");
  dof_handler.distribute_dofs(*fe);
  lap("setup: dofs");
  // The geometric multigrid's line smoother wants the dofs numbered by radial lines.
  if (FilmLinearSolver::choose(linear_solver, true, dof_handler.n_dofs(),
                               mesh_parameters.mesh_file.empty() &&
                                   FilmMultigrid::has_hierarchy(dof_handler),
                               n_ranks) == FilmLinearSolver::Method::cg_gmg)
    multigrid.number_by_radial_lines(dof_handler, *mapping);
  lap("setup: numbering by lines");

  locally_owned_dofs = dof_handler.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dof_handler, locally_relevant_dofs);

  // Zero Dirichlet data: the constraints of every correction and perturbation (Newton steps of
  // the cavitation models, linearised solves of the coefficients).
  homogeneous_constraints.clear();
  homogeneous_constraints.reinit(locally_relevant_dofs);
  DoFTools::make_hanging_node_constraints(dof_handler, homogeneous_constraints);
  for (const auto id : {AnnulusMesh::inner_boundary, AnnulusMesh::outer_boundary})
    VectorTools::interpolate_boundary_values(*mapping, dof_handler, id,
                                             Functions::ZeroFunction<2>(), homogeneous_constraints);
  homogeneous_constraints.close();

  // Dofs on each circle, for the consistent boundary fluxes (leakages).
  DoFTools::extract_boundary_dofs(dof_handler, ComponentMask(), inner_boundary_dofs,
                                  {AnnulusMesh::inner_boundary});
  DoFTools::extract_boundary_dofs(dof_handler, ComponentMask(), outer_boundary_dofs,
                                  {AnnulusMesh::outer_boundary});

  lap("setup: index sets, zero constraints, boundary dofs");
}

void ReynoldsSolver::setup_linear_algebra(const unsigned int coarsening)
{
  LapTimer lap(setup_detail);
  locally_relevant_solution.reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
  system_rhs.reinit(locally_owned_dofs, mpi_communicator);
  lap("setup: vectors");
  // The constrained dofs are the same with any Dirichlet data: one sparsity pattern per mesh.
  // Dirichlet constraints only (no hanging nodes) and one owned range per rank
  // (CellSparsity::applies): the same pattern from the cells' dofs by local index, and the
  // assembly adds the cells without constrained dofs by position; else deal.II's generic path.
  matrix_by_position =
      CellSparsity::applies(locally_owned_dofs, homogeneous_constraints, mpi_communicator);
  if (matrix_by_position)
  {
    const unsigned int n = fe->n_dofs_per_cell();
    const std::vector<unsigned int> cell_dofs = CellSparsity::active_cell_dofs(dof_handler);
    lap("setup: sparsity");
    CellSparsity::reinit(system_matrix, locally_owned_dofs, cell_dofs, n, homogeneous_constraints,
                         false, mpi_communicator);
    lap("setup: matrix");
  }
  else
  {
    DynamicSparsityPattern dsp(locally_relevant_dofs);
    DoFTools::make_sparsity_pattern(dof_handler, dsp, homogeneous_constraints, false);
    SparsityTools::distribute_sparsity_pattern(dsp, locally_owned_dofs, mpi_communicator,
                                               locally_relevant_dofs);
    lap("setup: sparsity");
    system_matrix.reinit(locally_owned_dofs, locally_owned_dofs, dsp, mpi_communicator);
    lap("setup: matrix");
  }
  setup_constraints();
  lap("setup: constraints");

  setup_settings = std::make_unique<FilmSettings>(settings);
  setup_coarsening = coarsening;
  ++setup_count;
}

void ReynoldsSolver::setup_while_coarse_levels_run(const unsigned int coarsening)
{
  const AnnulusMesh &m = mesh_parameters;
  if (Utilities::MPI::n_mpi_processes(mpi_communicator) != 1 || !m.mesh_file.empty() ||
      m.mesh_size > 0 || same_mesh_as_set_up(coarsening))
  {
    setup_system(coarsening);
    return;
  }
  clear_for_new_mesh(); // (the grading and alignment that sequences_jfo reads)
  // coarse_level_state's own test (more than 200 dofs) by the cells: a ring of nr x nt cells
  // has more dofs than cells
  const unsigned int next = coarsening + 1;
  const unsigned long long cells =
      coarsening <= m.global_refinements
          ? (1ull << 2 * (m.global_refinements - coarsening)) * m.radial_cells *
                m.circumferential_cells
          : (m.radial_cells >> (coarsening - m.global_refinements)) *
                static_cast<unsigned long long>(m.circumferential_cells >>
                                                (coarsening - m.global_refinements));
  if (cells <= 200 || !m.can_coarsen(next) ||
      !m.sequences_jfo(next, film.inner_radius, film.outer_radius))
  {
    setup_system(coarsening); // (its clear_for_new_mesh finds the objects cleared)
    return;
  }
  // This level's mesh, mapping, dofs, zero constraints and the nested dissection of its node
  // grid (from the cells' dofs: the matrix is made after) on a thread of their own, while this
  // thread solves the coarse levels: those touch nothing of this level, and their MUMPS
  // factorisations run on one core. The thread makes no MPI call (one rank, deal.II's serial
  // mesh); the vectors and the matrix (Trilinos, MPI) are made here after it. Tilted seal, JFO
  // at 1.05e6 dofs: the setup stage 0.99-1.30 -> 0.17-0.30 s (doc/performance.md "Session 40").
  struct MadeAhead
  {
    std::vector<Point<2>> support;
    std::vector<int> order;
    bool ordered = false;
  };
  std::future<MadeAhead> made = std::async(
      std::launch::async,
      [this, coarsening]()
      {
        setup_mesh_and_dofs(coarsening, 1);
        MadeAhead ahead;
        ahead.support = owned_support_points();
        // (factorize's wants_nested_dissection, whose other conditions hold here)
        ahead.ordered =
            !elimination_order_tried && dof_handler.n_dofs() >= SparseDirect::multifrontal_limit &&
            FilmLinearSolver::choose(linear_solver, false, dof_handler.n_dofs(), false, 1) ==
                FilmLinearSolver::Method::direct;
        if (ahead.ordered)
          ahead.order = polar_nested_dissection(ahead.support, polynomial_degree,
                                                CellSparsity::active_cell_dofs(dof_handler),
                                                fe->n_dofs_per_cell());
        return ahead;
      });
  solve_coarse_level(nullptr); // (run() has set current_coarsening)
  coarse_level_solved_ahead = true;
  // (the stage's time is the wait for the thread and the linear algebra: what the setup costs
  // the run)
  TimerOutput::Scope t(timer, "setup");
  MadeAhead ahead = made.get();
  setup_linear_algebra(coarsening);
  // the cells' order holds for a matrix of the cells' couplings (CellSparsity's pattern)
  if (ahead.ordered && matrix_by_position)
  {
    linear_system_solver.set_elimination_order(std::move(ahead.order));
    elimination_order_tried = true;
  }
  support_made_ahead = std::move(ahead.support);
}

void ReynoldsSolver::setup_constraints()
{
  // The Dirichlet data p = pi, po (or the test hook's) on the two circles.
  constraints.clear();
  constraints.reinit(locally_relevant_dofs);
  DoFTools::make_hanging_node_constraints(dof_handler, constraints);
  if (boundary_pressure)
  {
    const ScalarFunctionFromFunctionObject<2> g(boundary_pressure);
    for (const auto id : {AnnulusMesh::inner_boundary, AnnulusMesh::outer_boundary})
      VectorTools::interpolate_boundary_values(*mapping, dof_handler, id, g, constraints);
  }
  else
  {
    VectorTools::interpolate_boundary_values(
        *mapping, dof_handler, AnnulusMesh::inner_boundary,
        Functions::ConstantFunction<2>(conditions.inner_pressure), constraints);
    VectorTools::interpolate_boundary_values(
        *mapping, dof_handler, AnnulusMesh::outer_boundary,
        Functions::ConstantFunction<2>(conditions.outer_pressure), constraints);
  }
  constraints.close();
}

void ReynoldsSolver::assemble_system()
{
  TimerOutput::Scope t(timer, "assemble");
  // from zero: the matrix and right-hand side may hold another system (a repeated run on the same
  // mesh, or the cavitation models' flow scale and Jacobians)
  system_matrix = 0;
  system_rhs = 0;
  // h is not polynomial in x, y (cos theta, r): one Gauss point more than the element needs. The
  // load/residual integration uses the same rule, so that the interior residuals vanish to solver
  // tolerance and the leakages balance.
  const QGauss<2> quadrature(polynomial_degree + 2);
  const unsigned int dofs_per_cell = fe->n_dofs_per_cell();
  // Full film: the loads' parts at p = 0 and their weights in p at the same points
  // (AffineLoadSums), so that compute_loads() does not evaluate the film everywhere again.
  const LoadIntegrator load_integrator(*this);
  const bool gather = load_integrator.affine_applies();
  affine_loads.reset(gather, locally_relevant_dofs.n_elements(), dofs_per_cell);
  const unsigned int n_sums = affine_loads.constant.size(), n_q = quadrature.size();
  // The built-in annulus: every cell of a radial row is the row's first cell turned about the
  // axis, so its geometry comes from one FEValues evaluation per row (PolarCellValues; a cell
  // that is not such a rotation takes FEValues). The rows are found here, in the order of the
  // cells, so that every thread below turns the same first cell of each row.
  std::optional<PolarCellValues> polar;
  if (assembles_on_polar_rows())
    polar.emplace(*mapping, *fe, quadrature);
  const std::vector<DoFHandler<2>::active_cell_iterator> cells =
      owned_cells_finding_rows(dof_handler, polar);
  // the threads' lookups (index_within_set) in a compressed set: IndexSet::compress, which a
  // lookup calls, writes the set
  locally_relevant_dofs.compress();

  // Batches of cells: their cell matrices, right-hand sides and load parts computed on deal.II's
  // threads (each thread with its own FEValues and copy of the rows), and added to the system in
  // the order of the cells on one thread, while the next batch is computed (the same sums in
  // the same order as one loop over the cells: the same bits on any number of threads).
  struct CellTerms
  {
    FullMatrix<double> matrix;
    Vector<double> rhs;
    std::vector<types::global_dof_index> dofs;
    std::vector<unsigned int> relevant; // dofs' positions in locally_relevant_dofs (gather)
    std::vector<double> point_sums;     // [q n_sums + m]: point q's part of affine_loads.constant
    std::vector<double> weight;         // the cell's part of affine_loads.weight
  };
  struct Scratch
  {
    FEValues<2> fe_values;
    std::optional<PolarCellValues> polar;
    FullMatrix<double> unused;
    AffineLoadSums sums; // one point's constant sums, the cell's weights
    CellTerms *terms = nullptr;
    std::function<void(unsigned int, const LocalFilm &)> at_point, at_polar_point;
  };
  constexpr std::size_t batch_size = 1024;
  std::array<std::vector<CellTerms>, 2> batches;
  for (auto &batch : batches)
  {
    batch.resize(std::min(batch_size, cells.size()));
    for (CellTerms &terms : batch)
    {
      terms.matrix.reinit(dofs_per_cell, dofs_per_cell);
      terms.rhs.reinit(dofs_per_cell);
      terms.dofs.resize(dofs_per_cell);
      if (gather)
      {
        terms.relevant.resize(dofs_per_cell);
        terms.point_sums.resize(std::size_t(n_q) * n_sums);
        terms.weight.resize(std::size_t(AffineLoadSums::n_linear) * dofs_per_cell);
      }
    }
  }
  Threads::ThreadLocalStorage<std::unique_ptr<Scratch>> scratch;
  auto new_scratch = [&]()
  {
    // FEValues can be neither copied nor moved: the aggregate is made in place
    std::unique_ptr<Scratch> w(
        new Scratch{FEValues<2>(*mapping, *fe, quadrature,
                                update_values | update_gradients | update_quadrature_points |
                                    update_JxW_values),
                    polar, FullMatrix<double>(dofs_per_cell, dofs_per_cell), AffineLoadSums()});
    w->sums.reset(gather, 0, dofs_per_cell);
    if (gather)
    {
      Scratch *p = w.get();
      // each point's sums alone (each sum takes one term per point), added in order below
      auto keep = [p, n_sums](const unsigned int q)
      {
        std::copy(p->sums.constant.begin(), p->sums.constant.end(),
                  p->terms->point_sums.begin() + std::size_t(q) * n_sums);
        std::fill(p->sums.constant.begin(), p->sums.constant.end(), 0.0);
      };
      p->at_point = [p, keep, &load_integrator](const unsigned int q, const LocalFilm &f)
      {
        load_integrator.add_affine_point(p->sums, p->fe_values, q, f);
        keep(q);
      };
      p->at_polar_point = [p, keep, &load_integrator](const unsigned int q, const LocalFilm &f)
      {
        load_integrator.add_affine_point(p->sums, *p->polar, q, f);
        keep(q);
      };
    }
    return w;
  };
  auto compute = [&](std::vector<CellTerms> &batch, const std::size_t first_cell,
                     const std::size_t first, const std::size_t last)
  {
    std::unique_ptr<Scratch> &own = scratch.get();
    if (!own)
      own = new_scratch();
    Scratch &w = *own;
    for (std::size_t c = first; c < last; ++c)
    {
      CellTerms &terms = batch[c];
      w.terms = &terms;
      const auto &cell = cells[first_cell + c];
      cell->get_dof_indices(terms.dofs);
      // the full-film pressure matrix and Couette + squeeze right-hand side
      cell_film_matrices(w.polar, w.fe_values, cell, false, terms.matrix, w.unused, terms.rhs,
                         w.at_point, w.at_polar_point);
      if (gather)
      {
        // here, not where the batch is added on one thread (IndexSet's lookups are const)
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          terms.relevant[i] = locally_relevant_dofs.index_within_set(terms.dofs[i]);
        std::copy(w.sums.cell_weight.begin(), w.sums.cell_weight.end(), terms.weight.begin());
        std::fill(w.sums.cell_weight.begin(), w.sums.cell_weight.end(), 0.0);
      }
    }
  };
  // The matrix has CellSparsity's pattern where it applies (matrix_by_position, setup_system),
  // and the cells without constrained dofs are added by position.
  auto add = [&](const std::vector<CellTerms> &batch, std::size_t, const std::size_t n)
  {
    for (std::size_t c = 0; c < n; ++c)
    {
      const CellTerms &terms = batch[c];
      if (gather)
      {
        for (unsigned int q = 0; q < n_q; ++q)
          for (unsigned int m = 0; m < n_sums; ++m)
            affine_loads.constant[m] += terms.point_sums[std::size_t(q) * n_sums + m];
        std::copy(terms.weight.begin(), terms.weight.end(), affine_loads.cell_weight.begin());
        affine_loads.add_cell(terms.relevant);
      }
      // a cell without constrained dofs: the same sums as distribute_local_to_global, the
      // owned rows by position
      CellSparsity::distribute(constraints, matrix_by_position, terms.matrix, terms.rhs, terms.dofs,
                               system_matrix, system_rhs);
    }
  };
  try
  {
    numerics::compute_in_batches_add_in_order(cells.size(), batch_size, batches, 32, compute, add);
  }
  catch (...)
  {
    affine_loads.reset(false, 0, 0); // partial sums: neither valid nor kept
    throw;
  }
  // only now complete (a throw from local_film above leaves them invalid)
  affine_loads.valid = gather;
  system_matrix.compress(VectorOperation::add);
  system_rhs.compress(VectorOperation::add);
}

double ReynoldsSolver::full_film_flow_scale(const std::vector<FullMatrix<double>> &A,
                                            const std::vector<Vector<double>> &F)
{
  TimerOutput::Scope t(timer, "assemble");
  system_rhs = 0;
  std::vector<types::global_dof_index> dofs(fe->n_dofs_per_cell());
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      const auto k = cell->active_cell_index();
      cell->get_dof_indices(dofs);
      add_to_full_film_rhs(A[k], F[k], dofs);
    }
  return flow_scale_of_full_film_rhs();
}

void ReynoldsSolver::add_to_full_film_rhs(const FullMatrix<double> &A, const Vector<double> &F,
                                          const std::vector<types::global_dof_index> &dofs)
{
  // The Couette + squeeze + pressure flow right-hand side of the full film, as assemble_system()
  // adds it: a cell without constrained dofs adds its F (by position where the matrix has
  // CellSparsity's pattern), the others go through the constraints with their A (the Dirichlet
  // values' columns, and the diagonal of the constrained rows); that distribution adds those
  // cells' terms to system_matrix too: called before the cavitation models make their matrices,
  // which replace its values (after the full-film start's solve at most, whose factorisation is
  // made; never after a cavitation solve, when it holds the Jacobian at the solution).
  if (!CellSparsity::unconstrained(constraints, dofs))
    constraints.distribute_local_to_global(A, F, dofs, system_matrix, system_rhs);
  else if (matrix_by_position)
    CellSparsity::add(system_rhs, F, dofs);
  else
    constraints.distribute_local_to_global(F, dofs, system_rhs);
}

double ReynoldsSolver::flow_scale_of_full_film_rhs()
{
  system_matrix.compress(VectorOperation::add);
  system_rhs.compress(VectorOperation::add);
  return std::max(system_rhs.l2_norm(), 1e-300);
}

void ReynoldsSolver::factorize(const bool symmetric, const bool newton_sequence,
                               const bool deferred)
{
  TimerOutput::Scope t(timer, "linear solver setup");
  // Geometric multigrid on the levels of the built-in annulus (a mesh file has no hierarchy):
  // set up once per mesh, its level operators rebuilt for each full-film matrix.
  const bool hierarchy =
      mesh_parameters.mesh_file.empty() && symmetric && FilmMultigrid::has_hierarchy(dof_handler);
  const auto method =
      FilmLinearSolver::choose(linear_solver, symmetric, dof_handler.n_dofs(), hierarchy,
                               Utilities::MPI::n_mpi_processes(mpi_communicator));
  if (method == FilmLinearSolver::Method::cg_gmg)
  {
    if (!multigrid.is_setup())
      multigrid.setup(dof_handler, *mapping,
                      {AnnulusMesh::inner_boundary, AnnulusMesh::outer_boundary}, mpi_communicator);
    // the level matrices need K alone (pressure_flow: local_film's K without the rest)
    auto prepare = [this]()
    {
      const double cos_tilt = std::cos(film.tilt_angle), sin_tilt = std::sin(film.tilt_angle);
      const auto K = [this, cos_tilt, sin_tilt](const Point<2> &x)
      { return equation_scale * pressure_flow(x, cos_tilt, sin_tilt); };
      multigrid.prepare(system_matrix, K, polynomial_degree + 2, multigrid_parameters);
    };
    linear_system_solver.set_multigrid(&multigrid, prepare);
  }
  else
    linear_system_solver.set_multigrid(nullptr, {});
  // The AMG aggregates on the dof support points (film_linear_solver.h): built once per mesh,
  // and only for the sizes that use AMG.
  const bool may_use_amg =
      method == FilmLinearSolver::Method::cg_amg || method == FilmLinearSolver::Method::gmres_amg;
  if (may_use_amg && amg_support_x.empty())
  {
    // The support points of the locally owned dofs, in the order of locally_owned_dofs (the
    // rows of this rank; DoFTools::map_dofs_to_support_points fills a std::map: 0.4 s of the
    // AMG set-up at 1e6 dofs).
    const std::vector<Point<2>> support = owned_support_points();
    amg_support_x.resize(support.size());
    amg_support_y.resize(support.size());
    for (std::size_t k = 0; k < support.size(); ++k)
    {
      amg_support_x[k] = support[k][0];
      amg_support_y[k] = support[k][1];
    }
  }
  // The direct factorisations on the built-in annulus (one rank, MUMPS's sizes) in the nested
  // dissection of its node grid instead of MUMPS's AMD: 24-27 % fewer operations on the JFO
  // Jacobians of the tilted seal at 2.6e5-1.05e6 dofs (37 % at 6.6e4), 13-40 % on the wavy
  // example's, and the tilted seal's finest factorisation 3.5-4.2 -> 3.0-3.1 s
  // (doc/performance.md, Session 38). Made once per mesh, from the support points.
  // (The cavitation models' levels that start from a coarser one have it made while the coarse
  // levels run, coarse_level_state.)
  if (wants_nested_dissection(method))
  {
    elimination_order_tried = true;
    TimerOutput::Scope order_timer(timer, "nested dissection order");
    linear_system_solver.set_elimination_order(
        polar_nested_dissection(owned_support_points(), polynomial_degree, system_matrix));
  }
  linear_system_solver.prepare(system_matrix, symmetric, linear_solver, polynomial_degree,
                               solver_tolerance, amg_support_x, amg_support_y, newton_sequence,
                               deferred);
}

bool ReynoldsSolver::wants_nested_dissection(const FilmLinearSolver::Method method) const
{
  return method == FilmLinearSolver::Method::direct && !elimination_order_tried &&
         dof_handler.n_dofs() >= SparseDirect::multifrontal_limit &&
         Utilities::MPI::n_mpi_processes(mpi_communicator) == 1 &&
         settings.mesh.mesh_file.empty() && !(settings.mesh.mesh_size > 0);
}

unsigned int ReynoldsSolver::solve_linear_system(const TrilinosWrappers::MPI::Vector &rhs,
                                                 TrilinosWrappers::MPI::Vector &x) const
{
  return linear_system_solver.solve(rhs, x);
}

void ReynoldsSolver::solve()
{
  TimerOutput::Scope t(timer, "solve");
  factorize();
  TrilinosWrappers::MPI::Vector solution(locally_owned_dofs, mpi_communicator);
  last_iterations = solve_linear_system(system_rhs, solution);
  constraints.distribute(solution);
  if (!std::isfinite(solution.linfty_norm()))
    throw std::runtime_error("Reynolds solver: the linear solve produced a non-finite pressure");
  locally_relevant_solution = solution;
}

ReynoldsSolver::LocalFilm ReynoldsSolver::local_film(const Point<2> &x) const
{
  // called per point by the loads and the field output: no sine and cosine of the tilt angle
  // where there is no tilt (they multiply gamma = 0 there)
  const bool tilted = film.tilt != 0;
  return local_film(x, x.norm(), std::atan2(x[1], x[0]), tilted ? std::cos(film.tilt_angle) : 1,
                    tilted ? std::sin(film.tilt_angle) : 0);
}

ReynoldsSolver::LocalFilm ReynoldsSolver::local_film(const Point<2> &x, const double r,
                                                     const double theta, const double cos_tilt,
                                                     const double sin_tilt) const
{
  // The caller's cos psi and sin psi (once per assembly, or 1 and 0 where there is no tilt, which
  // they multiply) must be those of the film's tilt angle: both sides take std::cos and std::sin
  // of the same angle, so they agree to the bit; 4 eps (8 u) allows a rounding or two more.
  Assert(
      film.tilt == 0 || (std::abs(cos_tilt - std::cos(film.tilt_angle)) <=
                             4 * std::numeric_limits<double>::epsilon() &&
                         std::abs(sin_tilt - std::sin(film.tilt_angle)) <=
                             4 * std::numeric_limits<double>::epsilon()),
      ExcMessage("local_film: cos_tilt, sin_tilt are not the cosine and sine of the tilt angle"));
  LocalFilm f;
  f.r = r;
  f.theta = theta;
  double dh_dtheta, h_t;
  if (film.is_coned_tilted()) // no sine or cosine per point (4.2e6 points at 1e6 dofs)
  {
    f.h = film.coned_tilted_value(x[0], x[1], r, cos_tilt, sin_tilt);
    dh_dtheta = film.coned_tilted_d_dtheta(x[0], x[1], cos_tilt, sin_tilt);
    h_t = film.coned_tilted_d_dt(x[0], x[1]);
  }
  else
  {
    f.h = film.value(f.r, f.theta);
    dh_dtheta = film.d_dtheta(f.r, f.theta);
    h_t = film.d_dt(f.r, f.theta);
  }
  const double mu = conditions.viscosity;
  // Surface features: the equation is solved in the frame of the face that carries them (they
  // stand still there), where the mean surface velocity is (w1 + w2)/2 - w_F and the rest of the
  // film (analytic + expression) moves at -w_F: its dh/dt gains w_F dh/dtheta. For the full film
  // this is the stator-frame equation at the same instant (integrate the moving part by parts
  // in theta); with a cavity it neglects the cavity's own motion relative to the features
  // (quasi-steady, exact when the rest of the film is axisymmetric). Without features w_F = 0.
  const double w_frame = film.feature_frame_speed(conditions.rotor_speed, conditions.stator_speed);
  const double w_mean = conditions.mean_speed() - w_frame;
  const double w_half_difference = 0.5 * (conditions.rotor_speed - conditions.stator_speed);
  const Tensor<1, 2> er({x[0] / f.r, x[1] / f.r}), et({-x[1] / f.r, x[0] / f.r});
  const Tensor<1, 2> rotation({-x[1], x[0]}); // r e_theta
  f.u = w_mean * rotation;
  if (w_frame != 0)
    h_t += w_frame * dh_dtheta;
  if (source)
    h_t += source(x);

  if (flow_factors.is_smooth())
  {
    const double k = f.h * f.h * f.h / (12 * mu);
    f.K = k * unit_symmetric_tensor<2>();
    f.dK_dh = (3 * k / f.h) * unit_symmetric_tensor<2>();
    f.c = f.h * f.u;
    f.dc_dh = f.u;
    f.dc_div_factor = w_mean;
    f.squeeze = h_t;
    f.dsqueeze_dht = 1;
    f.h_T = f.h;
  }
  else
  {
    // Average Reynolds equation of Patir & Cheng in the polar frame: radial and circumferential
    // pressure flow factors, expected gap h_T in the Couette and squeeze terms, shear flow
    // sigma phi_s (u1 - u2)/2 along e_theta. The flow coefficient uses the nominal h, held at
    // 0.5 sigma (the fits' validity limit) where the faces are in asperity contact.
    const auto ff = flow_factors.film_factors(f.h);
    const double sigma = flow_factors.composite_roughness();
    const double h_flow = std::max(f.h, 0.5 * sigma);
    const double k = h_flow * h_flow * h_flow / (12 * mu);
    const double dk = f.h > 0.5 * sigma ? 3 * k / h_flow : 0.0;
    f.K = k * (ff.phi_r.value * outer_product(er, er) + ff.phi_theta.value * outer_product(et, et));
    f.dK_dh = (dk * ff.phi_r.value + k * ff.phi_r.d_dh) * outer_product(er, er) +
              (dk * ff.phi_theta.value + k * ff.phi_theta.d_dh) * outer_product(et, et);
    const double omega_eff = w_mean * ff.h_T.value + w_half_difference * sigma * ff.phi_s.value;
    f.dc_div_factor = w_mean * ff.h_T.d_dh + w_half_difference * sigma * ff.phi_s.d_dh;
    f.c = omega_eff * rotation;
    f.dc_dh = f.dc_div_factor * rotation;
    f.squeeze = ff.h_T.d_dh * h_t;
    f.dsqueeze_dht = ff.h_T.d_dh;
    f.phi_r = ff.phi_r.value;
    f.phi_theta = ff.phi_theta.value;
    f.phi_s = ff.phi_s.value;
    f.h_T = ff.h_T.value;
  }
  // div(omega_eff(h) r e_theta) = omega_eff'(h) dh/dtheta (r e_theta is divergence free)
  f.c_div = f.dc_div_factor * dh_dtheta;
  if (contact.enabled()) // (4.2e6 points at 1e6 dofs: no call where there is no contact model)
  {
    const ValueAndSlope pc = contact.contact_pressure(f.h);
    f.contact_pressure = pc.value;
    f.dcontact_dh = pc.d_dh;
  }
  return f;
}

Tensor<2, 2> ReynoldsSolver::pressure_flow(const Point<2> &x) const
{
  return pressure_flow(x, std::cos(film.tilt_angle), std::sin(film.tilt_angle));
}

Tensor<2, 2> ReynoldsSolver::pressure_flow(const Point<2> &x, const double cos_tilt,
                                           const double sin_tilt) const
{
  // local_film(x).K by the same expressions, without the film's derivatives, velocities and
  // contact: what the multigrid's level matrices need at every level quadrature point. The
  // coned, tilted film as in local_film (no sine, cosine or atan2 per point).
  const double r = x.norm();
  const double h = film.is_coned_tilted()
                       ? film.coned_tilted_value(x[0], x[1], r, cos_tilt, sin_tilt)
                       : film.value(r, std::atan2(x[1], x[0]));
  const double mu = conditions.viscosity;
  if (flow_factors.is_smooth())
  {
    const double k = h * h * h / (12 * mu);
    return k * unit_symmetric_tensor<2>();
  }
  const Tensor<1, 2> er({x[0] / r, x[1] / r}), et({-x[1] / r, x[0] / r});
  const auto ff = flow_factors.film_factors(h);
  const double h_flow = std::max(h, 0.5 * flow_factors.composite_roughness());
  const double k = h_flow * h_flow * h_flow / (12 * mu);
  return k * (ff.phi_r.value * outer_product(er, er) + ff.phi_theta.value * outer_product(et, et));
}

double ReynoldsSolver::streamline_tau(const DoFHandler<2>::active_cell_iterator &cell) const
{
  // Streamline-diffusion parameter for the transport of the void fraction in the cavity: full
  // upwinding, tau = h_K / (2 |u|), with |u| the Couette speed at the cell centre.
  const double w_frame = film.feature_frame_speed(conditions.rotor_speed, conditions.stator_speed);
  const double speed = std::abs(conditions.mean_speed() - w_frame) * cell->center().norm();
  return speed > 0 ? cell->diameter() / (2 * speed) : 0.0;
}

// ------------------------------------------------------------------------------------------------
// Cavitation (reynolds, jfo).
//
// JFO / Elrod-Adams: every dof j carries a_j = (p_j - p_cav)/P >= 0 and the void fraction
// v_j = 1 - s_j >= 0 with a_j v_j = 0 (p > p_cav => s = 1, s < 1 => p = p_cav). The discrete mass
// balance at dof i (the weak form of div(K grad p) = div(s h u) + s dh/dt, s = 1 - v, tested with
// phi_i) is
//
//   R_i = sum_j A_ij p_j - F_i + sum_j G_ij v_j = 0,
//   A_ij = int K grad phi_j . grad phi_i,          F_i = int h u . grad phi_i - dh/dt phi_i,
//   G_ij = int phi_j (h u . grad phi_i - dh/dt phi_i) - tau_K (u . grad(phi_j h))(u . grad phi_i).
//
// The last term is streamline diffusion of the transported void h v (with the sign of a positive
// diffusion relative to the transport term, which enters R as -u . grad(v h)): in the cavity the
// equation is pure transport along the Couette streamlines, which Galerkin alone leaves
// oscillating (Gravenkamp, Pfeil & Codina 2024). It acts on v only, so it vanishes identically
// wherever the film is full: without cavitation the JFO discretisation is the full-film Galerkin
// one. Summed over all test functions it is zero (sum phi_i = 1), so it moves no mass: the two
// boundary leakages balance the squeeze flow to solver tolerance. The complementarity is solved
// by Fischer-Burmeister-Newton-Schur (solve_jfo).
//
// Reynolds (Swift-Stieber): p_j = p_cav + P u_j with the complementarity min(u_j, R_j/J_jj) = 0,
// solved by the primal-dual active-set method (Hintermueller, Ito & Kunisch 2002).

void ReynoldsSolver::cell_film_matrices(
    std::optional<PolarCellValues> &polar, FEValues<2> &fe_values,
    const DoFHandler<2>::active_cell_iterator &cell, const bool with_void, FullMatrix<double> &A,
    FullMatrix<double> &G, Vector<double> &F,
    const std::function<void(unsigned int, const LocalFilm &)> &at_point,
    const std::function<void(unsigned int, const LocalFilm &)> &at_polar_point) const
{
  if (polar && polar->reinit(cell))
    film_matrices(*polar, cell, with_void, A, G, F, at_polar_point);
  else
  {
    fe_values.reinit(cell);
    film_matrices(fe_values, cell, with_void, A, G, F, at_point);
  }
}

template <class Values>
void ReynoldsSolver::film_matrices(
    Values &fe_values, const DoFHandler<2>::active_cell_iterator &cell, const bool with_void,
    FullMatrix<double> &A, FullMatrix<double> &G, Vector<double> &F,
    const std::function<void(unsigned int, const LocalFilm &)> &at_point) const
{
  // A: pressure flow, F: full-film Couette + squeeze, G: void-fraction terms (see above). All
  // scaled by 12 mu / C0^3 like the full-film system.
  constexpr bool polar = std::is_same_v<Values, PolarCellValues>;
  const unsigned int n = fe->n_dofs_per_cell();
  const double tau = with_void ? streamline_tau(cell) : 0.0;
  A = 0;
  G = 0;
  F = 0;
  // K grad phi_j once per point, not once per (i, j) pair (the same products, so the same bits)
  std::vector<Tensor<1, 2>> K_grad(n), shape_grad(n);
  std::vector<double> shape_value(n), div_c(n), couette_test(n), streamline_test(n);
  // cos, sin of the tilt angle once per cell (local_film's coned, tilted film)
  const double cos_tilt = std::cos(film.tilt_angle), sin_tilt = std::sin(film.tilt_angle);
  for (const unsigned int q : fe_values.quadrature_point_indices())
  {
    const Point<2> &x = fe_values.quadrature_point(q);
    LocalFilm f;
    if constexpr (polar)
      f = local_film(x, fe_values.radius(q), fe_values.angle(q), cos_tilt, sin_tilt);
    else
      f = local_film(x, x.norm(), std::atan2(x[1], x[0]), cos_tilt, sin_tilt);
    if (at_point)
      at_point(q, f);
    const Tensor<2, 2> K = equation_scale * f.K;
    const double JxW = fe_values.JxW(q);
    if constexpr (polar)
      if (K[0][1] == 0 && K[1][0] == 0 && K[0][0] == K[1][1])
      {
        // isotropic K = k I (smooth faces): k (grad phi_i . grad phi_j) JxW, the products of
        // the gradients being the same on every cell of the row; and the Couette flux turned
        // into the row's first cell instead of the gradients into this one
        const double k = K[0][0], *gram = fe_values.gram(q);
        double *a = &A(0, 0);
        for (unsigned int ij = 0; ij < n * n; ++ij)
          a[ij] += k * gram[ij];
        const Tensor<1, 2> c = fe_values.to_reference(f.c), u = fe_values.to_reference(f.u);
        for (unsigned int j = 0; j < n; ++j)
        {
          const Tensor<1, 2> &g = fe_values.reference_shape_grad(j, q);
          const double c_grad = c * g;
          shape_value[j] = fe_values.shape_value(j, q);
          couette_test[j] = equation_scale * (c_grad - f.squeeze * shape_value[j]) * JxW;
          F(j) += couette_test[j];
          if (with_void)
          {
            streamline_test[j] = equation_scale * tau * (u * g) * JxW;
            div_c[j] = c_grad + shape_value[j] * f.c_div;
          }
        }
        if (!with_void)
          continue;
        // G at this point is a sum of two outer products, (Couette flux test) x phi_j and
        // (streamline test) x div(phi_j c): 2 n^2 multiply-adds instead of the general loop's
        // tensor products per (i, j) ("jfo cell matrices" 1.14-1.19 -> 0.80-0.86 s at 5.3e5 dofs)
        for (unsigned int i = 0; i < n; ++i)
        {
          double *G_i = &G(i, 0);
          for (unsigned int j = 0; j < n; ++j)
            G_i[j] += couette_test[i] * shape_value[j] - streamline_test[i] * div_c[j];
        }
        continue;
      }
    // the point's shape values and gradients, and what the j loop needs of them, once per
    // point (the same products in the same order as taking them in the loop, so the same bits;
    // PolarCellValues' accessor, which turns the gradients on its first call, kept the compiler
    // from hoisting them: its JFO cell matrices took 20 % longer than FEValues')
    for (unsigned int j = 0; j < n; ++j)
    {
      shape_grad[j] = fe_values.shape_grad(j, q);
      shape_value[j] = fe_values.shape_value(j, q);
      K_grad[j] = K * shape_grad[j];
      // div(phi_j c) = c . grad phi_j + phi_j div c: the transported void content
      if (with_void)
        div_c[j] = f.c * shape_grad[j] + shape_value[j] * f.c_div;
    }
    for (unsigned int i = 0; i < n; ++i)
    {
      const Tensor<1, 2> &gi = shape_grad[i];
      const double vi = shape_value[i];
      const double c_grad_i = f.c * gi, u_grad_i = f.u * gi;
      F(i) += equation_scale * (c_grad_i - f.squeeze * vi) * JxW;
      for (unsigned int j = 0; j < n; ++j)
      {
        A(i, j) += (gi * K_grad[j]) * JxW;
        if (with_void)
          G(i, j) += equation_scale *
                     (shape_value[j] * (c_grad_i - f.squeeze * vi) - tau * div_c[j] * u_grad_i) *
                     JxW;
      }
    }
  }
}
template void ReynoldsSolver::film_matrices<FEValues<2>>(
    FEValues<2> &, const DoFHandler<2>::active_cell_iterator &, const bool, FullMatrix<double> &,
    FullMatrix<double> &, Vector<double> &,
    const std::function<void(unsigned int, const LocalFilm &)> &) const;
template void ReynoldsSolver::film_matrices<PolarCellValues>(
    PolarCellValues &, const DoFHandler<2>::active_cell_iterator &, const bool,
    FullMatrix<double> &, FullMatrix<double> &, Vector<double> &,
    const std::function<void(unsigned int, const LocalFilm &)> &) const;

void ReynoldsSolver::solve_cavitation()
{
  TimerOutput::Scope t(timer, "cavitation");
  const bool jfo = cavitation.model == Cavitation::jfo;
  const double p_cav = cavitation.pressure;
  const double p_lo = std::min(conditions.inner_pressure, conditions.outer_pressure);
  const double p_hi = std::max(conditions.inner_pressure, conditions.outer_pressure);
  if (!boundary_pressure && p_lo < p_cav)
  {
    std::ostringstream s;
    s << "Cavitation: a boundary pressure (pi = " << conditions.inner_pressure
      << " Pa, po = " << conditions.outer_pressure << " Pa) is below the cavitation pressure ("
      << p_cav << " Pa)";
    throw std::runtime_error(s.str());
  }
  if (jfo && !boundary_pressure && p_hi <= p_cav)
    throw std::runtime_error(
        "Cavitation: no supply: both boundary pressures equal the cavitation pressure, so the "
        "mass-conserving (jfo) film content is not determined (the solution is not unique); raise "
        "a boundary pressure above the cavitation pressure");

  if (jfo)
    JFOSolver(*this).solve(); // sets pressure_scale
  else
    ReynoldsCavitationSolver(*this).solve(); // sets pressure_scale
}

double ReynoldsSolver::full_film_pressure_scale() const
{
  // Scale of the pressure unknown of the cavitation models: the full-film pressure excursion
  // from p_cav (which includes the supply pressures).
  double excursion = 0;
  for (const auto i : locally_owned_dofs)
    excursion = std::max(excursion, std::abs(locally_relevant_solution[i] - cavitation.pressure));
  return std::max(Utilities::MPI::max(excursion, mpi_communicator), 1e-300);
}

FilmLoads ReynoldsSolver::compute_loads() const
{
  TimerOutput::Scope t(timer, "loads");
  return LoadIntegrator(*this).loads();
}

FilmLoads ReynoldsSolver::linearized_loads(const FilmPerturbation &perturbation) const
{
  return linearized_loads(std::vector<FilmPerturbation>{perturbation})[0];
}

std::vector<FilmLoads>
ReynoldsSolver::linearized_loads(const std::vector<FilmPerturbation> &perturbations) const
{
  TimerOutput::Scope t(timer, "linearized solve");
  return LoadIntegrator(*this).linearized_loads(perturbations);
}

std::vector<std::array<double, 3>> ReynoldsSolver::linearized_generalized_forces(
    const std::vector<FilmPerturbation> &perturbations) const
{
  TimerOutput::Scope t(timer, "linearized solve");
  return LoadIntegrator(*this).linearized_generalized_forces(perturbations);
}

FilmLoads ReynoldsSolver::run(const FilmThickness &film_in,
                              const OperatingConditions &conditions_in,
                              const unsigned int coarsening)
{
  film = film_in;
  conditions = conditions_in;
  return run(coarsening);
}

FilmLoads ReynoldsSolver::run(const unsigned int coarsening)
{
  flow_factors.validate();
  contact.validate();
  // With rough faces in asperity contact a film that touches down is carried by the asperities
  // (h is the distance between the mean planes, Green (2002) Eq. 24; it may be <= 0).
  film.validate(contact.enabled() && !flow_factors.is_smooth());
  conditions.validate();
  if (coarsening == 0) // before anything is allocated
  {
    // Below the element degree the circumferential error of the loads would fall at 2m < 2k,
    // which the error estimates (at the elements' order) do not bound.
    if (settings.mapping_degree() < settings.polynomial_degree)
      throw std::runtime_error(
          "Mapping degree " + std::to_string(settings.mapping_degree()) +
          " is below the Polynomial degree " + std::to_string(settings.polynomial_degree) +
          ": the error estimate would not bound the circumferential error; use k, k+1 or a "
          "number >= " +
          std::to_string(settings.polynomial_degree));
    settings.mesh.check_memory(settings.polynomial_degree, film.inner_radius, film.outer_radius);
    if (film.wave_amplitude != 0)
      settings.mesh.check_resolves_waves(film.wave_number, settings.polynomial_degree);
    // Surface features: the built-in mesh can put cell edges on the steps only if every period
    // of the features gets the same cells, at least one per piece (annulus_mesh.cc).
    const AnnulusMesh &m = settings.mesh;
    if (film.features && m.align_with_features && m.mesh_file.empty())
    {
      const AnnulusMesh::Alignment a = film.features->mesh_alignment();
      const unsigned int nt = m.circumferential_cells, n = a.periods;
      const unsigned int pieces = a.theta_breaks.size();
      if (pieces > 1 && (nt % n != 0 || nt / n < pieces))
      {
        std::ostringstream s;
        s << "Discretization: Circumferential cells = " << nt
          << " cannot put cell edges on the steps of " << n
          << " surface features (it must be a multiple of " << n << " with at least " << pieces
          << " cells per period, e.g. " << n * std::max(pieces, 8u)
          << "); or set Align with features = false";
        throw std::runtime_error(s.str());
      }
    }
  }
  flow_factors.reset_clamp_record();
  equation_scale = 12 * conditions.viscosity / Utilities::fixed_power<3>(film.clearance);
  timer.reset();
  // the finer breakdown is of this run too (a same-mesh run skips the mesh set-up: no entries)
  setup_detail.clear();
  multigrid.reset_times();
  linear_system_solver.reset_statistics();
  current_coarsening = coarsening;
  coarse_iterations = 0;
  coarse_factorizations = coarse_krylov_iterations = coarse_workspace_retries = 0;
  jfo_newton_steps = jfo_active_set_rounds = jfo_band_rounds = jfo_low_rank_updates = 0;
  jfo_band_workspace_retries = 0;
  coarse_level_solved_ahead = false;
  support_made_ahead.clear();
  if (cavitation.model == Cavitation::jfo)
    setup_while_coarse_levels_run(coarsening);
  else
    setup_system(coarsening);
  // The cavitation models (jfo, reynolds) start from their solution of the mesh twice as coarse
  // (mesh sequencing) and assemble and solve the full film only where that start is not
  // available (JFOSolver::warm_start, ReynoldsCavitationSolver::start); the right-hand side they
  // scale their residual by comes from their own cell matrices (full_film_flow_scale, or
  // add_to_full_film_rhs in their one pass over the cells). The
  // assembly here took 0.62-0.82 s of 19-24 s at 1.05e6 dofs (tilted JFO, session 22).
  if (cavitation.is_nonlinear())
    affine_loads.reset(false, 0, 0); // no full-film load sums
  else
    assemble_system();
  last_iterations = 0;
  if (!cavitation.is_nonlinear())
    solve();
  cavitation_iterations = 0;
  cavitation_residual = 0;
  pressure_scale = 1;
  locally_relevant_void.reinit(locally_owned_dofs, locally_relevant_dofs, mpi_communicator);
  if (cavitation.is_nonlinear())
    solve_cavitation();
  if (start_only)
    return FilmLoads();
  const FilmLoads loads = compute_loads();
  // at extreme bearing numbers the viscous terms cancel to round-off (doc/guarantees.md)
  refuse_round_off_collapse(estimate_round_off(film, conditions, loads));
  return loads;
}

std::map<std::string, double> ReynoldsSolver::stage_times() const
{
  return timer.get_summary_data(TimerOutput::total_wall_time);
}

bool ReynoldsSolver::loads_from_assembled_sums() const
{
  return LoadIntegrator(*this).uses_assembled_sums();
}

std::map<std::string, double> ReynoldsSolver::detail_times() const
{
  std::map<std::string, double> times = setup_detail;
  for (const auto &[name, t] : multigrid.times())
    times["multigrid: " + name] = t;
  return times;
}

double ReynoldsSolver::volume_flow_through_circle(const double rho,
                                                  const unsigned int n_points) const
{
  std::vector<Point<2>> points;
  if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
    for (unsigned int k = 0; k < n_points; ++k)
    {
      const double t = 2 * M_PI * (k + 0.5) / n_points;
      points.emplace_back(rho * std::cos(t), rho * std::sin(t));
    }
  Utilities::MPI::RemotePointEvaluation<2> cache;
  const auto gradients = VectorTools::point_gradients<1>(*mapping, dof_handler,
                                                         locally_relevant_solution, points, cache);
  double flow = 0;
  for (unsigned int k = 0; k < points.size(); ++k)
  {
    const Point<2> &x = points[k];
    const LocalFilm f = local_film(x);
    const Tensor<1, 2> er({x[0] / rho, x[1] / rho});
    flow += -(er * (f.K * gradients[k])) * rho * 2 * M_PI / n_points;
  }
  return Utilities::MPI::sum(flow, mpi_communicator);
}

std::vector<double> ReynoldsSolver::pressure_at(const std::vector<Point<2>> &points) const
{
  Utilities::MPI::RemotePointEvaluation<2> cache;
  return VectorTools::point_values<1>(*mapping, dof_handler, locally_relevant_solution, points,
                                      cache);
}

double ReynoldsSolver::l2_error(const Function<2> &exact) const
{
  Vector<float> cellwise(triangulation.n_active_cells());
  VectorTools::integrate_difference(*mapping, dof_handler, locally_relevant_solution, exact,
                                    cellwise, QGauss<2>(polynomial_degree + 2),
                                    VectorTools::L2_norm);
  return VectorTools::compute_global_error(triangulation, cellwise, VectorTools::L2_norm);
}

double ReynoldsSolver::pressure_integral(const std::function<double(double)> &g,
                                         const Quadrature<2> &cell_rule) const
{
  FEValues<2> fe_values(*mapping, *fe, cell_rule, update_values | update_JxW_values);
  std::vector<double> p(cell_rule.size());
  double sum = 0;
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (cell->is_locally_owned())
    {
      fe_values.reinit(cell);
      fe_values.get_function_values(locally_relevant_solution, p);
      for (unsigned int q = 0; q < p.size(); ++q)
        sum += g(p[q]) * fe_values.JxW(q);
    }
  return Utilities::MPI::sum(sum, mpi_communicator);
}

std::string ReynoldsSolver::write_output(const std::string &directory) const
{
  return write_film_output(*this, directory);
}

FilmLoads estimate_load_errors(const FilmLoads &fine, const FilmLoads &coarse,
                               const unsigned int degree)
{
  FilmLoads error;
  for (auto member :
       {&FilmLoads::force_z, &FilmLoads::moment_x, &FilmLoads::moment_y,
        &FilmLoads::moment_restoring, &FilmLoads::moment_transverse, &FilmLoads::leakage_inner,
        &FilmLoads::leakage_outer, &FilmLoads::friction_torque, &FilmLoads::cavitated_fraction})
    error.*member = richardson_error(fine.*member, coarse.*member, degree);
  return error;
}

} // namespace sealfe
