#include <sealfe/film/cell_sparsity.h>
#include <sealfe/film/film_multigrid.h>
#include <sealfe/film/lap_timer.h>
#include <sealfe/film/level_transfer.h>
#include <sealfe/film/line_jacobi.h>
#include <sealfe/film/line_stencil_matrix.h>
#include <sealfe/film/polar_cell_values.h>
#include <sealfe/film/sparse_direct.h>
#include <sealfe/numerics/threaded_product.h>

#include <deal.II/base/mg_level_object.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/exceptions.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/multigrid/mg_base.h>
#include <deal.II/multigrid/mg_constrained_dofs.h>
#include <deal.II/multigrid/mg_tools.h>
#include <deal.II/multigrid/mg_transfer.h>
#include <deal.II/multigrid/multigrid.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <vector>

namespace sealfe
{
using namespace dealii;

namespace
{
using VectorType = FilmMultigrid::VectorType;
using MatrixType = TrilinosWrappers::SparseMatrix;

/// The radial lines of the owned dofs of `level` (numbers::invalid_unsigned_int: the active
/// dofs), from the support points: sorted by angle, then radius.
RadialLines find_radial_lines(const DoFHandler<2> &dof_handler, const Mapping<2> &mapping,
                              const unsigned int level)
{
  const bool active = level == numbers::invalid_unsigned_int;
  const auto &fe = dof_handler.get_fe();
  FEValues<2> fe_values(mapping, fe, Quadrature<2>(fe.get_unit_support_points()),
                        update_quadrature_points);
  std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
  const IndexSet &owned =
      active ? dof_handler.locally_owned_dofs() : dof_handler.locally_owned_mg_dofs(level);
  std::vector<std::pair<long, double>> key(owned.n_elements(), {-1, 0.0}); // (angle, radius)
  auto visit = [&](const auto &cell)
  {
    fe_values.reinit(cell);
    for (unsigned int i = 0; i < dofs.size(); ++i)
      // a dof shared by several cells is keyed once (its support point is the same)
      if (owned.is_element(dofs[i]) && key[owned.index_within_set(dofs[i])].first < 0)
      {
        const Point<2> &x = fe_values.quadrature_point(i);
        // k angles per cell around, the same along a radial line (the mapping is a tensor product
        // of its radial and angular interpolations), ~2 pi / (k N_theta) apart: 2^24 keys a turn
        // separate them
        double turns = std::atan2(x[1], x[0]) / (2 * M_PI);
        if (turns < 0)
          turns += 1;
        const long turn_key = 1l << 24;
        key[owned.index_within_set(dofs[i])] = {std::lround(turns * turn_key) % turn_key, x.norm()};
      }
  };
  if (active)
  {
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
      {
        cell->get_dof_indices(dofs);
        visit(cell);
      }
  }
  else
    for (const auto &cell : dof_handler.mg_cell_iterators_on_level(level))
      if (cell->is_locally_owned_on_level())
      {
        cell->get_mg_dof_indices(dofs);
        visit(cell);
      }
  std::vector<unsigned int> sorted(key.size());
  std::iota(sorted.begin(), sorted.end(), 0u);
  std::sort(sorted.begin(), sorted.end(),
            [&](unsigned int a, unsigned int b) { return key[a] < key[b]; });
  RadialLines lines;
  lines.order.resize(key.size());
  for (unsigned int p = 0; p < sorted.size(); ++p)
  {
    lines.order[sorted[p]] = p;
    if (p == 0 || key[sorted[p]].first != key[sorted[p - 1]].first)
      lines.start.push_back(p);
  }
  lines.start.push_back(sorted.size());
  return lines;
}

/// New numbers of the owned dofs: the same index set, in the order of `lines`.
std::vector<types::global_dof_index> numbers_by_lines(const IndexSet &owned,
                                                      const RadialLines &lines)
{
  std::vector<types::global_dof_index> numbers(owned.n_elements());
  for (unsigned int i = 0; i < numbers.size(); ++i)
    numbers[i] = owned.nth_index_in_set(lines.order[i]);
  return numbers;
}

/// A level's operator in the smoother and the V-cycle's residual: the level matrix, or on the
/// finest level (the system) its single-precision line stencil (LineStencilMatrix), whose
/// products read about half the memory. The CG iterations keep the system matrix.
struct LevelOperator : public Subscriptor
{
  const MatrixType *matrix = nullptr;
  const LineStencilMatrix *stencil = nullptr;
  void vmult(VectorType &dst, const VectorType &src) const
  {
    if (stencil)
      stencil->vmult(dst, src);
    else
      numerics::threaded_vmult(*matrix, dst, src);
  }
  types::global_dof_index m() const { return matrix->m(); }
  types::global_dof_index n() const { return matrix->n(); }
};

using Smoother = PreconditionChebyshev<LevelOperator, VectorType, LineJacobi>;
/// CG (Lanczos) steps that estimate the largest eigenvalue of each level's smoothed operator
/// (scaled by 1.2 below). 6 and 12 steps gave the same CG iterations at 1.05e6 Q2 dofs (9) and
/// the same or one fewer on six meshes of degrees 1-3 and Ntheta/Nr = 1-32 (doc/performance.md);
/// each step is a level product and a line solve.
constexpr unsigned int eigenvalue_iterations = 6;

/// The level operators: pointers, so that the finest level can be the system matrix itself.
class LevelMatrices : public MGMatrixBase<VectorType>
{
public:
  std::vector<const MatrixType *> matrices;
  void vmult(const unsigned int l, VectorType &dst, const VectorType &src) const override
  {
    matrices[l]->vmult(dst, src);
  }
  void vmult_add(const unsigned int l, VectorType &dst, const VectorType &src) const override
  {
    matrices[l]->vmult_add(dst, src);
  }
  void Tvmult(const unsigned int l, VectorType &dst, const VectorType &src) const override
  {
    matrices[l]->Tvmult(dst, src);
  }
  void Tvmult_add(const unsigned int l, VectorType &dst, const VectorType &src) const override
  {
    matrices[l]->Tvmult_add(dst, src);
  }
  unsigned int get_minlevel() const override { return 0; }
  unsigned int get_maxlevel() const override { return matrices.size() - 1; }
};

/// Chebyshev smoothing on each level (symmetric: the same polynomial before and after the
/// coarse correction, so the V-cycle is a symmetric preconditioner for CG).
class ChebyshevSmoother : public MGSmootherBase<VectorType>
{
public:
  MGLevelObject<Smoother> smoothers;
  void smooth(const unsigned int l, VectorType &u, const VectorType &rhs) const override
  {
    smoothers[l].step(u, rhs);
  }
  void apply(const unsigned int l, VectorType &u, const VectorType &rhs) const override
  {
    smoothers[l].vmult(u, rhs);
  }
  void clear() override { smoothers.resize(0, 0); }
};

/// KLU on the coarsest level.
class CoarseDirect : public MGCoarseGridBase<VectorType>
{
public:
  mutable SparseDirect direct;
  void operator()(const unsigned int, VectorType &dst, const VectorType &src) const override
  {
    direct.solve(src, dst);
  }
};
} // namespace

struct FilmMultigrid::Data
{
  MGConstrainedDoFs constrained_dofs;
  std::vector<AffineConstraints<double>> level_constraints;
  /// [l]: level l's matrix has CellSparsity's pattern (set in setup: boundary constraints only,
  /// one owned range per rank), so prepare adds the cells without boundary dofs by position.
  std::vector<char> by_position;
  std::vector<RadialLines> lines;
  MGLevelObject<MatrixType> level_matrices; // the assembled ones
  LevelMatrices operators;
  /// [l]: the smoother's and the V-cycle's operator on level l (the finest level's stencil
  /// where the finest level is the system and Parameters::single_precision_finest is set).
  std::vector<LevelOperator> level_operators;
  LineStencilMatrix fine_stencil;
  /// The finest level is the system (setup): its operator the system matrix, its vectors the
  /// system's, its lines the active ones, the transfer's last rows the active dofs.
  bool fine_is_system = false;
  /// Level l is the system itself (not assembled, no level constraints or matrix of its own).
  bool is_system_level(const unsigned int l) const
  {
    return fine_is_system && l + 1 == level_matrices.n_levels();
  }
  std::unique_ptr<MGTransferPrebuilt<VectorType>> transfer; // !fine_is_system
  LevelTransfer level_transfer;                             // fine_is_system
  ChebyshevSmoother smoother;
  CoarseDirect coarse;
  std::unique_ptr<Multigrid<VectorType>> multigrid;
  std::unique_ptr<PreconditionMG<2, VectorType, MGTransferPrebuilt<VectorType>>> preconditioner;
  // The V-cycle's level vectors, allocated once per mesh (fine_is_system: see v_cycle).
  MGLevelObject<VectorType> defect, solution, residual;

