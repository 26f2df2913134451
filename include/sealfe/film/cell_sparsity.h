// CellSparsity: on one rank, the sparsity of a matrix assembled cell by cell with Dirichlet
// constraints only, built by local index from the cells' dofs, and cell matrices added by position.
#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <mpi.h>

#include <vector>

namespace sealfe
{
/// The same sparsity pattern as DoFTools::make_sparsity_pattern(..., constraints, false) (or
/// MGTools' on a level) followed by TrilinosWrappers::SparseMatrix::reinit, and the same sums
/// as AffineConstraints::distribute_local_to_global for a cell without constrained dofs, without
/// their global index lookups and dynamic pattern. Measured at 1.05e6 Q2 dofs (128 x 2048 cells,
/// benchmarks/reynolds_speed/case.prm with cg-gmg, one rank, session 11; doc/performance.md,
/// "cg-gmg at 1.05e6 dofs: structured set-up"): system sparsity + matrix 0.39 -> 0.24 s, level
/// sparsity 0.12 -> 0.05 s, assembly -0.07 s, level assembly -0.035 s. Only where it is provably
/// the same: one rank owning every dof (local index = global number) and every constraint a
/// Dirichlet one (a line without entries, which adds no coupling); else the caller keeps
/// deal.II's generic path (applies() is false).
class CellSparsity
{
public:
  /// Whether the path applies: one rank in `comm`, `owned` all dofs 0..n-1, and every
  /// constraint line of `constraints` without entries.
  static bool applies(const dealii::IndexSet &owned,
                      const dealii::AffineConstraints<double> &constraints, MPI_Comm comm);

  /// matrix = 0 with the pattern of a matrix assembled over cells whose dofs are `cell_dofs`
  /// (`dofs_per_cell` numbers per cell): row i holds the dofs of the cells around i (sorted).
  /// keep_constrained_dofs = false (DoFTools' pattern of the system): without the constrained
  /// ones, and a constrained row holds only its diagonal; true (MGTools' level pattern): all of
  /// them. Column map = row map, so a local column index is the dof number.
  static void reinit(dealii::TrilinosWrappers::SparseMatrix &matrix, const dealii::IndexSet &owned,
                     const std::vector<unsigned int> &cell_dofs, unsigned int dofs_per_cell,
                     const dealii::AffineConstraints<double> &constraints,
                     bool keep_constrained_dofs, MPI_Comm comm);

  /// The dof numbers of the active cells of `dof_handler`, cell after cell in the order of
  /// active_cell_iterators() (reinit's `cell_dofs` for the system; one rank: every cell owned).
  static std::vector<unsigned int> active_cell_dofs(const dealii::DoFHandler<2> &dof_handler);
  /// The same with the level dofs of the cells of `level` (mg_cell_iterators_on_level()).
  static std::vector<unsigned int> level_cell_dofs(const dealii::DoFHandler<2> &dof_handler,
                                                   unsigned int level);

  /// Whether none of `dofs` is constrained: a cell add() may take (else
  /// distribute_local_to_global, which also applies the constraints).
  static bool unconstrained(const dealii::AffineConstraints<double> &constraints,
                            const std::vector<dealii::types::global_dof_index> &dofs);

  /// matrix(dofs[i], dofs[j]) += cell_matrix(i, j) for every i, j: what
  /// distribute_local_to_global adds for a cell without constrained dofs (each entry receives the
  /// same one addition, so the sums over the cells in the same order are the same bits). The
  /// matrix must come from reinit() (local column index = dof number); throws if an entry is not
  /// in its pattern.
  static void add(dealii::TrilinosWrappers::SparseMatrix &matrix,
                  const dealii::FullMatrix<double> &cell_matrix,
                  const std::vector<dealii::types::global_dof_index> &dofs);
};

} // namespace sealfe
