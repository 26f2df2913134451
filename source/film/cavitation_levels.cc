// The pieces of the cavitation models (reynolds, jfo) that both solvers use: the film matrices of
// every cell, and the start from the converged state of the mesh twice as coarse.
#include <sealfe/film/nested_transfer.h>
#include <sealfe/film/polar_cell_values.h>
#include <sealfe/film/polar_node_grid.h>
#include <sealfe/film/reynolds_solver.h>
#include <sealfe/numerics/ordered_batches.h>

#include <deal.II/base/mpi_remote_point_evaluation.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/thread_local_storage.h>
#include <deal.II/base/utilities.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/vector_tools_evaluate.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <future>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sealfe
{
using namespace dealii;

void ReynoldsSolver::compute_cell_matrices(const bool with_void, std::vector<FullMatrix<double>> &A,
                                           std::vector<FullMatrix<double>> &G,
                                           std::vector<Vector<double>> &F) const
{
  A.resize(triangulation.n_active_cells());
  G.resize(with_void ? triangulation.n_active_cells() : 0);
  F.resize(triangulation.n_active_cells());
  for_each_cell_film_matrices(with_void,
                              [&](const DoFHandler<2>::active_cell_iterator &cell,
                                  const FullMatrix<double> &A_k, const FullMatrix<double> &G_k,
                                  const Vector<double> &F_k)
                              {
                                const auto k = cell->active_cell_index();
                                A[k] = A_k;
                                F[k] = F_k;
                                if (with_void)
                                  G[k] = G_k;
                              });
}

void ReynoldsSolver::for_each_cell_film_matrices(const bool with_void,
                                                 const CellFilmVisit &visit) const
{
  const unsigned int n = fe->n_dofs_per_cell();
  const QGauss<2> quadrature(polynomial_degree + 2);
  // The built-in annulus: each cell's geometry (points, radius and angle, JxW, gradients) from
  // its radial row, as in the full-film assembly (ReynoldsSolver::assemble_system), so no
  // mapping, atan2 or square root per point; a cell that is not its row's first cell turned
  // takes FEValues. The leakage residual of the loads takes the same values for the cells on the
  // circles (LoadIntegrator::polar_assembly), so that the leakages of the solved field balance to
  // round-off.
  std::optional<PolarCellValues> polar;
  if (assembles_on_polar_rows())
    polar.emplace(*mapping, *fe, quadrature);
  const std::vector<DoFHandler<2>::active_cell_iterator> cells =
      owned_cells_finding_rows(dof_handler, polar);
  // Batches of cells computed on deal.II's threads (each with its own FEValues and copy of the
  // rows) and visited on this thread in the order of the cells, as by one loop (the visitors sum
  // into global matrices: the same bits on any number of threads)
  struct CellMatrices
  {
    FullMatrix<double> A, G; // (film_matrices sets G, to zero without the void)
    Vector<double> F;
  };
  constexpr std::size_t batch_size = 1024;
  std::array<std::vector<CellMatrices>, 2> batches;
  for (auto &batch : batches)
    batch.assign(
        std::min(batch_size, cells.size()),
        CellMatrices{FullMatrix<double>(n, n), FullMatrix<double>(n, n), Vector<double>(n)});
  struct Scratch
  {
    FEValues<2> fe_values;
    std::optional<PolarCellValues> polar;
  };
  Threads::ThreadLocalStorage<std::unique_ptr<Scratch>> scratch;
  auto compute = [&](std::vector<CellMatrices> &batch, const std::size_t first_cell,
                     const std::size_t first, const std::size_t last)
  {
    std::unique_ptr<Scratch> &own = scratch.get();
    if (!own)
      // FEValues can be neither copied nor moved: the aggregate is made in place
      own.reset(new Scratch{FEValues<2>(*mapping, *fe, quadrature,
                                        update_values | update_gradients |
                                            update_quadrature_points | update_JxW_values),
                            polar});
    for (std::size_t c = first; c < last; ++c)
      cell_film_matrices(own->polar, own->fe_values, cells[first_cell + c], with_void, batch[c].A,
                         batch[c].G, batch[c].F);
  };
  auto add = [&](const std::vector<CellMatrices> &batch, const std::size_t first_cell,
                 const std::size_t count)
  {
    for (std::size_t c = 0; c < count; ++c)
      visit(cells[first_cell + c], batch[c].A, batch[c].G, batch[c].F);
  };
  numerics::compute_in_batches_add_in_order(cells.size(), batch_size, batches, 32, compute, add);
}

void ReynoldsSolver::solve_coarse_level(std::vector<Point<2>> *support)
{
  // The coarse level solves the same physics: a copy of the whole settings (flow factors and
  // contact included) and the same test hooks. Kept in the solver, so that its mesh is reused.
  // Several ranks on the built-in mesh: every rank solves the coarse levels whole by itself
  // (MPI_COMM_SELF), as one rank would, instead of all ranks together. They are small (a quarter
  // of this level and less) but need many direct factorisations, which on 2 ranks took 7x the
  // one-rank time (44 against 6 s at 1.05e6 dofs, doc/performance.md "Two ranks, session 10");
  // each rank then holds the whole coarse solution, and its start values are those of one rank.
  // Meshes from files stay distributed (each rank would read, or generate, the file again).
  const bool whole_on_each_rank = Utilities::MPI::n_mpi_processes(mpi_communicator) > 1 &&
                                  settings.mesh.mesh_file.empty() && !(settings.mesh.mesh_size > 0);
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(mpi_communicator);
  // a solver kept from a run of the other kind (a mesh file set since) is made again
  if (coarse_solver && Utilities::MPI::n_mpi_processes(coarse_solver->mpi_communicator) !=
                           (whole_on_each_rank ? 1 : n_ranks))
    coarse_solver.reset();
  if (!coarse_solver)
    coarse_solver = std::make_unique<ReynoldsSolver>(
        settings, whole_on_each_rank ? MPI_COMM_SELF : mpi_communicator);
  ReynoldsSolver &coarse = *coarse_solver;
  // The ranks that each solve the coarse levels whole factorise their larger matrices together
  // (SparseDirect::share_with: a separator splits each over the ranks), the levels below too;
  // every rank then still holds the same whole solution, bit for bit
  coarse.linear_system_solver.share_direct_with(
      whole_on_each_rank ? mpi_communicator : linear_system_solver.direct_team());
  coarse.settings = settings;
  coarse.boundary_pressure = boundary_pressure;
  coarse.source = source;
  coarse.start_only = true;
  const bool first_rank = Utilities::MPI::this_mpi_process(mpi_communicator) == 0;
  coarse.reports_progress = reports_progress && first_rank;
  TimerOutput::Scope timer_scope(
      timer, cavitation.model == Cavitation::jfo ? "jfo coarse levels" : "reynolds coarse levels");
  // Every rank decides together: solved whole on each rank, the coarse levels could fail on
  // one rank only (memory, say), which would then take the full-film start alone and wait
  // forever in its collective solve. Their shared factorisations (share_direct_with) agree on a
  // failure inside them on every rank (numerics::SubstructuredLU); a failure on one rank outside
  // them (an allocation in its assembly, say) still leaves the others waiting in their next
  // shared factorisation: not handled.
  // This level's nested dissection (for the direct factorisations of its Jacobians, factorize())
  // and its owned dofs' support points (for the start below) are made on a thread of their own
  // while the coarse levels run: those touch nothing of this level, whose mesh, dofs and matrix
  // pattern are fixed since setup_system, and their MUMPS factorisations run on one core. The
  // thread only reads, and makes no MPI call (one rank). Tilted seal, JFO at 1.05e6 dofs: the
  // order's 0.18-0.24 s off the run's wall time (doc/performance.md "Session 40").
  struct MadeAhead
  {
    std::vector<Point<2>> support;
    std::vector<int> order;
  };
  std::future<MadeAhead> ahead;
  if (support && wants_nested_dissection(FilmLinearSolver::choose(
                     linear_solver, false, dof_handler.n_dofs(), false, n_ranks)))
    ahead = std::async(std::launch::async,
                       [this]()
                       {
                         MadeAhead made;
                         made.support = owned_support_points();
                         made.order = polar_nested_dissection(made.support, polynomial_degree,
                                                              system_matrix);
                         return made;
                       });
  std::string failure;
  try
  {
    coarse.run(current_coarsening + 1);
  }
  catch (std::exception &e)
  {
    failure = e.what();
  }
  if (ahead.valid())
  {
    // (the stage's time is the wait for the thread: what the order costs the run)
    TimerOutput::Scope order_timer(timer, "nested dissection order");
    MadeAhead made = ahead.get();
    linear_system_solver.set_elimination_order(std::move(made.order));
    elimination_order_tried = true;
    *support = std::move(made.support);
  }
  // The coarse level's solution is all this level takes from it: its factorisation (with those
  // of the levels below it, which it freed in turn) goes before this level factorises. Tilted
  // seal, JFO at 1.05e6 dofs: peak memory 3.82 -> 3.39 GB on one rank, 2.76 -> 2.26-2.37 GB per
  // rank on two, where every rank holds the coarse levels whole (doc/performance.md "Session
  // 26"). A later run on this mesh analyses the coarse patterns again (no time measurable in a
  // JFO table at 1.3e5 dofs).
  coarse.linear_system_solver.release_factorization();
  const bool failed_somewhere =
      whole_on_each_rank ? Utilities::MPI::max(int(!failure.empty()), mpi_communicator) != 0
                         : !failure.empty();
  coarse_level_failed = failed_somewhere;
  if (failed_somewhere && !failure.empty() && reports_progress &&
      (first_rank || whole_on_each_rank))
    std::cerr << "Cavitation: the coarse start failed (" << failure
              << "); starting from the full film instead" << std::endl;
}

bool ReynoldsSolver::coarse_level_state(std::vector<double> &pressure_at_dofs,
                                        std::vector<double> &void_at_dofs)
{
  // The cavity boundary moves by about one cell per Newton (JFO) or active-set (Reynolds)
  // iteration, so the iteration counts of a start from the full film grow with the mesh
  // (JFOSolver::warm_start). On textured faces the sequencing stops at the coarsest level that
  // still resolves the dimples, and never regenerates a gmsh mesh (AnnulusMesh::sequences_jfo).
  // The coarse level may have been solved already, while this level's mesh was made
  // (setup_while_coarse_levels_run).
  std::vector<Point<2>> support = std::move(support_made_ahead);
  support_made_ahead.clear();
  if (!coarse_level_solved_ahead)
  {
    const unsigned int next = current_coarsening + 1;
    if (dof_handler.n_dofs() <= 200 || !mesh_parameters.can_coarsen(next) ||
        !mesh_parameters.sequences_jfo(next, film.inner_radius, film.outer_radius))
      return false;
    solve_coarse_level(&support);
  }
  coarse_level_solved_ahead = false;
  if (coarse_level_failed)
    return false; // fall back to the full-film start
  const ReynoldsSolver &coarse = *coarse_solver;
  const bool whole_on_each_rank = Utilities::MPI::n_mpi_processes(mpi_communicator) > 1 &&
                                  settings.mesh.mesh_file.empty() && !(settings.mesh.mesh_size > 0);
  // the owned dofs' support points by owned index (owned_support_points: a std::map's 1.3e5
  // insertions were a quarter of the coarse start's time at 1.3e5 dofs)
  const unsigned int n_owned = locally_owned_dofs.n_elements();
  if (support.empty())
    support = owned_support_points();
  std::vector<Point<2>> points;
  std::vector<types::global_dof_index> indices;
  std::vector<unsigned int> owned_index; // of each point
  {
    unsigned int k = 0;
    for (const auto i : locally_owned_dofs)
    {
      if (!homogeneous_constraints.is_constrained(i))
      {
        indices.push_back(i);
        owned_index.push_back(k);
        points.push_back(support[k]);
      }
      ++k;
    }
  }
  std::vector<double> pressure, void_fraction;
  bool all_found = true;
  const std::vector<const TrilinosWrappers::MPI::Vector *> fields = {
      &coarse.locally_relevant_solution, &coarse.locally_relevant_void};
  std::vector<std::vector<double>> values;
  // the built-in polar grid: cells by (r, theta); a mesh file refined globally: the coarse
  // level is the same mesh refined once less (parent cells); other meshes on one rank: a search
  // over the coarse cells' bounding boxes (values_at_points)
  if (coarse_values_on_polar_grid(points, pressure, void_fraction))
  {
    // every point found by its (r, theta)
  }
  else if ((!settings.mesh.mesh_file.empty() &&
            values_from_parent_cells(dof_handler, coarse.dof_handler, fields, indices, values)) ||
           values_at_points(*coarse.mapping, coarse.dof_handler, fields, points, values))
  {
    pressure = std::move(values[0]);
    void_fraction = std::move(values[1]);
  }
  else
  {
    // several ranks: deal.II's point search (at 1e6 points a third of the JFO time,
    // doc/performance.md; on one rank 25 s of 36 s for 1e5 points on a gmsh mesh)
    Utilities::MPI::RemotePointEvaluation<2> cache;
    pressure = VectorTools::point_values<1>(*coarse.mapping, coarse.dof_handler,
                                            coarse.locally_relevant_solution, points, cache);
    void_fraction =
        VectorTools::point_values<1>(cache, coarse.dof_handler, coarse.locally_relevant_void);
    all_found = cache.all_points_found();
  }
  coarse_iterations = coarse.cavitation_iterations + coarse.coarse_iterations;
  const auto &coarse_work = coarse.linear_system_solver.statistics();
  coarse_factorizations = coarse_work.factorizations + coarse.coarse_factorizations;
  coarse_krylov_iterations = coarse_work.krylov_iterations + coarse.coarse_krylov_iterations;
  coarse_workspace_retries = coarse_work.workspace_retries + coarse.jfo_band_workspace_retries +
                             coarse.coarse_workspace_retries;
  // the same answer on every rank (each rank looked up its own points)
  if (Utilities::MPI::min(int(all_found), mpi_communicator) == 0)
    return false;
  // The coarse level's pressure scale (a scale only: the solution does not depend on it, but
  // every rank must scale its rows alike: rank 0's copy), and the Dirichlet values of this mesh
  // at the constrained dofs.
  pressure_scale = whole_on_each_rank
                       ? Utilities::MPI::broadcast(mpi_communicator, coarse.pressure_scale, 0)
                       : coarse.pressure_scale;
  TrilinosWrappers::MPI::Vector boundary(locally_owned_dofs, mpi_communicator);
  constraints.distribute(boundary);
  pressure_at_dofs.resize(n_owned);
  void_at_dofs.assign(n_owned, 0.0);
  {
    unsigned int k = 0;
    for (const auto i : locally_owned_dofs)
      pressure_at_dofs[k++] = boundary[i];
  }
  for (unsigned int k = 0; k < indices.size(); ++k)
  {
    pressure_at_dofs[owned_index[k]] = pressure[k];
    void_at_dofs[owned_index[k]] = void_fraction[k];
  }
  return true;
}

std::vector<Point<2>> ReynoldsSolver::owned_support_points() const
{
  std::vector<Point<2>> support(locally_owned_dofs.n_elements());
  FEValues<2> fe_values(*mapping, *fe, Quadrature<2>(fe->get_unit_support_points()),
                        update_quadrature_points);
  std::vector<types::global_dof_index> dofs(fe->n_dofs_per_cell());
  for (const auto &cell : dof_handler.active_cell_iterators())
    if (!cell->is_artificial())
    {
      fe_values.reinit(cell);
      cell->get_dof_indices(dofs);
      for (unsigned int i = 0; i < dofs.size(); ++i)
        if (locally_owned_dofs.is_element(dofs[i]))
          support[locally_owned_dofs.index_within_set(dofs[i])] = fe_values.quadrature_point(i);
    }
  return support;
}

bool ReynoldsSolver::coarse_values_on_polar_grid(const std::vector<Point<2>> &points,
                                                 std::vector<double> &pressure,
                                                 std::vector<double> &void_fraction) const
{
  const ReynoldsSolver &coarse = *coarse_solver;
  // the coarse mesh whole on this rank (one rank, or coarse_start's levels on each rank)
  if (!settings.mesh.mesh_file.empty() ||
      Utilities::MPI::n_mpi_processes(coarse.mpi_communicator) > 1)
    return false;
  // The built-in mesh is a tensor grid in (r, theta): radial nodes (graded) and nt equal angles.
  // Its cells are found from a point's polar coordinates; the reference coordinates inside the
  // cell are those of the polar rectangle, which the cell's mapping (degree m) follows up to its
  // O(h^(m+1)) departure from the circles: far below the discretisation error, and this is only the
  // start of the Newton iteration on the finer mesh.
  const auto &tria = coarse.dof_handler.get_triangulation();
  std::vector<double> radii;
  for (const Point<2> &v : tria.get_vertices())
    radii.push_back(v.norm());
  std::sort(radii.begin(), radii.end());
  const double ri = radii.front(), ro = radii.back(), tolerance = 1e-9 * ro;
  radii.erase(std::unique(radii.begin(), radii.end(),
                          [tolerance](double a, double b) { return b - a < tolerance; }),
              radii.end());
  const unsigned int nr = radii.size() - 1;
  if (nr == 0 || tria.n_active_cells() % nr != 0)
    return false;
  const unsigned int nt = tria.n_active_cells() / nr;
  const double dtheta = 2 * M_PI / nt;
  auto angle = [](const Point<2> &x)
  {
    const double t = std::atan2(x[1], x[0]);
    return t < 0 ? t + 2 * M_PI : t;
  };
  auto radial_index = [&](const double r)
  {
    const auto it = std::upper_bound(radii.begin(), radii.end(), r);
    return std::clamp<long>(it - radii.begin() - 1, 0, long(nr) - 1);
  };
  auto angular_index = [&](const double t)
  { return std::min<unsigned int>(static_cast<unsigned int>(t / dtheta), nt - 1); };
  std::vector<DoFHandler<2>::active_cell_iterator> cells(nr * nt);
  for (const auto &cell : coarse.dof_handler.active_cell_iterators())
  {
    // the slot of the cell's mean vertex radius and its centre's angle (the norm of the vertex
    // mean falls below the cell when the cells span large angles: 8 % inside at 8 cells around)
    double r = 0;
    for (const unsigned int v : cell->vertex_indices())
      r += 0.25 * cell->vertex(v).norm();
    const std::size_t k = angular_index(angle(cell->center())) * nr + radial_index(r);
    if (cells[k].state() == IteratorState::valid)
      return false; // two cells in one slot: not a polar tensor grid
    cells[k] = cell;
  }
  const FiniteElement<2> &fe = *coarse.fe;
  Vector<double> p_nodal(fe.n_dofs_per_cell()), v_nodal(fe.n_dofs_per_cell());
  pressure.resize(points.size());
  void_fraction.resize(points.size());
  // (r, theta) of vertex k of a cell, theta unwrapped next to `near`
  auto polar = [&](const Point<2> &x, const double near)
  {
    double t = angle(x);
    t += 2 * M_PI * std::round((near - t) / (2 * M_PI));
    return Tensor<1, 2>({x.norm(), t});
  };
  for (std::size_t q = 0; q < points.size(); ++q)
  {
    const double r = std::clamp(points[q].norm(), ri, ro), t = angle(points[q]);
    const auto &cell = cells[angular_index(t) * nr + radial_index(r)];
    // the polar rectangle P(xi, eta) = P0 + xi (P1 - P0) + eta (P2 - P0) of vertices 0, 1, 2
    const Tensor<1, 2> P0 = polar(cell->vertex(0), t), P1 = polar(cell->vertex(1), t),
                       P2 = polar(cell->vertex(2), t), P = Tensor<1, 2>({r, t});
    const Tensor<1, 2> e1 = P1 - P0, e2 = P2 - P0, d = P - P0;
    const double det = e1[0] * e2[1] - e1[1] * e2[0];
    const double xi = (d[0] * e2[1] - d[1] * e2[0]) / det,
                 eta = (e1[0] * d[1] - e1[1] * d[0]) / det;
    // a point outside the cell its (r, theta) slot names: the angles are not nt equal ones
    // (a mesh aligned with surface features, or sheared along spiral grooves); the caller
    // searches instead
    const double slack = 1e-6;
    if (std::min(xi, eta) < -slack || std::max(xi, eta) > 1 + slack)
      return false;
    const Point<2> unit(std::clamp(xi, 0.0, 1.0), std::clamp(eta, 0.0, 1.0));
    cell->get_dof_values(coarse.locally_relevant_solution, p_nodal);
    cell->get_dof_values(coarse.locally_relevant_void, v_nodal);
    double p = 0, v = 0;
    for (unsigned int k = 0; k < fe.n_dofs_per_cell(); ++k)
    {
      const double phi = fe.shape_value(k, unit);
      p += p_nodal[k] * phi;
      v += v_nodal[k] * phi;
    }
    pressure[q] = p;
    void_fraction[q] = v;
  }
  return true;
}

} // namespace sealfe