  /// deal.II's Multigrid::level_v_step on persistent level vectors: PreconditionMG and
  /// Multigrid re-create every level vector (with new Trilinos maps) at each V-cycle, and the
  /// Chebyshev smoothers then re-allocate their own work vectors too.
  void v_step(const unsigned int l)
  {
    if (l == 0)
    {
      coarse(0, solution[0], defect[0]);
      return;
    }
    smoother.apply(l, solution[l], defect[l]);
    level_operators[l].vmult(residual[l], solution[l]);
    residual[l].sadd(-1.0, 1.0, defect[l]);
    defect[l - 1] = 0;
    level_transfer.restrict_and_add(l, defect[l - 1], residual[l]);
    v_step(l - 1);
    level_transfer.prolongate_and_add(l, solution[l], solution[l - 1]);
    smoother.smooth(l, solution[l], defect[l]);
  }
};

FilmMultigrid::FilmMultigrid() = default;
FilmMultigrid::~FilmMultigrid() = default;

void FilmMultigrid::number_by_radial_lines(DoFHandler<2> &dof_handler, const Mapping<2> &mapping)
{
  const RadialLines lines = find_radial_lines(dof_handler, mapping, numbers::invalid_unsigned_int);
  dof_handler.renumber_dofs(numbers_by_lines(dof_handler.locally_owned_dofs(), lines));
  active_line_start = lines.start;
}

bool FilmMultigrid::has_hierarchy(const DoFHandler<2> &dof_handler)
{
  return dof_handler.get_triangulation().n_global_levels() >= 2;
}

unsigned int FilmMultigrid::n_levels() const
{
  return dof_handler ? dof_handler->get_triangulation().n_global_levels() : 0;
}

void FilmMultigrid::clear()
{
  data.reset();
  dof_handler = nullptr;
  mapping = nullptr;
  active_line_start.clear();
  lap_times.clear();
}

void FilmMultigrid::setup(DoFHandler<2> &dof_handler_in, const Mapping<2> &mapping_in,
                          const std::vector<types::boundary_id> &dirichlet_ids, const MPI_Comm comm)
{
  data.reset(); // not clear(): the active lines of number_by_radial_lines are kept
  LapTimer lap(lap_times);
  dof_handler = &dof_handler_in;
  mapping = &mapping_in;
  data = std::make_unique<Data>();
  dof_handler->distribute_mg_dofs();
  lap("level dofs");
  const auto &tria = dof_handler->get_triangulation();
  communicator = comm;
  const unsigned int n_levels = tria.n_global_levels(), fine = n_levels - 1;

  // The radial lines of every level (the smoother's line blocks).
  data->lines.resize(n_levels);
  // The finest level is the system itself where every locally owned active cell is on it (a
  // globally refined mesh) and the active dofs are numbered by lines: its operator is the system
  // matrix, its vectors the system's, its lines the active ones, and the transfer takes the
  // active numbers of its cells as rows: its level dofs are never used. Else, or where the
  // transfer cannot reach every owned active dof from a parent cell this rank sees (several
  // ranks), the finest level gets its own lines and is assembled like the others, with
  // MGTransferPrebuilt. Each test is reduced over the ranks before its branch: every rank must
  // take the same one (collectives).
  bool fine_active = !active_line_start.empty() &&
                     active_line_start.back() == dof_handler->locally_owned_dofs().n_elements();
  if (fine_active)
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned() && cell->level() != int(fine))
      {
        fine_active = false;
        break;
      }
  fine_active = Utilities::MPI::min(fine_active ? 1 : 0, comm) == 1;
  // The levels keep deal.II's numbering: the smoother gathers each vector into line order
  // (LineJacobi::vmult). deal.II's renumbering of a level costs a pass over the whole
  // hierarchy (~0.02 s per level at 1.05e6 dofs, whatever the level's size: 0.14 s for the 7
  // coarse levels, doc/performance.md); the gather costs a pass over the level's vector.
  auto number_level = [&](const unsigned int l)
  {
    data->lines[l] = find_radial_lines(*dof_handler, *mapping, l);
    data->lines[l].index_by_position();
  };
  for (unsigned int l = 0; l < n_levels; ++l)
    if (l < fine || !fine_active)
      number_level(l);
  lap("level numbering by lines");
  data->constrained_dofs.initialize(*dof_handler);
  data->constrained_dofs.make_zero_boundary_constraints(
      *dof_handler, std::set<types::boundary_id>(dirichlet_ids.begin(), dirichlet_ids.end()));
  lap("level boundary dofs");

