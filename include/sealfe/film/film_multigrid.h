// FilmMultigrid: a geometric multigrid V-cycle (matrix-based, Trilinos matrices) for the symmetric
// film systems on the built-in annulus, whose mesh is a hierarchy of globally refined levels.
#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <functional>
#include <map>
#include <memory>

namespace sealfe
{
/// Preconditioner for A p = b, A_ij = int K grad phi_j . grad phi_i with zero Dirichlet rows on
/// both circles (the full film, its linearisation, rough faces). One V-cycle: the level matrices
/// are re-discretisations of the same operator on the coarser levels of the mesh (K evaluated at
/// the level cells' quadrature points), Chebyshev smoothing around radial line Jacobi (LineJacobi,
/// line_jacobi.h: each line of dofs at one angle solved exactly, the cells being long in theta)
/// on every level, KLU on the coarsest level, prolongation by the finite-element embedding. On
/// the finest level, where it is the system, the smoother's and the residual's products take
/// the system matrix in single precision (LineStencilMatrix: half the memory read; the CG keeps
/// the double matrix).
///
/// The finest level is the system itself where it can be: its operator is the system matrix,
/// its vectors the system's, its lines the active ones (number_by_radial_lines), and the last
/// prolongation matrix takes the active dof numbers of that level's cells as its rows, so the
/// level's own dofs are never used (that level is never numbered, constrained or assembled).
/// The coarser levels keep deal.II's level numbering (the line smoother gathers their vectors
/// into line order). Fallback: where a locally owned active cell is not on the finest level
/// (a mesh that is not globally refined), the active dofs were not numbered by lines, or the
/// transfer does not reach every owned active dof from a parent cell its rank sees (possible
/// on several ranks), the finest level gets its own lines and level matrix like the others and
/// the transfer is deal.II's MGTransferPrebuilt (copies between the active and level numbers);
/// every rank takes the same branch. Either way the same prolongation, entry for entry.
class FilmMultigrid
{
public:
  using VectorType = dealii::TrilinosWrappers::MPI::Vector;
  /// The (scaled) pressure-flow tensor K at a point of the dam.
  using Coefficient = std::function<dealii::Tensor<2, 2>(const dealii::Point<2> &)>;

  /// Chebyshev degree of the smoother (pre- and post-smoothing each) and the fraction of the
  /// spectrum it damps ([lambda_max / range, lambda_max]). Degree 2 on [lambda_max / 5,
  /// lambda_max]: with the radial line solves the coarse levels take the rest of the spectrum,
  /// and 5 matrix products per V-cycle on the finest level instead of 9 (degree 4 on
  /// [lambda_max / 20, lambda_max]) cost about a third less CG time (measured at 1.05e6 Q2
  /// dofs: 9 iterations instead of 8, CG 1.2 s instead of 1.85 s; 6-17 iterations over
  /// degrees 1-3 and Ntheta/Nr = 1-32, doc/performance.md).
  struct Parameters
  {
    unsigned int smoother_degree = 2;
    double smoothing_range = 5;
    /// The smoother's and the V-cycle's products on the finest level with the system matrix's
    /// values in single precision (LineStencilMatrix), where that level is the system; the CG
    /// keeps the double matrix, so the solution is that of the same system.
    bool single_precision_finest = true;
  };

  FilmMultigrid();
  ~FilmMultigrid();

  /// Number the (active) dofs by radial lines: by angle, then radius, within each rank's set,
  /// so that the finest level is the system matrix with contiguous line blocks. The coarser
  /// levels keep deal.II's numbering (the smoother gathers their vectors into line order).
  void number_by_radial_lines(dealii::DoFHandler<2> &dof_handler,
                              const dealii::Mapping<2> &mapping);

  /// Whether `dof_handler`'s mesh has a level hierarchy worth a multigrid (at least 2 levels).
  static bool has_hierarchy(const dealii::DoFHandler<2> &dof_handler);

  /// Once per mesh: level dofs (distributes them), zero-Dirichlet level constraints on the two
  /// boundary ids, level sparsity, transfer. `comm`: the communicator of the system's vectors
  /// and matrix, which the level objects share (a serial mesh's own is MPI_COMM_SELF).
  void setup(dealii::DoFHandler<2> &dof_handler, const dealii::Mapping<2> &mapping,
             const std::vector<dealii::types::boundary_id> &dirichlet_ids, MPI_Comm comm);
  bool is_setup() const { return dof_handler != nullptr; }
  void clear();

  /// For each new fine matrix: assemble the coarser level matrices with `K` and the Gauss rule of
  /// `n_gauss` points per direction, estimate the smoothers' spectra, factorise the coarsest.
  void prepare(const dealii::TrilinosWrappers::SparseMatrix &fine, const Coefficient &K,
               unsigned int n_gauss, const Parameters &parameters);

  /// dst = one V-cycle applied to src (a symmetric positive definite operator).
  void vmult(VectorType &dst, const VectorType &src) const;

  unsigned int n_levels() const;

  /// Seconds of the parts of setup() and prepare() since the last reset_times() (the owner
  /// resets them per run, so that a solver reused on one mesh reports that run's prepares only).
  const std::map<std::string, double> &times() const { return lap_times; }
  void reset_times() { lap_times.clear(); }

private:
  std::map<std::string, double> lap_times;
  struct Data;
  std::unique_ptr<Data> data;
  dealii::DoFHandler<2> *dof_handler = nullptr;
  const dealii::Mapping<2> *mapping = nullptr;
  MPI_Comm communicator = MPI_COMM_NULL; // of setup()
  /// The radial lines of the active numbering (number_by_radial_lines): first position of each
  /// line within the owned dofs; the finest level reuses them.
  std::vector<unsigned int> active_line_start;
};

} // namespace sealfe
