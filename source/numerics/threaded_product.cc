#include <sealfe/numerics/threaded_product.h>

#include <deal.II/base/parallel.h>

namespace sealfe::numerics
{
bool threaded_product(const Epetra_CrsMatrix &A, const double *x, double *y)
{
  if (A.Importer() != nullptr || !A.Filled() || !A.StorageOptimized())
    return false;
  int *offsets = nullptr, *columns = nullptr;
  double *values = nullptr;
  if (A.ExtractCrsDataPointers(offsets, columns, values) != 0)
    return false;
  // Without an importer the column map is the domain map: column index = index into x.
  const auto rows = [=](const int first, const int last)
  {
    for (int i = first; i < last; ++i)
    {
      double sum = 0;
      for (int e = offsets[i]; e < offsets[i + 1]; ++e)
        sum += values[e] * x[columns[e]];
      y[i] = sum;
    }
  };
  // a grain of 2048 rows (~3e4 entries of Q2): task overhead well below the work
  dealii::parallel::apply_to_subranges(0, A.NumMyRows(), rows, 2048);
  return true;
}

void threaded_vmult(const dealii::TrilinosWrappers::SparseMatrix &A,
                    dealii::TrilinosWrappers::MPI::Vector &dst,
                    const dealii::TrilinosWrappers::MPI::Vector &src)
{
  if (!threaded_product(A.trilinos_matrix(), src.begin(), dst.begin()))
    A.vmult(dst, src);
}
} // namespace sealfe::numerics