  data->fine_is_system =
      fine_active && data->level_transfer.build(*dof_handler, data->constrained_dofs, true, comm);
  if (fine_active && !data->fine_is_system)
    number_level(fine); // the finest level's own lines after all
  if (data->fine_is_system)
  {
    data->lines[fine].order.resize(dof_handler->locally_owned_dofs().n_elements());
    data->lines[fine].start = active_line_start;
  }
  else
  {
    data->transfer = std::make_unique<MGTransferPrebuilt<VectorType>>(data->constrained_dofs);
    data->transfer->build(*dof_handler);
  }
  lap("transfer");

  data->level_constraints.resize(n_levels);
  data->by_position.assign(n_levels, 0);
  // sized once per mesh: the smoothers of every prepare() hold references to them
  data->level_operators.resize(n_levels);
  data->level_matrices.resize(0, fine);
  for (unsigned int l = 0; l < n_levels; ++l)
  {
    if (data->is_system_level(l))
      continue; // the system matrix, with the system's constraints
    IndexSet relevant;
    DoFTools::extract_locally_relevant_level_dofs(*dof_handler, l, relevant);
    auto &c = data->level_constraints[l];
    c.reinit(relevant);
    c.add_lines(data->constrained_dofs.get_boundary_indices(l));
    c.close();
    const IndexSet &owned = dof_handler->locally_owned_mg_dofs(l);
    // boundary constraints only: MGTools' pattern from the level cells' dofs by local index, and
    // the level assembly adds the cells without boundary dofs by position
    data->by_position[l] = CellSparsity::applies(owned, c, comm);
    if (data->by_position[l])
    {
      CellSparsity::reinit(data->level_matrices[l], owned,
                           CellSparsity::level_cell_dofs(*dof_handler, l),
                           dof_handler->get_fe().n_dofs_per_cell(), c, true, comm);
      continue;
    }
    DynamicSparsityPattern dsp(relevant);
    MGTools::make_sparsity_pattern(*dof_handler, dsp, l, c);
    SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
    data->level_matrices[l].reinit(owned, owned, dsp, comm);
  }

