// CellSparsity: the sparsity of a matrix assembled cell by cell with Dirichlet constraints only,
// built from the cells' dofs by local index, and cell matrices added by position.
#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <mpi.h>

#include <vector>

namespace sealfe
{
/// The same sparsity pattern as DoFTools::make_sparsity_pattern(..., constraints, false) (or
/// MGTools' on a level), SparsityTools::distribute_sparsity_pattern and
/// TrilinosWrappers::SparseMatrix::reinit, and the same sums as
/// AffineConstraints::distribute_local_to_global for a cell without constrained dofs, without
/// their global index lookups and dynamic pattern. Measured at 1.05e6 Q2 dofs (128 x 2048 cells,
/// benchmarks/reynolds_speed/case.prm with cg-gmg, one rank, session 11; doc/performance.md,
/// "cg-gmg at 1.05e6 dofs: structured set-up"): system sparsity + matrix 0.39 -> 0.24 s, level
/// sparsity 0.12 -> 0.05 s, assembly -0.07 s, level assembly -0.035 s; two ranks (session 14):
/// whole process 3.77 -> 3.37 s. Only where it is provably the same: every constraint a Dirichlet
/// one (a line without entries, which adds no coupling) and each rank owning one range of dofs, the
/// ranges in rank order (deal.II's numbering: a dof's owner follows from the ranges); else the
/// caller keeps deal.II's generic path (applies() is false). On several ranks each rank builds the
/// rows of its cells' dofs and sends the rows of dofs it does not own to their owners, and a cell's
/// rows of such dofs go into the Epetra matrix's own off-rank store (deal.II's: a separate
/// off-rank matrix), both added to the owners' entries by an Epetra_Export at compress().
class CellSparsity
{
public:
  /// Whether the path applies: every constraint line of `constraints` without entries, and
  /// `owned` all dofs 0..n-1 on one rank, or on several one range per rank, the ranges in rank
  /// order. Collective on several ranks (all of them get the same answer).
  static bool applies(const dealii::IndexSet &owned,
                      const dealii::AffineConstraints<double> &constraints, MPI_Comm comm);

  /// matrix = 0 with the pattern of a matrix assembled over cells whose dofs are `cell_dofs`
  /// (`dofs_per_cell` numbers per cell): row i holds the dofs of the cells around i (sorted).
  /// keep_constrained_dofs = false (DoFTools' pattern of the system): without the constrained
  /// ones, and a constrained row holds only its diagonal; true (MGTools' level pattern): all of
  /// them. One rank: column map = row map, so a local column index is the dof number; several:
  /// `cell_dofs` are this rank's cells' (active_cell_dofs, level_cell_dofs), the column map
  /// is the owned dofs in order and then the others as Epetra orders them for deal.II's matrix
  /// (the rows stored in the same order). Collective on several ranks.
  static void reinit(dealii::TrilinosWrappers::SparseMatrix &matrix, const dealii::IndexSet &owned,
                     const std::vector<unsigned int> &cell_dofs, unsigned int dofs_per_cell,
                     const dealii::AffineConstraints<double> &constraints,
                     bool keep_constrained_dofs, MPI_Comm comm);

  /// The dof numbers of the active cells of `dof_handler`, cell after cell in the order of
  /// active_cell_iterators(), the locally owned ones (reinit's `cell_dofs` for the system).
  static std::vector<unsigned int> active_cell_dofs(const dealii::DoFHandler<2> &dof_handler);
  /// The same with the level dofs of this rank's cells of `level` (mg_cell_iterators_on_level()).
  static std::vector<unsigned int> level_cell_dofs(const dealii::DoFHandler<2> &dof_handler,
                                                   unsigned int level);

  /// Whether none of `dofs` is constrained: a cell add() may take (else
  /// distribute_local_to_global, which also applies the constraints).
  static bool unconstrained(const dealii::AffineConstraints<double> &constraints,
                            const std::vector<dealii::types::global_dof_index> &dofs);

  /// matrix(dofs[i], dofs[j]) += cell_matrix(i, j) for every i, j: what
  /// distribute_local_to_global adds for a cell without constrained dofs (each entry receives the
  /// same one addition, so the sums over the cells in the same order are the same bits). The
  /// matrix must come from reinit() (an owned column's local index is its place in the owned
  /// range); throws if an entry is not in its pattern. The rows of dofs another rank owns go to
  /// matrix.add (kept by Epetra until compress()).
  static void add(dealii::TrilinosWrappers::SparseMatrix &matrix,
                  const dealii::FullMatrix<double> &cell_matrix,
                  const std::vector<dealii::types::global_dof_index> &dofs);
  /// vector(dofs[i]) += cell_vector(i): the owned entries by position, the others through
  /// vector.add (kept until compress; zeros left out, as by distribute_local_to_global).
  static void add(dealii::TrilinosWrappers::MPI::Vector &vector,
                  const dealii::Vector<double> &cell_vector,
                  const std::vector<dealii::types::global_dof_index> &dofs);

  /// A cell's matrix and right-hand side into the system: by position (add) where `by_position`
  /// (the matrix has reinit()'s pattern) and unconstrained(constraints, dofs), else
  /// constraints.distribute_local_to_global (which also applies the constraints). The two give
  /// the same sums, so the choice is one of speed only.
  static void distribute(const dealii::AffineConstraints<double> &constraints, bool by_position,
                         const dealii::FullMatrix<double> &cell_matrix,
                         const dealii::Vector<double> &cell_vector,
                         const std::vector<dealii::types::global_dof_index> &dofs,
                         dealii::TrilinosWrappers::SparseMatrix &matrix,
                         dealii::TrilinosWrappers::MPI::Vector &vector);
  /// The same for a matrix alone (the multigrid levels) and for a vector alone.
  static void distribute(const dealii::AffineConstraints<double> &constraints, bool by_position,
                         const dealii::FullMatrix<double> &cell_matrix,
                         const std::vector<dealii::types::global_dof_index> &dofs,
                         dealii::TrilinosWrappers::SparseMatrix &matrix);
  static void distribute(const dealii::AffineConstraints<double> &constraints, bool by_position,
                         const dealii::Vector<double> &cell_vector,
                         const std::vector<dealii::types::global_dof_index> &dofs,
                         dealii::TrilinosWrappers::MPI::Vector &vector);
};

} // namespace sealfe
