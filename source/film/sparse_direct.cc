#include <sealfe/film/sparse_direct.h>
#include <sealfe/numerics/gather.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Amesos_Mumps.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_LinearProblem.h>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace sealfe
{
namespace
{
/// Amesos_Mumps with a solve of several right-hand sides in one MUMPS call (NRHS > 1): Amesos
/// calls MUMPS once per column of a multivector; and, on several ranks, repeated numeric
/// factorisations that refresh the values of the redistributed matrix in place. It relies on
/// Amesos_Mumps's protected members (the MUMPS structure MDS, the redistributed matrix and its
/// triplets), an implementation detail of the Trilinos version it was written for (Debian 12's
/// Trilinos 13.2): recheck it when Trilinos changes.
class BlockMumps : public Amesos_Mumps
{
public:
  using Amesos_Mumps::Amesos_Mumps;

  /// On several ranks Amesos_Mumps gives MUMPS the matrix redistributed over an even split of
  /// the rows, and it builds that copy anew (a new Epetra_CrsMatrix, an Import, FillComplete)
  /// twice per numeric factorisation (once itself, once to read the values): 0.3-0.4 s each at
  /// 5e5 unknowns, where MUMPS's numeric factorisation itself takes 1.1-1.3 s on two ranks
  /// (doc/performance.md "MUMPS on several ranks"). A repeated factorisation of a matrix with the
  /// same pattern (the only kind SparseDirect makes) zeroes the copy it has, adds the matrix into
  /// it through the same importer and reads the values row by row, in the order of the triplets the
  /// symbolic analysis read from a copy built the same way: the same values in the same places.
  int NumericFactorization() override
  {
    // (a BlockMumps analyses one pattern: SparseDirect makes a new one for another)
    if (Comm().NumProc() == 1 || NumNumericFact() == 0 || RedistrMatrix_.is_null() ||
        !RedistrMatrix_->Filled())
      return Amesos_Mumps::NumericFactorization();
    Epetra_CrsMatrix &copy = *RedistrMatrix_;
    int status = copy.PutScalar(0.0);
    status += copy.Import(Matrix(), RedistrImporter(), Add);
    std::size_t count = 0;
    for (int i = 0; i < copy.NumMyRows() && status == 0; ++i)
    {
      int n = 0;
      double *values = nullptr;
      status += copy.ExtractMyRowView(i, n, values);
      if (count + n > Val.size())
        status = -1;
      else
        std::copy(values, values + n, Val.begin() + count);
      count += n;
    }
    if (count != Val.size())
      status = -1;
    int failed = status != 0, any_failed = 0;
    Comm().SumAll(&failed, &any_failed, 1);
    if (any_failed)
      return -1;
    MDS.job = 2;
    if (Comm().MyPID() < MaxProcs_)
    {
      MDS.a_loc = Val.data();
      dmumps_c(&MDS);
    }
    failed = MDS.infog[0] < 0 || MDS.info[0] < 0;
    Comm().SumAll(&failed, &any_failed, 1);
    // (Amesos's status flags are private: they stay those of the first factorisation, which
    // was complete, and a failure here is an error SparseDirect throws on)
    return any_failed ? -1 : 0;
  }

  /// values[c * rows.size() + p] = (A^-1)(rows[p], columns[c]), columns ascending (one rank).
  int inverse_entries(const std::vector<unsigned int> &rows,
                      const std::vector<unsigned int> &columns, std::vector<double> &values)
  {
    // the requested entries as a sparse n x n right-hand side in compressed columns (1-based):
    // every column of the matrix, those not requested empty; the values come back in place
    const int n = MDS.n;
    std::vector<int> column_start(n + 1), entry_row;
    entry_row.reserve(rows.size() * columns.size());
    std::size_t next = 0;
    for (int j = 0; j < n; ++j)
    {
      column_start[j] = int(entry_row.size()) + 1;
      if (next < columns.size() && columns[next] == unsigned(j))
      {
        for (const unsigned int r : rows)
          entry_row.push_back(int(r) + 1);
        ++next;
      }
    }
    column_start[n] = int(entry_row.size()) + 1;
    if (next != columns.size())
      return -1; // columns not ascending, repeated or out of range
    values.assign(entry_row.size(), 0.0);
    return solve_phase(
        [&](DMUMPS_STRUC_C &id)
        {
          id.icntl[29] = 1;
          // right-hand-side columns per block of the pruned solves (ICNTL(27); MUMPS's default
          // -32 lets it choose up to 32): 256 took 0.64 s against 0.96-1.03 s for the 48 x 640
          // entries of a low-rank update at 1.05e6 unknowns (tilted seal), with the same peak
          // memory (doc/performance.md "Session 20")
          id.icntl[26] = 256;
          id.nz_rhs = int(entry_row.size());
          id.nrhs = n;
          id.lrhs = n;
          id.irhs_ptr = column_start.data();
          id.irhs_sparse = entry_row.data();
          id.rhs_sparse = values.data();
        });
  }

  /// The n x m column-major block X overwritten by A^-1 X (one rank: the host holds it all).
  int solve_block(double *X, const int n, const int m)
  {
    return solve_phase(
        [&](DMUMPS_STRUC_C &id)
        {
          id.nrhs = m;
          id.lrhs = n;
          id.rhs = X;
        });
  }

private:
  /// One MUMPS solve (job 3) with the right-hand side `set_rhs` describes; the right-hand-side
  /// fields Amesos set for its own solves are restored afterwards. Returns INFO(1).
  template <class SetRhs>
  int solve_phase(SetRhs &&set_rhs)
  {
    const DMUMPS_STRUC_C saved = MDS;
    set_rhs(MDS);
    MDS.job = 3;
    dmumps_c(&MDS);
    const int info = MDS.info[0];
    MDS.icntl[26] = saved.icntl[26];
    MDS.icntl[29] = saved.icntl[29];
    MDS.nz_rhs = saved.nz_rhs;
    MDS.nrhs = saved.nrhs;
    MDS.lrhs = saved.lrhs;
    MDS.rhs = saved.rhs;
    MDS.irhs_ptr = saved.irhs_ptr;
    MDS.irhs_sparse = saved.irhs_sparse;
    MDS.rhs_sparse = saved.rhs_sparse;
    return info;
  }
};
} // namespace

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
    // MUMPS made directly (what the factory does) as BlockMumps, for solve_block
    if (package == std::string("KLU"))
      solver.reset(factory.Create("Amesos_Klu", *problem));
    else
      solver = std::make_unique<BlockMumps>(*problem);
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

void SparseDirect::solve_block(std::vector<double> &X, const unsigned int m)
{
  const Epetra_RowMatrix &A = *dynamic_cast<const Epetra_RowMatrix *>(problem->GetOperator());
  const int n = A.NumMyRows();
  if (A.Comm().NumProc() != 1 || X.size() != static_cast<std::size_t>(n) * m)
    throw std::logic_error("SparseDirect::solve_block: one rank, n x m values");
  if (auto *mumps = dynamic_cast<BlockMumps *>(solver.get()))
  {
    if (mumps->solve_block(X.data(), n, m) != 0)
      throw std::runtime_error("Reynolds solver: MUMPS block solve failed");
    return;
  }
  // KLU: one klu_solve for the whole multivector
  const std::vector<double> B(X);
  Epetra_MultiVector x(View, A.OperatorDomainMap(), X.data(), n, m),
      b(View, A.OperatorRangeMap(), const_cast<double *>(B.data()), n, m);
  problem->SetLHS(&x);
  problem->SetRHS(&b);
  const int status = solver->Solve();
  problem->SetLHS(nullptr);
  problem->SetRHS(nullptr);
  if (status != 0)
    throw std::runtime_error(std::string("Reynolds solver: ") + package + " solve failed");
}

bool SparseDirect::inverse_entries(const std::vector<unsigned int> &rows,
                                   const std::vector<unsigned int> &columns,
                                   std::vector<double> &values)
{
  auto *mumps = dynamic_cast<BlockMumps *>(solver.get());
  if (!mumps || mumps->Comm().NumProc() != 1)
    return false;
  // MUMPS takes the columns in order: sort them, and put the values back in the caller's order
  std::vector<unsigned int> order(columns.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](unsigned a, unsigned b) { return columns[a] < columns[b]; });
  std::vector<unsigned int> sorted(columns.size());
  for (std::size_t c = 0; c < order.size(); ++c)
    sorted[c] = columns[order[c]];
  std::vector<double> sorted_values;
  if (mumps->inverse_entries(rows, sorted, sorted_values) != 0)
    throw std::runtime_error("Reynolds solver: MUMPS selected inverse entries failed");
  const std::size_t m = rows.size();
  values.resize(m * columns.size());
  for (std::size_t c = 0; c < order.size(); ++c)
    std::copy(sorted_values.begin() + c * m, sorted_values.begin() + (c + 1) * m,
              values.begin() + order[c] * m);
  return true;
}