  lap("level sparsity");
}

void FilmMultigrid::prepare(const MatrixType &fine_matrix, const Coefficient &K,
                            const unsigned int n_gauss, const Parameters &parameters)
{
  LapTimer lap(lap_times);
  const auto &tria = dof_handler->get_triangulation();
  const unsigned int n_levels = tria.n_global_levels(), fine = n_levels - 1;
  const auto &fe = dof_handler->get_fe();
  const unsigned int n = fe.n_dofs_per_cell();

  // Re-discretised level operators: the same bilinear form with K at the level cells'
  // quadrature points (the film is analytic, so every level sees the true h(r, theta)).
  const QGauss<2> quadrature(n_gauss);
  FEValues<2> fe_values(*mapping, fe, quadrature,
                        update_gradients | update_quadrature_points | update_JxW_values);
  FullMatrix<double> cell_matrix(n, n);
  std::vector<types::global_dof_index> dofs(n);
  std::vector<Tensor<1, 2>> k_grad(n);
  // K grad phi_j . grad phi_i JxW summed over the points, from either kind of values
  auto add_point = [&](const auto &values, const unsigned int q, const Tensor<2, 2> &Kq)
  {
    const Tensor<2, 2> KJ = Kq * values.JxW(q);
    for (unsigned int j = 0; j < n; ++j)
      k_grad[j] = KJ * values.shape_grad(j, q);
    for (unsigned int i = 0; i < n; ++i)
    {
      const Tensor<1, 2> gi = values.shape_grad(i, q);
      for (unsigned int j = 0; j < n; ++j)
        cell_matrix(i, j) += gi * k_grad[j];
    }
  };
  // Every level is a polar grid: the cells of a radial row are one cell turned (as in the
  // assembly of the system, ReynoldsSolver::assemble_system), and an isotropic K = k I needs
  // only the products of the gradients, the same on the whole row.
  PolarCellValues polar(*mapping, fe, quadrature);
  for (unsigned int l = 0; l < n_levels; ++l)
  {
    if (data->is_system_level(l))
      continue;
    auto &matrix = data->level_matrices[l];
    matrix = 0;
    for (const auto &cell : dof_handler->mg_cell_iterators_on_level(l))
      if (cell->is_locally_owned_on_level())
      {
        cell_matrix = 0;
        if (polar.reinit(cell))
          for (const unsigned int q : polar.quadrature_point_indices())
          {
            const Tensor<2, 2> Kq = K(polar.quadrature_point(q));
            if (Kq[0][1] == 0 && Kq[1][0] == 0 && Kq[0][0] == Kq[1][1])
            {
              const double k = Kq[0][0], *gram = polar.gram(q);
              double *a = &cell_matrix(0, 0);
              for (unsigned int ij = 0; ij < n * n; ++ij)
                a[ij] += k * gram[ij];
            }
            else
              add_point(polar, q, Kq);
          }
        else
        {
          fe_values.reinit(cell);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            add_point(fe_values, q, K(fe_values.quadrature_point(q)));
        }
        cell->get_mg_dof_indices(dofs);
        // a cell without boundary dofs: distribute_local_to_global's sums, by position
        CellSparsity::distribute(data->level_constraints[l], data->by_position[l], cell_matrix,
                                 dofs, matrix);
      }
    matrix.compress(VectorOperation::add);
  }

  lap("level assembly");
  data->operators.matrices.resize(n_levels);
  for (unsigned int l = 0; l < n_levels; ++l)
    data->operators.matrices[l] =
        data->is_system_level(l) ? &fine_matrix : &data->level_matrices[l];
  // The finest level's stencil: only where that level is the system (numbered by lines).
  Assert(data->level_operators.size() == n_levels, ExcInternalError());
  for (unsigned int l = 0; l < n_levels; ++l)
  {
    data->level_operators[l].matrix = data->operators.matrices[l];
    data->level_operators[l].stencil = nullptr;
  }
  if (data->fine_is_system && parameters.single_precision_finest)
  {
    data->fine_stencil.initialize(fine_matrix, data->lines[fine].start);
    data->level_operators[fine].stencil = &data->fine_stencil;
    lap("finest level stencil");
  }

  // Smoothers: Chebyshev around radial line Jacobi, spectrum estimated by a few CG steps.
  data->smoother.smoothers.resize(0, fine);
  for (unsigned int l = 1; l < n_levels; ++l)
  {
    const MatrixType &A = *data->operators.matrices[l];
    const LevelOperator &level_operator = data->level_operators[l];
    typename Smoother::AdditionalData smoother_data;
    smoother_data.preconditioner = std::make_shared<LineJacobi>();
    smoother_data.preconditioner->initialize(A, data->lines[l]);
    lap("line factorisations");
    smoother_data.degree = parameters.smoother_degree;
    smoother_data.smoothing_range = parameters.smoothing_range;
    // Largest eigenvalue of B^-1 A by CG from a random start (Lanczos estimates). deal.II's own
    // estimate starts Trilinos vectors from a constant, which the line solves almost invert:
    // the estimate then missed the top of the spectrum and the smoother diverged on some meshes.
    {
      VectorType x(A.locally_owned_range_indices(), A.get_mpi_communicator()), b(x);
      std::uint64_t state =
          88172645463325252ull + A.locally_owned_range_indices().nth_index_in_set(0);
      // in line order: the same start on a level numbered by lines or not
      for (unsigned int p = 0; p < data->lines[l].size(); ++p)
      {
        state ^= state << 13; // xorshift64
        state ^= state >> 7;
        state ^= state << 17;
        b.begin()[data->lines[l].index(p)] = double(state >> 11) / double(1ull << 53) - 0.5;
      }
      IterationNumberControl control(eigenvalue_iterations, 1e-300, false, false);
      SolverCG<VectorType> cg(control);
      double largest = 1;
      cg.connect_eigenvalues_slot(
          [&](const std::vector<double> &eigenvalues)
          {
            if (!eigenvalues.empty())
              largest = eigenvalues.back();
          });
      cg.solve(level_operator, x, b, *smoother_data.preconditioner);
      smoother_data.eig_cg_n_iterations = 0;
      smoother_data.max_eigenvalue = 1.2 * largest;
    }
    lap("eigenvalue estimates");
    data->smoother.smoothers[l].initialize(level_operator, smoother_data);
  }
  data->coarse.direct.factorize(*data->operators.matrices[0]);
  lap("coarse factorisation");

  if (data->fine_is_system && data->defect.max_level() != fine)
  {
    data->defect.resize(0, fine);
    data->solution.resize(0, fine);
    data->residual.resize(0, fine);
    for (unsigned int l = 0; l < n_levels; ++l)
    {
      // the finest level is the system: its vectors have the system's (active) dofs
      data->defect[l].reinit(l == fine ? dof_handler->locally_owned_dofs()
                                       : dof_handler->locally_owned_mg_dofs(l),
                             communicator);
      data->solution[l].reinit(data->defect[l]);
      data->residual[l].reinit(data->defect[l]);
    }
  }
  if (!data->fine_is_system)
  {
    data->multigrid = std::make_unique<Multigrid<VectorType>>(
        data->operators, data->coarse, *data->transfer, data->smoother, data->smoother);
    data->preconditioner =
        std::make_unique<PreconditionMG<2, VectorType, MGTransferPrebuilt<VectorType>>>(
            *dof_handler, *data->multigrid, *data->transfer);
  }
  lap("vectors");
}

void FilmMultigrid::vmult(VectorType &dst, const VectorType &src) const
{
  if (!data->fine_is_system)
  {
    data->preconditioner->vmult(dst, src);
    return;
  }
  // The finest level and the system have the same owned dofs in the same order.
  const unsigned int fine = data->defect.max_level();
  std::copy(src.begin(), src.end(), data->defect[fine].begin());
  data->v_step(fine);
  std::copy(data->solution[fine].begin(), data->solution[fine].end(), dst.begin());
}

} // namespace sealfe
