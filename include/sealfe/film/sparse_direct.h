// SparseDirect: a sparse LU factorisation (Amesos: KLU for small systems, MUMPS above) that keeps
// its symbolic analysis (ordering, block structure) across matrices of one sparsity pattern, as
// the Newton systems of the cavitation models are.
#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <memory>
#include <vector>

class Amesos_BaseSolver;
class Epetra_LinearProblem;
class Epetra_CrsMatrix;

namespace sealfe
{
/// KLU or MUMPS through Amesos. factorize() of a matrix with the pattern of the previous one (the
/// same Trilinos matrix object, unchanged number of entries) repeats only the numeric
/// factorisation.
class SparseDirect
{
public:
  /// From this many unknowns on MUMPS (multifrontal, AMD ordering) instead of KLU: the measured
  /// crossover on the annulus meshes is between 1.7e4 and 6.7e4 unknowns.
  static constexpr long long multifrontal_limit = 20000;

  SparseDirect();
  ~SparseDirect();
  /// Factorise `matrix` (kept by reference until the next factorize() or clear()).
  void factorize(const dealii::TrilinosWrappers::SparseMatrix &matrix);
  /// x = A^-1 b with the last factorisation.
  void solve(const dealii::TrilinosWrappers::MPI::Vector &b,
             dealii::TrilinosWrappers::MPI::Vector &x);
  void clear();
  bool initialized() const { return static_cast<bool>(solver); }
  /// Factorisations that reused the symbolic analysis of an earlier one.
  unsigned int numeric_only() const { return reused_symbolic; }
  /// "KLU" or "MUMPS": the package of the last factorisation ("" before the first).
  const char *package_name() const { return package; }

private:
  std::unique_ptr<Epetra_LinearProblem> problem;
  std::unique_ptr<Amesos_BaseSolver> solver;
  const Epetra_CrsMatrix *pattern_owner = nullptr;
  long long pattern_entries = -1;
  unsigned int reused_symbolic = 0;
  const char *package = "";
};

/// The dofs of `marked` (flags by global index) and their neighbours in the matrix graph, `layers`
/// times (serial matrix).
std::vector<bool> grow_in_graph(const dealii::TrilinosWrappers::SparseMatrix &matrix,
                                std::vector<bool> marked, unsigned int layers);

/// x_S = A_SS^-1 b_S on the dofs S with `subset` set (the others of x untouched): a KLU
/// factorisation of the principal submatrix (serial matrix; KLU or MUMPS by its size).
void solve_on_subset(const dealii::TrilinosWrappers::SparseMatrix &matrix,
                     const std::vector<bool> &subset,
                     const dealii::TrilinosWrappers::MPI::Vector &b,
                     dealii::TrilinosWrappers::MPI::Vector &x);

} // namespace sealfe
