// The matrix-vector product y = A x of a one-rank Epetra matrix with its rows split over the
// threads deal.II allows this process (MultithreadInfo): the CG's and the coarse levels' products,
// which Epetra does on one thread.
#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Epetra_CrsMatrix.h>

namespace sealfe::numerics
{
/// y = A x, the rows split over deal.II's threads (parallel::apply_to_subranges; on one thread
/// the same loop, unsplit); each row is summed by one thread in the order of its entries, so the
/// result has the same bits on any number of threads. x is indexed by A's columns, y by its
/// rows. Returns false, leaving y untouched, where the product cannot be done here: a column map
/// that is not the domain map (columns owned by other ranks: Epetra's Multiply imports them), or
/// rows not held in one array (a matrix whose storage was not optimised by FillComplete).
bool threaded_product(const Epetra_CrsMatrix &A, const double *x, double *y);

/// dst = A src: threaded_product where it applies, else Epetra's Multiply (several ranks).
void threaded_vmult(const dealii::TrilinosWrappers::SparseMatrix &A,
                    dealii::TrilinosWrappers::MPI::Vector &dst,
                    const dealii::TrilinosWrappers::MPI::Vector &src);
} // namespace sealfe::numerics