LowRankSolve solve_column_update(SparseDirect &lu,
                                 const dealii::TrilinosWrappers::SparseMatrix &matrix,
                                 const std::vector<unsigned int> &columns,
                                 const std::vector<SparseColumn> &U, const double *b, double *x,
                                 const double min_rcond, const double max_backward_error,
                                 double &rcond, double &backward_error)
{
  rcond = backward_error = std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = matrix.m(), k = columns.size();
  if (U.size() != k)
    throw std::logic_error("solve_column_update: U must hold k columns");
  // y = A0^-1 b and EZ = E^T A0^-1 U (k x k, column-major)
  std::vector<double> y(b, b + n), EZ(k * k, 0.0), X;
  std::vector<unsigned int> support; // rows where U has entries, ascending
  for (const SparseColumn &column : U)
    for (const auto &[i, value] : column)
    {
      if (i >= n)
        throw std::logic_error("solve_column_update: a row of U beyond the matrix");
      support.push_back(i);
    }
  std::sort(support.begin(), support.end());
  support.erase(std::unique(support.begin(), support.end()), support.end());
  std::vector<double> entries; // (A0^-1)(columns[p], support[s]) at s * k + p
  const bool by_entries = k > 0 && lu.inverse_entries(columns, support, entries);
  if (by_entries || k == 0)
  {
    lu.solve_block(y, 1);
    for (std::size_t q = 0; q < k; ++q)
      for (const auto &[i, value] : U[q])
      {
        const std::size_t s = std::lower_bound(support.begin(), support.end(), i) - support.begin();
        for (std::size_t p = 0; p < k; ++p)
          EZ[q * k + p] += entries[s * k + p] * value;
      }
  }
  else
  {
    // [y Z] = A0^-1 [b U], one block solve of n x (k + 1) values (KLU: below 2e4 unknowns)
    X.assign(n * (k + 1), 0.0);
    std::copy(b, b + n, X.begin());
    for (std::size_t q = 0; q < k; ++q)
      for (const auto &[i, value] : U[q])
        X[(q + 1) * n + i] += value;
    lu.solve_block(X, k + 1);
    std::copy(X.begin(), X.begin() + n, y.begin());
    for (std::size_t q = 0; q < k; ++q)
      for (std::size_t p = 0; p < k; ++p)
        EZ[q * k + p] = X[(q + 1) * n + columns[p]];
  }
  // capacitance C = I + E^T Z and t = C^-1 E^T y
  dealii::LAPACKFullMatrix<double> C(k, k);
  dealii::Vector<double> t(k);
  for (std::size_t p = 0; p < k; ++p)
  {
    t(p) = y[columns[p]];
    for (std::size_t q = 0; q < k; ++q)
      C(p, q) = (p == q ? 1.0 : 0.0) + EZ[q * k + p];
  }
  if (k > 0)
  {
    // |E^T Z|_1: C's condition is measured against the size of the terms summed into it, so that
    // a cancellation (C = 1 + z with z near -1: A1 near singular) shows even when k = 1, where
    // the plain condition number of C is 1
    double terms = 0;
    for (std::size_t q = 0; q < k; ++q)
    {
      double column = 0;
      for (std::size_t p = 0; p < k; ++p)
        column += std::abs(EZ[q * k + p]);
      terms = std::max(terms, column);
    }
    // a zero pivot throws in deal.II: that is a singular C
    try
    {
      C.compute_lu_factorization();
    }
    catch (...)
    {
      rcond = 0;
      return LowRankSolve::ill_conditioned;
    }
    // |C^-1|_1 exactly, column by column (k is small)
    double inverse_norm = 0;
    for (std::size_t q = 0; q < k; ++q)
    {
      dealii::Vector<double> e(k);
      e(q) = 1;
      C.solve(e);
      inverse_norm = std::max(inverse_norm, e.l1_norm());
    }
    rcond = 1 / ((1 + terms) * inverse_norm);
    if (!(rcond >= min_rcond))
      return LowRankSolve::ill_conditioned;
    C.solve(t);
  }
  else
    rcond = 1;
  std::vector<double> result;
  if (by_entries)
  {
    // x = A0^-1 (b - U t)
    result.assign(b, b + n);
    for (std::size_t q = 0; q < k; ++q)
      for (const auto &[i, value] : U[q])
        result[i] -= value * t(q);
    lu.solve_block(result, 1);
  }
  else
  {
    // x = y - Z t
    result = y;
    for (std::size_t q = 0; q < k; ++q)
    {
      const double *z = X.data() + (q + 1) * n;
      for (std::size_t i = 0; i < n; ++i)
        result[i] -= z[i] * t(q);
    }
  }
  // the true residual of A1: the update is exact algebra, its round-off is checked here
  const Epetra_CrsMatrix &A1 = matrix.trilinos_matrix();
  std::vector<double> x_column(A1.NumMyCols()); // result by local column index
  for (int c = 0; c < A1.NumMyCols(); ++c)
    x_column[c] = result[A1.ColMap().GID64(c)];
  double r_max = 0, x_max = 0, b_max = 0;
  for (int row = 0; row < A1.NumMyRows(); ++row)
  {
    int entries;
    double *values;
    int *cols;
    A1.ExtractMyRowView(row, entries, values, cols);
    double r = b[A1.RowMap().GID64(row)];
    for (int e = 0; e < entries; ++e)
      r -= values[e] * x_column[cols[e]];
    r_max = std::max(r_max, std::abs(r));
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    x_max = std::max(x_max, std::abs(result[i]));
    b_max = std::max(b_max, std::abs(b[i]));
  }
  const double scale = matrix.linfty_norm() * x_max + b_max;
  backward_error = scale > 0 ? r_max / scale : 0.0;
  if (!(backward_error <= max_backward_error))
    return LowRankSolve::inaccurate;
  std::copy(result.begin(), result.end(), x);
  return LowRankSolve::solved;
}

