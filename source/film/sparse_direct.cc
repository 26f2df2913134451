#include <sealfe/film/sparse_direct.h>

#include <deal.II/base/index_set.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Amesos_Mumps.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Teuchos_ParameterList.hpp>

#include <stdexcept>
#include <string>

namespace sealfe
{
SparseDirect::SparseDirect() = default;
SparseDirect::~SparseDirect() = default;

void SparseDirect::clear()
{
  solver.reset();
  problem.reset();
  pattern_owner = nullptr;
  pattern_entries = -1;
}

void SparseDirect::factorize(const dealii::TrilinosWrappers::SparseMatrix &matrix)
{
  const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
  // The symbolic analysis (BTF, AMD ordering) depends on the pattern only: a Newton Jacobian
  // assembled into the same matrix object has the same one.
  const bool same_pattern =
      solver && pattern_owner == &A && pattern_entries == A.NumGlobalNonzeros64();
  if (!same_pattern)
  {
    clear();
    problem = std::make_unique<Epetra_LinearProblem>();
    problem->SetOperator(const_cast<Epetra_CrsMatrix *>(&A));
    // KLU (left-looking, no dense kernels) is quickest on small systems; above a few 1e4
    // unknowns MUMPS's multifrontal factorisation with dense BLAS-3 fronts is 2-7x faster on these
    // 2D meshes (doc/performance.md "Direct solver"). AMD ordering: measured quicker than METIS
    // nested dissection and MUMPS's automatic choice at 2.6e5 and 1e6 unknowns.
    package = A.NumGlobalRows64() < multifrontal_limit ? "KLU" : "MUMPS";
    Amesos factory;
    solver.reset(
        factory.Create(package == std::string("KLU") ? "Amesos_Klu" : "Amesos_Mumps", *problem));
    if (!solver)
      throw std::runtime_error(std::string("Reynolds solver: Amesos ") + package +
                               " is not available");
    Teuchos::ParameterList parameters;
    solver->SetParameters(parameters);
    if (auto *mumps = dynamic_cast<Amesos_Mumps *>(solver.get()))
      mumps->SetICNTL(7, 0); // AMD
    if (solver->SymbolicFactorization() != 0)
      throw std::runtime_error(std::string("Reynolds solver: ") + package +
                               " symbolic factorisation failed");
    pattern_owner = &A;
    pattern_entries = A.NumGlobalNonzeros64();
  }
  else
    ++reused_symbolic;
  if (solver->NumericFactorization() != 0)
    throw std::runtime_error(std::string("Reynolds solver: ") + package +
                             " factorisation failed (singular matrix)");
}

void SparseDirect::solve(const dealii::TrilinosWrappers::MPI::Vector &b,
                         dealii::TrilinosWrappers::MPI::Vector &x)
{
  problem->SetLHS(&x.trilinos_vector());
  problem->SetRHS(const_cast<Epetra_MultiVector *>(
      static_cast<const Epetra_MultiVector *>(&b.trilinos_vector())));
  if (solver->Solve() != 0)
    throw std::runtime_error(std::string("Reynolds solver: ") + package + " solve failed");
}

std::vector<bool> grow_in_graph(const dealii::TrilinosWrappers::SparseMatrix &matrix,
                                std::vector<bool> marked, const unsigned int layers)
{
  const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
  for (unsigned int layer = 0; layer < layers; ++layer)
  {
    std::vector<bool> grown(marked);
    for (int row = 0; row < A.NumMyRows(); ++row)
    {
      if (!marked[A.RowMap().GID64(row)])
        continue;
      int n;
      double *values;
      int *columns;
      A.ExtractMyRowView(row, n, values, columns);
      for (int k = 0; k < n; ++k)
        grown[A.ColMap().GID64(columns[k])] = true;
    }
    marked.swap(grown);
  }
  return marked;
}

void solve_on_subset(const dealii::TrilinosWrappers::SparseMatrix &matrix,
                     const std::vector<bool> &subset,
                     const dealii::TrilinosWrappers::MPI::Vector &b,
                     dealii::TrilinosWrappers::MPI::Vector &x)
{
  const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
  std::vector<long long> local(subset.size(), -1), global;
  for (std::size_t i = 0; i < subset.size(); ++i)
    if (subset[i])
    {
      local[i] = global.size();
      global.push_back(i);
    }
  const unsigned int n = global.size();
  dealii::DynamicSparsityPattern pattern(n, n);
  std::vector<std::vector<std::pair<unsigned int, double>>> rows(n);
  for (unsigned int r = 0; r < n; ++r)
  {
    int entries;
    double *values;
    int *columns;
    A.ExtractMyRowView(A.RowMap().LID(static_cast<long long>(global[r])), entries, values, columns);
    for (int k = 0; k < entries; ++k)
    {
      const long long c = local[A.ColMap().GID64(columns[k])];
      if (c >= 0)
      {
        pattern.add(r, c);
        rows[r].emplace_back(c, values[k]);
      }
    }
  }
  const dealii::IndexSet all = dealii::complete_index_set(n);
  dealii::TrilinosWrappers::SparseMatrix sub;
  sub.reinit(all, all, pattern, MPI_COMM_SELF);
  for (unsigned int r = 0; r < n; ++r)
    for (const auto &[c, value] : rows[r])
      sub.set(r, c, value);
  sub.compress(dealii::VectorOperation::insert);
  dealii::TrilinosWrappers::MPI::Vector sub_b(all, MPI_COMM_SELF), sub_x(all, MPI_COMM_SELF);
  for (unsigned int r = 0; r < n; ++r)
    sub_b[r] = b[global[r]];
  SparseDirect lu;
  lu.factorize(sub);
  lu.solve(sub_b, sub_x);
  for (unsigned int r = 0; r < n; ++r)
    x[global[r]] = sub_x[r];
}

} // namespace sealfe