std::vector<bool> grow_in_graph(const dealii::TrilinosWrappers::SparseMatrix &matrix,
                                const std::vector<bool> &seeds, const unsigned int layers)
{
  const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
  const MPI_Comm comm = matrix.get_mpi_communicator();
  const bool several_ranks = dealii::Utilities::MPI::n_mpi_processes(comm) > 1;
  // On several ranks each rank marks the neighbours of its own rows; the union over the ranks
  // (every row has one owner) is the layer of the whole graph. The union is taken of the seeds
  // (a rank may mark a dof another rank owns) and after each layer: layers + 1 logical-or
  // reductions of n bytes (1 MB at 1e6 unknowns).
  std::vector<unsigned char> marked(seeds.begin(), seeds.end());
  auto unite = [&](std::vector<unsigned char> &flags)
  {
    if (several_ranks)
    {
      const int ierr = MPI_Allreduce(MPI_IN_PLACE, flags.data(), static_cast<int>(flags.size()),
                                     MPI_UNSIGNED_CHAR, MPI_LOR, comm);
      AssertThrowMPI(ierr);
    }
  };
  unite(marked);
  for (unsigned int layer = 0; layer < layers; ++layer)
  {
    std::vector<unsigned char> grown(marked);
    for (int row = 0; row < A.NumMyRows(); ++row)
    {
      if (!marked[A.RowMap().GID64(row)])
        continue;
      int n;
      double *values;
      int *columns;
      A.ExtractMyRowView(row, n, values, columns);
      for (int k = 0; k < n; ++k)
        grown[A.ColMap().GID64(columns[k])] = 1;
    }
    unite(grown);
    marked.swap(grown);
  }
  return std::vector<bool>(marked.begin(), marked.end());
}

void solve_on_subset(const dealii::TrilinosWrappers::SparseMatrix &matrix,
                     const std::vector<bool> &subset,
                     const dealii::TrilinosWrappers::MPI::Vector &b,
                     dealii::TrilinosWrappers::MPI::Vector &x)
{
  const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
  const MPI_Comm comm = matrix.get_mpi_communicator();
  // The subset's own numbering (the same on every rank: `subset` is)
  std::vector<int> local(subset.size(), -1);
  std::vector<long long> global;
  for (std::size_t i = 0; i < subset.size(); ++i)
    if (subset[i])
    {
      AssertThrow(global.size() < std::size_t(std::numeric_limits<int>::max()),
                  dealii::ExcMessage("band solve: the subset has too many dofs"));
      local[i] = static_cast<int>(global.size());
      global.push_back(i);
    }
  const unsigned int n = global.size();
  // This rank's rows of A_SS and entries of b_S by the subset's numbering: integers (row, entry
  // count, the entries' columns) and values (b_S entry, the entries' values), row after row
  const Epetra_BlockMap &b_map = b.trilinos_vector().Map();
  std::vector<int> my_integers;
  std::vector<double> my_values;
  for (int row = 0; row < A.NumMyRows(); ++row)
  {
    const long long gid = A.RowMap().GID64(row);
    const int r = local[gid];
    if (r < 0)
      continue;
    const int b_index = b_map.LID(gid);
    AssertThrow(b_index >= 0, dealii::ExcMessage("band solve: b lacks an owned row"));
    int entries;
    double *values;
    int *columns;
    A.ExtractMyRowView(row, entries, values, columns);
    my_integers.push_back(r);
    my_integers.push_back(0);
    const std::size_t count = my_integers.size() - 1;
    my_values.push_back(b.trilinos_vector()[0][b_index]);
    for (int k = 0; k < entries; ++k)
      if (const int c = local[A.ColMap().GID64(columns[k])]; c >= 0)
      {
        my_integers.push_back(c);
        my_values.push_back(values[k]);
        ++my_integers[count];
      }
  }
  // On several ranks every rank gathers the whole subsystem and solves it (the ranks would wait
  // for one solver otherwise): small, a band of a few graph layers around the flipped nodes.
  const std::vector<int> integers = numerics::gather_on_every_rank(comm, my_integers);
  const std::vector<double> numbers = numerics::gather_on_every_rank(comm, my_values);

  dealii::DynamicSparsityPattern pattern(n, n);
  unsigned int rows = 0;
  for (std::size_t i = 0; i < integers.size(); i += 2 + integers[i + 1], ++rows)
    for (int e = 0; e < integers[i + 1]; ++e)
      pattern.add(integers[i], integers[i + 2 + e]);
  // every dof of the subset is some rank's row exactly once (else the ranks' subsets differ)
  AssertThrow(rows == n, dealii::ExcMessage("band solve: the ranks' rows do not make the subset"));
  const dealii::IndexSet all = dealii::complete_index_set(n);
  dealii::TrilinosWrappers::SparseMatrix sub;
  sub.reinit(all, all, pattern, MPI_COMM_SELF);
  dealii::TrilinosWrappers::MPI::Vector sub_b(all, MPI_COMM_SELF), sub_x(all, MPI_COMM_SELF);
  for (std::size_t i = 0, d = 0; i < integers.size(); i += 2 + integers[i + 1])
  {
    const int r = integers[i];
    sub_b[r] = numbers[d++];
    for (int e = 0; e < integers[i + 1]; ++e)
      sub.set(r, integers[i + 2 + e], numbers[d++]);
  }
  sub.compress(dealii::VectorOperation::insert);
  SparseDirect lu;
  lu.factorize(sub);
  lu.solve(sub_b, sub_x);
  // every rank its own entries of x
  const Epetra_BlockMap &x_map = x.trilinos_vector().Map();
  for (unsigned int r = 0; r < n; ++r)
    if (const int lid = x_map.LID(global[r]); lid >= 0)
      x.trilinos_vector()[0][lid] = sub_x[r];
}

} // namespace sealfe
