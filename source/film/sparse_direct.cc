#include <sealfe/film/sparse_direct.h>
#include <sealfe/numerics/gather.h>
#include <sealfe/numerics/substructured_lu.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <Amesos.h>
#include <Amesos_BaseSolver.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_LinearProblem.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>
#include <Epetra_Vector.h>
#include <Teuchos_ParameterList.hpp>
#include <dmumps_c.h>
#include <mpi.h>
#include <smumps_c.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace sealfe
{
namespace
{
/// This rank's entries of A as global (row, column) indices plus `base` (1: MUMPS's), row by row
/// in the order of the matrix's storage, in which values_in_storage_order() reads the values.
void entries_in_storage_order(const Epetra_CrsMatrix &A, const int base, std::vector<int> &row,
                              std::vector<int> &column)
{
  std::vector<int> column_index(A.NumMyCols());
  for (int c = 0; c < A.NumMyCols(); ++c)
    column_index[c] = static_cast<int>(A.ColMap().GID64(c)) + base;
  row.clear();
  column.clear();
  row.reserve(A.NumMyNonzeros());
  column.reserve(A.NumMyNonzeros());
  for (int i = 0; i < A.NumMyRows(); ++i)
  {
    int entries;
    int *columns;
    if (A.Graph().ExtractMyRowView(i, entries, columns) != 0)
      throw std::runtime_error("Reynolds solver: cannot read the matrix rows for MUMPS");
    const int global_row = static_cast<int>(A.RowMap().GID64(i)) + base;
    for (int k = 0; k < entries; ++k)
    {
      row.push_back(global_row);
      column.push_back(column_index[columns[k]]);
    }
  }
}

/// The values of A in the order of entries_in_storage_order(), straight from the matrix's own
/// array: deal.II's compress() leaves the rows in one (Epetra's optimised storage). Checks on
/// every rank of `comm` first (collective) that the pattern is the one read then, with
/// `entries` entries on this rank.
double *values_in_storage_order(const Epetra_CrsMatrix &A, const std::size_t entries,
                                const MPI_Comm comm)
{
  double *storage = nullptr;
  int *offsets = nullptr, *indices = nullptr;
  int pattern_kept = static_cast<std::size_t>(A.NumMyNonzeros()) == entries &&
                     A.StorageOptimized() &&
                     A.ExtractCrsDataPointers(offsets, indices, storage) == 0 &&
                     offsets[A.NumMyRows()] == A.NumMyNonzeros();
  int everywhere = 0;
  const int ierr = MPI_Allreduce(&pattern_kept, &everywhere, 1, MPI_INT, MPI_MIN, comm);
  AssertThrowMPI(ierr);
  if (!everywhere)
    throw std::logic_error("SparseDirect: the matrix pattern or storage changed since the "
                           "analysis");
  return storage;
}

/// The normwise backward error |b - A x|_inf / (|A|_inf |x|_inf + |b|_inf) of x for A, b and x
/// whole on this rank (n values each, by global index); A's rows this rank's, their residuals'
/// largest taken over `comm` (collective there). NaN if x is. `residual` (one rank, n values, or
/// null): b - A x.
double backward_error_of(const Epetra_CrsMatrix &A, const double *b, const double *x,
                         const std::size_t n, const MPI_Comm comm, double *residual = nullptr)
{
  std::vector<double> x_column(A.NumMyCols()); // x by local column index
  for (int c = 0; c < A.NumMyCols(); ++c)
    x_column[c] = x[A.ColMap().GID64(c)];
  double r_max = 0, x_max = 0, b_max = 0;
  for (int row = 0; row < A.NumMyRows(); ++row)
  {
    int entries;
    double *values;
    int *columns;
    A.ExtractMyRowView(row, entries, values, columns);
    const long long global_row = A.RowMap().GID64(row);
    double r = b[global_row];
    for (int e = 0; e < entries; ++e)
      r -= values[e] * x_column[columns[e]];
    r_max = std::max(r_max, std::abs(r));
    if (residual)
      residual[global_row] = r;
  }
  const int ierr = MPI_Allreduce(MPI_IN_PLACE, &r_max, 1, MPI_DOUBLE, MPI_MAX, comm);
  AssertThrowMPI(ierr);
  for (std::size_t i = 0; i < n; ++i)
  {
    x_max = std::max(x_max, std::abs(x[i]));
    b_max = std::max(b_max, std::abs(b[i]));
  }
  const double scale = A.NormInf() * x_max + b_max;
  return scale > 0 ? r_max / scale : 0.0;
}

/// Denormal floats flushed to zero (and read as zero) while this lives, the caller's mode
/// restored after. Single-precision MUMPS needs it on these matrices: without it its sgemm ran
/// 10x slower on the subnormal numbers of the fronts' Schur complements (7.4-9.2 s against
/// 1.4-1.7 s for one factorisation at 5.3e5 unknowns; doc/performance.md "Session 18").
class SubnormalsFlushed
{
public:
#if defined(__SSE__)
  // MXCSR bits FTZ (0x8000) and DAZ (0x0040)
  SubnormalsFlushed() : saved(_mm_getcsr())
  {
    _mm_setcsr(saved | 0x8040);
  }
  ~SubnormalsFlushed()
  {
    _mm_setcsr(saved);
  }

private:
  unsigned int saved;
#endif
};

/// MUMPS's C interface in double (dmumps) or single (smumps) precision: the same structure with
/// the type of the values.
template <class Real>
struct MumpsArithmetic;
template <>
struct MumpsArithmetic<double>
{
  using Instance = DMUMPS_STRUC_C;
  static void call(Instance &id) { dmumps_c(&id); }
};
template <>
struct MumpsArithmetic<float>
{
  using Instance = SMUMPS_STRUC_C;
  static void call(Instance &id)
  {
    const SubnormalsFlushed flushed;
    smumps_c(&id);
  }
};

/// Iterative refinement of the n values x: `residual(x, r)` writes b - A x into r and returns
/// x's normwise backward error; `correct(r)` overwrites r by an approximation of A^-1 r (the
/// single factors, or a low-rank update of them). Steps x += correct(b - A x) while the error is
/// above SparseDirect::refined_backward_error, at most SparseDirect::max_refinement_steps times,
/// and stops where a step no longer halves it (that step's iterate dropped). Returns x's error
/// (NaN stops it too); `steps` counts the corrections made.
template <class Residual, class Correction>
double refine(double *x, const std::size_t n, Residual &&residual, Correction &&correct,
              unsigned int &steps)
{
  std::vector<double> r(n), trial(n);
  double error = residual(x, r.data());
  for (unsigned int step = 0;
       error > SparseDirect::refined_backward_error && step < SparseDirect::max_refinement_steps;
       ++step)
  {
    correct(r.data());
    for (std::size_t i = 0; i < n; ++i)
      trial[i] = x[i] + r[i];
    ++steps;
    const double trial_error = residual(trial.data(), r.data());
    if (!(trial_error < 0.5 * error))
      break;
    std::copy(trial.begin(), trial.end(), x);
    error = trial_error;
  }
  return error;
}
} // namespace

/// MUMPS driven directly through its C interface. Amesos_Mumps, used before, converted the matrix
/// to triplets row by row through copies and two index look-ups per entry (0.8 s of a 1.9 s
/// analysis at 1e6 unknowns), and on several ranks redistributed a copy of the matrix before
/// every factorisation (4 s of 11 s at 1e6 unknowns on two ranks; doc/performance.md "Session
/// 21"). Here each rank reads its own rows of the Trilinos matrix: the row and column indices
/// once per pattern, the values straight from the matrix's storage at every factorisation; on
/// several ranks both are gathered on the host (MPI_Gatherv), in the same order. The MUMPS
/// settings are those Amesos made: MUMPS's defaults with AMD ordering (ICNTL(7) = 0; or a given
/// order, ICNTL(7) = 1, SparseDirect::set_elimination_order), automatic
/// column permutation and scaling (ICNTL(6) = ICNTL(8) = 7), 20 % workspace margin (ICNTL(14),
/// SparseDirect::initial_workspace_margin). `Real` float: the factors in single precision, one
/// rank only (SparseDirect::single_precision_limit), the solves those of the single factors
/// (SparseDirect refines them).
template <class Real>
class SparseDirect::Mumps
{
  static constexpr bool in_double = std::is_same_v<Real, double>;

public:
  /// A MUMPS instance on A's communicator. Collective.
  explicit Mumps(const Epetra_CrsMatrix &A)
      : several_ranks(A.Comm().NumProc() > 1),
        comm(dynamic_cast<const Epetra_MpiComm &>(A.Comm()).GetMpiComm())
  {
    if (A.NumGlobalRows64() >= std::numeric_limits<int>::max())
      throw std::runtime_error("Reynolds solver: the matrix is too large for MUMPS's indices");
    if (!several_ranks && !(A.RowMap().LinearMap() && A.RowMap().MinAllGID64() == 0))
      throw std::logic_error("SparseDirect: one rank needs the rows in order from 0");
    if (!in_double && several_ranks)
      throw std::logic_error("SparseDirect: single-precision factors on one rank only");
    id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(comm));
    id.par = 1; // the host works too
    id.sym = 0; // unsymmetric
    id.job = -1;
    MumpsArithmetic<Real>::call(id);
    check("initialisation");
    for (const int stream : {0, 1, 2, 3})
      id.icntl[stream] = -1; // no messages: errors come back as INFOG(1) and are thrown
    id.icntl[5] = 7;         // column permutation (ICNTL(6)) chosen by MUMPS
    id.icntl[6] = 0;         // AMD ordering: quicker than PORD and MUMPS's choice here
    id.icntl[7] = 7;         // scaling (ICNTL(8)) chosen by MUMPS
    id.icntl[13] = initial_workspace_margin; // ICNTL(14), per cent of the estimate
    // the matrix on the host (ICNTL(18) = 0), also on several ranks (analyse, factorize)
    id.icntl[17] = 0;
  }

  /// MUMPS's estimate of the elimination's operations from the last analysis (RINFOG(1)).
  double estimated_operations() const { return id.rinfog[0]; }

  /// The analysis (ordering, elimination tree) of A's pattern. Collective. `order`: the
  /// elimination position of every row (1-based; one rank), or null for MUMPS's AMD.
  void analyse(const Epetra_CrsMatrix &A, const std::vector<int> *order = nullptr)
  {
    // this rank's entries as (row, column) 1-based global indices, in the order in which the
    // values are read at every factorisation
    entries_in_storage_order(A, 1, row, column);
    id.n = static_cast<int>(A.NumGlobalRows64());
    // Several ranks: the whole matrix on the host (ICNTL(18) = 0), its structure gathered here
    // once and its values at every factorisation; MUMPS then sends the workers their parts (the
    // host keeps ~16 bytes per entry: 0.3 GB at 1.05e6 Q2 dofs). The column permutation option
    // (ICNTL(6) = 7) needs the matrix on the host: with the entries distributed (ICNTL(18) = 2)
    // the analysis came out as with ICNTL(6) = 0 (the same estimated flops and factor size,
    // measured), 1.5x the flops on a 1e6-unknown grid matrix (6.2e10 against 4.2e10) and 1.19x
    // on the tilted seal's finest JFO Jacobian at 1.05e6 dofs (6.41e10 against 5.37e10; doc/
    // performance.md "Session 23").
    if (several_ranks)
    {
      // (-1: more entries on this rank than an int counts; refused below on every rank)
      const int ranks = A.Comm().NumProc(),
                mine = row.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())
                           ? -1
                           : static_cast<int>(row.size());
      host_counts.assign(ranks, 0);
      host_offsets.assign(ranks + 1, 0);
      // (every rank learns the counts, so that all of them refuse a too large matrix together)
      int ierr = MPI_Allgather(&mine, 1, MPI_INT, host_counts.data(), 1, MPI_INT, comm);
      AssertThrowMPI(ierr);
      for (int r = 0; r < ranks; ++r)
      {
        if (host_counts[r] < 0 ||
            host_offsets[r] > std::numeric_limits<int>::max() - host_counts[r])
          throw std::runtime_error("Reynolds solver: too many matrix entries for MUMPS's indices");
        host_offsets[r + 1] = host_offsets[r] + host_counts[r];
      }
      std::vector<int> host_row, host_column;
      if (A.Comm().MyPID() == 0)
      {
        host_row.resize(host_offsets[ranks]);
        host_column.resize(host_offsets[ranks]);
        host_values.resize(host_offsets[ranks]);
      }
      for (auto [mine_indices, host_indices] :
           {std::pair{&row, &host_row}, std::pair{&column, &host_column}})
      {
        ierr = MPI_Gatherv(mine_indices->data(), mine, MPI_INT, host_indices->data(),
                           host_counts.data(), host_offsets.data(), MPI_INT, 0, comm);
        AssertThrowMPI(ierr);
      }
      // this rank's indices are no longer needed (the values' order is that of the storage,
      // checked by its size at every factorisation); the host keeps the whole structure, which
      // MUMPS reads at every factorisation to distribute the values
      row_entries = row.size();
      row = std::move(host_row);
      column = std::move(host_column);
      id.nnz = static_cast<MUMPS_INT8>(row.size());
      id.irn = row.data();
      id.jcn = column.data();
      // the right-hand side and the solution whole on the host (ICNTL(20) = ICNTL(21) = 0); one
      // importer for both, the matrix being square with its range map its domain map (deal.II)
      const int host_rows = A.Comm().MyPID() == 0 ? id.n : 0;
      host_map = std::make_unique<Epetra_Map>(id.n, host_rows, 0, A.Comm());
      to_host = std::make_unique<Epetra_Import>(*host_map, A.OperatorDomainMap());
    }
    else
    {
      row_entries = row.size();
      id.nnz = static_cast<MUMPS_INT8>(row.size());
      id.irn = row.data();
      id.jcn = column.data();
    }
    // A given order (ICNTL(7) = 1): MUMPS reads PERM_IN at the analysis only. Its elimination
    // tree from column counts (ICNTL(58) = 2, new in MUMPS 5.5) instead of MUMPS 5.5's default,
    // a run of its quotient-graph minimum degree (SYMQAMD) constrained to the given order: the
    // same tree (the same operations and largest front), and the analysis of a Q2 ring of 513 x
    // 2048 nodes in its nested dissection 0.46-0.65 s instead of 0.74-1.14 s (doc/
    // performance.md "Session 40").
    if (order && !several_ranks && order->size() == static_cast<std::size_t>(id.n))
    {
      id.perm_in = const_cast<int *>(order->data());
      id.icntl[6] = 1;
      id.icntl[57] = 2;
    }
    id.job = 1;
    MumpsArithmetic<Real>::call(id);
    id.perm_in = nullptr;
    id.icntl[6] = 0;
    // (MUMPS reads the rows and columns again at every factorisation: `row` and `column` live as
    // long as this instance)
    check("analysis");
  }

  ~Mumps()
  {
    id.job = -2;
    MumpsArithmetic<Real>::call(id);
  }

  Mumps(const Mumps &) = delete;
  Mumps &operator=(const Mumps &) = delete;

  /// The numeric factorisation of A, which has the pattern analysed. Collective.
  void factorize(const Epetra_CrsMatrix &A)
  {
    // MUMPS reads the values in this call only (no iterative refinement, ICNTL(10) = 0), from
    // the matrix's own array, in the order the analysis read the indices in (checked on every
    // rank before the collective call)
    double *storage = values_in_storage_order(A, row_entries, comm);
    if constexpr (!in_double)
    {
      // rounded to single precision for this call only
      single_values.assign(storage, storage + row_entries);
      id.a = single_values.data();
    }
    else if (several_ranks)
    {
      // the values to the host, in the order of the structure gathered there
      const int ierr =
          MPI_Gatherv(storage, static_cast<int>(row_entries), MPI_DOUBLE, host_values.data(),
                      host_counts.data(), host_offsets.data(), MPI_DOUBLE, 0, comm);
      AssertThrowMPI(ierr);
      id.a = A.Comm().MyPID() == 0 ? host_values.data() : nullptr;
    }
    else
      id.a = storage;
    // a workspace estimate that falls short (INFOG(1) = -8 or -9: the numerical pivoting delays
    // more pivots than the analysis of the pattern foresaw) is retried with twice the margin,
    // three times (20 % up to 160 %); the margin found stays for the later factorisations of the
    // pattern. The factorisation is the one the final margin would have made at once: the
    // margin sizes the workspace, not the operations.
    bool short_of_workspace = false;
    for (int attempt = 0;; ++attempt)
    {
      id.job = 2;
      MumpsArithmetic<Real>::call(id);
      short_of_workspace = id.infog[0] == -8 || id.infog[0] == -9;
      if (!short_of_workspace || attempt == max_workspace_retries)
        break;
      id.icntl[13] *= 2;
      ++workspace_retries;
    }
    id.a = nullptr;
    single_values = std::vector<float>(); // (freed: MUMPS keeps its own copy in its factors)
    if (short_of_workspace)
      throw std::runtime_error(
          "Reynolds solver: MUMPS factorisation ran out of workspace even with " +
          std::to_string(id.icntl[13]) + " % more than its estimate (INFOG(1) = " +
          std::to_string(id.infog[0]) + ", INFOG(2) = " + std::to_string(id.infog[1]) +
          "): its numerical pivoting needs far more fill than the analysis of the pattern "
          "foresaw");
    check("factorisation");
  }

  /// Factorisations repeated with a larger workspace margin, since this instance was made.
  unsigned int workspace_retries = 0;
  static constexpr int max_workspace_retries = 3;

  /// x = A^-1 b for every column of b. Collective.
  void solve(const Epetra_MultiVector &b, Epetra_MultiVector &x)
  {
    if (!several_ranks)
    {
      if (b.MyLength() != id.n || x.MyLength() != id.n || x.NumVectors() != b.NumVectors())
        throw std::logic_error("SparseDirect::solve: b and x must have the matrix's rows");
      for (int j = 0; j < b.NumVectors(); ++j)
      {
        if (x[j] != b[j])
          std::copy(b[j], b[j] + b.MyLength(), x[j]);
        solve_block(x[j], 1);
      }
      return;
    }
    if constexpr (!in_double)
      throw std::logic_error("SparseDirect: single-precision factors on one rank only");
    // the columns gathered on the host, solved there in one call, and the solution sent back
    Epetra_MultiVector on_host(*host_map, b.NumVectors());
    if (on_host.Import(b, *to_host, Insert) != 0)
      throw std::runtime_error("Reynolds solver: gathering the right-hand side for MUMPS failed");
    solve_phase(
        [&](Instance &s)
        {
          s.nrhs = b.NumVectors();
          s.lrhs = id.n;
          s.rhs = on_host.Values(); // on the host (the others hold no rows): n x nrhs, by columns
        },
        "solve");
    if (x.Export(on_host, *to_host, Insert) != 0)
      throw std::runtime_error("Reynolds solver: scattering the MUMPS solution failed");
  }

  /// The n x m column-major block X overwritten by A^-1 X (one rank); in single precision by
  /// the single factors, X rounded to single precision and back.
  void solve_block(double *X, const int m)
  {
    Real *rhs = nullptr;
    std::vector<float> rounded;
    if constexpr (in_double)
      rhs = X;
    else
    {
      rounded.assign(X, X + std::size_t(id.n) * m);
      rhs = rounded.data();
    }
    solve_phase(
        [&](Instance &s)
        {
          s.nrhs = m;
          s.lrhs = id.n;
          s.rhs = rhs;
        },
        "block solve");
    if constexpr (!in_double)
      std::copy(rounded.begin(), rounded.end(), X);
  }

  /// values[c * rows.size() + p] = (A^-1)(rows[p], columns[c]), columns ascending (one rank).
  void inverse_entries(const std::vector<unsigned int> &rows,
                       const std::vector<unsigned int> &columns, std::vector<double> &values)
  {
    // the requested entries as a sparse n x n right-hand side in compressed columns (1-based):
    // every column of the matrix, those not requested empty; the values come back in place
    const int n = id.n;
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
      throw std::logic_error("SparseDirect: inverse entries' columns not ascending or repeated");
    std::vector<Real> entries(entry_row.size(), Real(0));
    solve_phase(
        [&](Instance &s)
        {
          s.icntl[29] = 1; // selected entries of A^-1 (ICNTL(30))
          // right-hand-side columns per block of the pruned solves (ICNTL(27); MUMPS's default
          // -32 lets it choose up to 32): 256 took 0.64 s against 0.96-1.03 s for the 48 x 640
          // entries of a low-rank update at 1.05e6 unknowns (tilted seal), with the same peak
          // memory (doc/performance.md "Session 20")
          s.icntl[26] = 256;
          s.nz_rhs = int(entry_row.size());
          s.nrhs = n;
          s.lrhs = n;
          s.irhs_ptr = column_start.data();
          s.irhs_sparse = entry_row.data();
          s.rhs_sparse = entries.data();
        },
        "selected inverse entries");
    values.assign(entries.begin(), entries.end());
  }

private:
  /// One solve (job 3) with the right-hand side `set_rhs` describes; the solve settings are
  /// restored afterwards, so that every solve starts from the same ones.
  template <class SetRhs>
  void solve_phase(SetRhs &&set_rhs, const char *what)
  {
    const Instance saved = id;
    set_rhs(id);
    id.job = 3;
    MumpsArithmetic<Real>::call(id);
    const int status = id.infog[0], detail = id.infog[1];
    id.icntl[26] = saved.icntl[26];
    id.icntl[29] = saved.icntl[29];
    id.nz_rhs = saved.nz_rhs;
    id.nrhs = saved.nrhs;
    id.lrhs = saved.lrhs;
    id.rhs = saved.rhs;
    id.irhs_ptr = saved.irhs_ptr;
    id.irhs_sparse = saved.irhs_sparse;
    id.rhs_sparse = saved.rhs_sparse;
    throw_on_error(status, detail, what);
  }

  /// INFOG(1) < 0 (the same on every rank) is an error; -10 a singular matrix.
  void check(const char *what) const { throw_on_error(id.infog[0], id.infog[1], what); }

  static void throw_on_error(const int status, const int detail, const char *what)
  {
    if (status >= 0)
      return;
    if (status == -10)
      throw std::runtime_error("Reynolds solver: MUMPS factorisation failed (singular matrix)");
    throw std::runtime_error(std::string("Reynolds solver: MUMPS ") + what +
                             " failed (INFOG(1) = " + std::to_string(status) +
                             ", INFOG(2) = " + std::to_string(detail) + ")");
  }

  using Instance = typename MumpsArithmetic<Real>::Instance;
  bool several_ranks;
  MPI_Comm comm; // A's, for the gathers on the host
  Instance id{};
  std::vector<float> single_values; // single precision: the values during the factorisation
  // 1-based global indices of the entries: one rank its own; several ranks the whole matrix's
  // on the host (empty on the others)
  std::vector<int> row, column;
  std::size_t row_entries = 0; // this rank's entries
  // several ranks: the entries of each rank on the host (counts, offsets), and their values there
  std::vector<int> host_counts, host_offsets;
  std::vector<double> host_values;
  std::unique_ptr<Epetra_Map> host_map; // several ranks: every row on the host
  std::unique_ptr<Epetra_Import> to_host;
};

/// A factorisation that the ranks of a team share (numerics::SubstructuredLU). The matrix is
/// either whole on every rank (MPI_COMM_SELF, the same on every rank of the team) or distributed
/// by rows over the ranks of its communicator; then every rank gathers the whole pattern once and
/// the values at every factorisation (one MPI_Allgatherv of ~8 bytes per entry, 0.13 GB at
/// 1.05e6 Q2 dofs), the right-hand side at every solve, and keeps its own rows of the solution.
class SparseDirect::Shared
{
public:
  /// Collective over the team; `ready` false where SubstructuredLU refuses the split.
  Shared(const Epetra_CrsMatrix &A, const MPI_Comm team)
      : distributed(A.Comm().NumProc() > 1),
        comm(distributed ? dynamic_cast<const Epetra_MpiComm &>(A.Comm()).GetMpiComm() : team),
        lu(comm)
  {
    const long long n_global = A.NumGlobalRows64();
    if (n_global >= std::numeric_limits<int>::max())
      throw std::runtime_error("Reynolds solver: the matrix is too large for MUMPS's indices");
    n = static_cast<int>(n_global);
    if (!distributed && !(A.RowMap().LinearMap() && A.RowMap().MinAllGID64() == 0))
      throw std::logic_error("SparseDirect: one rank needs the rows in order from 0");
    // this rank's entries by global (row, column), in the order in which the values are read at
    // every factorisation
    std::vector<int> row, column;
    entries_in_storage_order(A, 0, row, column);
    my_entries = row.size();
    my_row_count = A.NumMyRows();
    whole.resize(n);
    if (distributed)
    {
      row = numerics::gather_on_every_rank(comm, row);
      column = numerics::gather_on_every_rank(comm, column);
      std::vector<int> my_rows(A.NumMyRows());
      for (int i = 0; i < A.NumMyRows(); ++i)
        my_rows[i] = static_cast<int>(A.RowMap().GID64(i));
      row_of_gathered = numerics::gather_on_every_rank(comm, my_rows);
      if (row_of_gathered.size() != std::size_t(n))
        throw std::logic_error("SparseDirect: the ranks' rows do not make the matrix");
      // every rank's count and offset of entries, for the values' gather at every factorisation
      // into one buffer kept with the pattern (a new one each time was fresh memory: page faults)
      const int ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
      const int mine = static_cast<int>(my_entries);
      value_counts.resize(ranks);
      value_offsets.assign(ranks + 1, 0);
      const int ierr = MPI_Allgather(&mine, 1, MPI_INT, value_counts.data(), 1, MPI_INT, comm);
      AssertThrowMPI(ierr);
      for (int r = 0; r < ranks; ++r)
        value_offsets[r + 1] = value_offsets[r] + value_counts[r];
      values.resize(row.size());
    }
    // the ranks' blocks: equal ranges of the global numbering (on the annulus meshes the
    // ranges of p4est's partition, sectors of the annulus)
    const int ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
    std::vector<long long> block_start(ranks + 1);
    for (int r = 0; r <= ranks; ++r)
      block_start[r] = (static_cast<long long>(n) * r) / ranks;
    ready = lu.analyse(n, row, column, block_start);
  }

  /// Collective.
  void factorize(const Epetra_CrsMatrix &A)
  {
    // (checked on every rank of the team: the matrix may be whole on each)
    const double *storage = values_in_storage_order(A, my_entries, comm);
    if (distributed)
    {
      const int ierr =
          MPI_Allgatherv(storage, static_cast<int>(my_entries), MPI_DOUBLE, values.data(),
                         value_counts.data(), value_offsets.data(), MPI_DOUBLE, comm);
      AssertThrowMPI(ierr);
      lu.factorize(values.data());
    }
    else
      lu.factorize(storage);
  }

  /// x = A^-1 b, A the factorised matrix; returns the answer's normwise backward error
  /// (backward_error_of, the same on every rank; NaN for a NaN answer). Collective.
  double solve(const Epetra_CrsMatrix &A, const Epetra_MultiVector &b, Epetra_MultiVector &x)
  {
    if (b.NumVectors() != 1 || x.NumVectors() != 1)
      throw std::logic_error("SparseDirect::solve: one right-hand side");
    if (!distributed)
    {
      if (b.MyLength() != n || x.MyLength() != n)
        throw std::logic_error("SparseDirect::solve: b and x must have the matrix's rows");
      std::copy(b[0], b[0] + n, whole.begin());
    }
    else
    {
      // b's entries by the rows' order (deal.II's vectors share the matrix's row map)
      if (!b.Map().SameAs(x.Map()) || b.MyLength() != static_cast<int>(my_row_count))
        throw std::logic_error("SparseDirect::solve: b and x must have the matrix's rows");
      const std::vector<double> mine(b[0], b[0] + b.MyLength());
      const std::vector<double> gathered = numerics::gather_on_every_rank(comm, mine);
      for (std::size_t k = 0; k < gathered.size(); ++k)
        whole[row_of_gathered[k]] = gathered[k];
    }
    const std::vector<double> rhs(whole);
    lu.solve(whole.data(), 1);
    for (int i = 0; i < x.MyLength(); ++i)
      x[0][i] = whole[x.Map().GID64(i)];
    return backward_error_of(A, rhs.data(), whole.data(), n, comm);
  }

  /// X (n x m, this rank's whole matrix) = A^-1 X. Collective.
  void solve_block(double *X, const int m) { lu.solve(X, m); }

  unsigned int workspace_retries() const { return lu.workspace_retries(); }

  bool ready = false;

private:
  bool distributed;
  MPI_Comm comm; // the team: the matrix's communicator, or the ranks that each hold it whole
  numerics::SubstructuredLU lu;
  int n = 0;
  std::size_t my_entries = 0, my_row_count = 0;
  std::vector<int> row_of_gathered;  // distributed: every rank's rows in gathering order
  std::vector<double> values, whole; // distributed: every rank's entries; the whole vector
  std::vector<int> value_counts, value_offsets; // distributed: each rank's entries in `values`
};

SparseDirect::SparseDirect() = default;
SparseDirect::~SparseDirect() = default;

void SparseDirect::share_with(const MPI_Comm team_in)
{
  if (team_in != team)
    clear();
  team = team_in;
}

unsigned int SparseDirect::workspace_retries() const
{
  return retried_workspace + (mumps ? mumps->workspace_retries : 0) +
         (single ? single->workspace_retries : 0) + (shared ? shared->workspace_retries() : 0);
}

void SparseDirect::clear()
{
  if (mumps)
    retried_workspace += mumps->workspace_retries;
  if (single)
    retried_workspace += single->workspace_retries;
  if (shared)
    retried_workspace += shared->workspace_retries();
  mumps.reset();
  single.reset();
  shared.reset();
  solver.reset();
  problem.reset();
  pattern_owner = nullptr;
  pattern_entries = -1;
  package = ""; // no factorisation: none to name (a later method may not factorise at all)
}

void SparseDirect::set_elimination_order(std::vector<int> position_of_row)
{
  std::vector<bool> taken(position_of_row.size(), false);
  for (const int p : position_of_row)
  {
    if (p < 1 || static_cast<std::size_t>(p) > taken.size() || taken[p - 1])
      throw std::logic_error("SparseDirect: the elimination order is not a permutation");
    taken[p - 1] = true;
  }
  elimination_order = std::move(position_of_row);
}

const std::vector<int> *SparseDirect::order_for(const Epetra_CrsMatrix &A) const
{
  const bool applies = !elimination_order.empty() && A.Comm().NumProc() == 1 &&
                       static_cast<long long>(elimination_order.size()) == A.NumGlobalRows64();
  return applies ? &elimination_order : nullptr;
}

template <class Real>
std::unique_ptr<SparseDirect::Mumps<Real>>
SparseDirect::analysed_by_mumps(const Epetra_CrsMatrix &A)
{
  auto analysed = std::make_unique<Mumps<Real>>(A);
  const std::vector<int> *order = order_for(A);
  analysed->analyse(A, order);
  given_order_count += order != nullptr;
  return analysed;
}

double SparseDirect::estimated_operations() const
{
  return mumps ? mumps->estimated_operations() : single ? single->estimated_operations() : 0.0;
}

void SparseDirect::factorize(const dealii::TrilinosWrappers::SparseMatrix &matrix)
{
  const Epetra_CrsMatrix &A = matrix.trilinos_matrix();
  // The symbolic analysis (BTF, AMD ordering) depends on the pattern only: a Newton Jacobian
  // assembled into the same matrix object has the same one.
  bool same_pattern =
      initialized() && pattern_owner == &A && pattern_entries == A.NumGlobalNonzeros64();
  // (a team whose ranks each hold their own matrix object decides together: a new analysis and a
  // numeric factorisation are different sequences of collective calls)
  if (A.Comm().NumProc() == 1 && dealii::Utilities::MPI::n_mpi_processes(team) > 1)
    same_pattern = dealii::Utilities::MPI::min(same_pattern ? 1 : 0, team) == 1;
  if (!same_pattern)
  {
    clear();
    // KLU (left-looking, no dense kernels) is quickest on small systems; above a few 1e4
    // unknowns MUMPS's multifrontal factorisation with dense BLAS-3 fronts is 2-7x faster on these
    // 2D meshes (doc/performance.md "Direct solver"). AMD ordering: measured quicker than nested
    // dissection (PORD: Debian's MUMPS has no METIS, doc/performance.md "Session 28") and
    // MUMPS's automatic choice at 2.6e5 and 1e6 unknowns.
    package = A.NumGlobalRows64() < multifrontal_limit ? "KLU" : "MUMPS";
    // Several ranks on one matrix: shared by a separator where it is large enough to pay
    const MPI_Comm sharing =
        A.Comm().NumProc() > 1 ? dynamic_cast<const Epetra_MpiComm &>(A.Comm()).GetMpiComm() : team;
    if (A.NumGlobalRows64() >= substructured_limit &&
        dealii::Utilities::MPI::n_mpi_processes(sharing) > 1)
    {
      auto split = std::make_unique<Shared>(A, team);
      if (split->ready)
      {
        shared = std::move(split);
        package = "MUMPS, substructured"; // (each rank's part: MUMPS)
      }
    }
    if (shared)
    {
      // (analysed by its constructor)
    }
    else if (package == std::string("MUMPS") && A.Comm().NumProc() == 1 &&
             A.NumGlobalRows64() >= single_precision_limit)
    {
      single = analysed_by_mumps<float>(A);
      package = "MUMPS, single precision refined";
    }
    else if (package == std::string("MUMPS"))
    {
      // kept only once analysed: a SparseDirect whose analysis failed holds no factorisation
      mumps = analysed_by_mumps<double>(A);
    }
    else
    {
      problem = std::make_unique<Epetra_LinearProblem>();
      problem->SetOperator(const_cast<Epetra_CrsMatrix *>(&A));
      Amesos factory;
      solver.reset(factory.Create("Amesos_Klu", *problem));
      if (!solver)
        throw std::runtime_error("Reynolds solver: Amesos KLU is not available");
      Teuchos::ParameterList parameters;
      solver->SetParameters(parameters);
      if (solver->SymbolicFactorization() != 0)
        throw std::runtime_error("Reynolds solver: KLU symbolic factorisation failed");
    }
    pattern_owner = &A;
    pattern_entries = A.NumGlobalNonzeros64();
  }
  else
    ++reused_symbolic;
  if (shared)
  {
    try
    {
      shared->factorize(A);
      return;
    }
    catch (const std::runtime_error &failure)
    {
      // (thrown on every rank of the team together, SubstructuredLU's agreement): a part or the
      // complement is singular where the whole matrix need not be, whose factorisation pivots
      // across the separator
      factorize_whole(A);
      return;
    }
  }
  if (single)
  {
    try
    {
      single->factorize(A);
      return;
    }
    catch (const std::runtime_error &failure)
    {
      // singular in single precision (values below its range flushed to zero, say) or short of
      // workspace: the double factorisation decides, and the pattern stays with it
      factorize_in_double(A);
      return;
    }
  }
  if (mumps)
    mumps->factorize(A);
  else if (solver->NumericFactorization() != 0)
    throw std::runtime_error("Reynolds solver: KLU factorisation failed (singular matrix)");
}

void SparseDirect::factorize_whole(const Epetra_CrsMatrix &A)
{
  // MUMPS's parallel factorisation of the whole matrix, or each rank's own where it is whole
  // on every rank (SparseDirect::Mumps); this pattern stays with it
  retried_workspace += shared->workspace_retries();
  shared.reset();
  factorize_in_double(A);
}

void SparseDirect::factorize_in_double(const Epetra_CrsMatrix &A)
{
  if (single)
  {
    retried_workspace += single->workspace_retries;
    ++fallback_count;
  }
  single.reset();
  package = "MUMPS";
  mumps = analysed_by_mumps<double>(A);
  mumps->factorize(A);
}

double SparseDirect::refined_solve(const Epetra_Vector &b, Epetra_Vector &x)
{
  // Mixed-precision iterative refinement: x from the single factors, then x += S^-1 (b - A x)
  // with the residual in double (refine()). Each step gains about log10(1 / (c kappa 2^-24))
  // digits; the tilted seal's JFO Jacobian at 1.05e6 unknowns: 1.4e-10 from the single factors
  // (MUMPS's scaling), 2.6e-15 after one step (doc/performance.md "Session 30").
  const Epetra_CrsMatrix &A = *pattern_owner;
  const int n = A.NumMyRows();
  if (b.MyLength() != n || x.MyLength() != n)
    throw std::logic_error("SparseDirect::solve: b and x must have the matrix's rows");
  std::copy(b.Values(), b.Values() + n, x.Values());
  single->solve_block(x.Values(), 1);
  double b_max;
  b.NormInf(&b_max);
  const double A_norm = A.NormInf();
  auto residual = [&](double *values, double *r_values)
  {
    const Epetra_Vector candidate(View, A.DomainMap(), values);
    Epetra_Vector r(View, A.RangeMap(), r_values);
    A.Multiply(false, candidate, r);
    r.Update(1.0, b, -1.0); // r = b - A x
    double r_max, x_max;
    r.NormInf(&r_max);
    candidate.NormInf(&x_max);
    const double scale = A_norm * x_max + b_max;
    return scale > 0 ? r_max / scale : 0.0;
  };
  return refine(
      x.Values(), n, residual, [&](double *r) { single->solve_block(r, 1); }, refinement_count);
}

void SparseDirect::solve(const dealii::TrilinosWrappers::MPI::Vector &b,
                         dealii::TrilinosWrappers::MPI::Vector &x)
{
  // (a factorisation whose analysis threw leaves none)
  if (!initialized())
    throw std::logic_error("SparseDirect::solve: no factorisation");
  if (shared)
  {
    // A part that MUMPS could not factorise inside (a zero pivot coupled only to separator
    // unknowns, which may not be pivots) came back as a factorisation without an error and a
    // wrong answer (measured: backward error 1e-2, SparseDirect.SingularPartOnSeveralRanks...)
    // before the parts counted their null and replaced pivots (numerics::SubstructuredLU); a
    // case those counts miss would still show here, so every answer is checked: backward-stable
    // solves of these matrices measure 7e-19 to 4e-17, and one above 1e-12 is refactorised whole
    // and solved again (on every rank: the error is the same on all) (a NaN error fails the
    // comparison too)
    if (shared->solve(*pattern_owner, b.trilinos_vector(), x.trilinos_vector()) <=
        max_substructured_backward_error)
      return;
    factorize_whole(*pattern_owner);
  }
  if (single)
  {
    // (a NaN error fails the comparison too)
    if (refined_solve(*b.trilinos_vector()(0), *x.trilinos_vector()(0)) <= refined_backward_error)
      return;
    // the single factors too far from A (its condition near 2^24): A in double instead
    factorize_in_double(*pattern_owner);
  }
  if (mumps)
  {
    mumps->solve(b.trilinos_vector(), x.trilinos_vector());
    return;
  }
  problem->SetLHS(&x.trilinos_vector());
  problem->SetRHS(const_cast<Epetra_MultiVector *>(
      static_cast<const Epetra_MultiVector *>(&b.trilinos_vector())));
  if (solver->Solve() != 0)
    throw std::runtime_error("Reynolds solver: KLU solve failed");
}

void SparseDirect::solve_block(std::vector<double> &X, const unsigned int m)
{
  if (!initialized())
    throw std::logic_error("SparseDirect::solve_block: no factorisation");
  const Epetra_CrsMatrix &A = *pattern_owner;
  const int n = A.NumMyRows();
  if (A.Comm().NumProc() != 1 || X.size() != static_cast<std::size_t>(n) * m)
    throw std::logic_error("SparseDirect::solve_block: one rank, n x m values");
  if (shared)
  {
    shared->solve_block(X.data(), m);
    return;
  }
  if (mumps)
  {
    mumps->solve_block(X.data(), m);
    return;
  }
  if (single)
  {
    single->solve_block(X.data(), m);
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
    throw std::runtime_error("Reynolds solver: KLU solve failed");
}

bool SparseDirect::inverse_entries(const std::vector<unsigned int> &rows,
                                   const std::vector<unsigned int> &columns,
                                   std::vector<double> &values)
{
  if ((!mumps && !single) || pattern_owner->Comm().NumProc() != 1)
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
  if (mumps)
    mumps->inverse_entries(rows, sorted, sorted_values);
  else
    single->inverse_entries(rows, sorted, sorted_values);
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
  // (a shared factorisation has no selected entries of its inverse: the block path, dear for
  // many columns)
  if (lu.substructured() && k > SparseDirect::max_shared_update_columns)
    return LowRankSolve::too_many_columns;
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
  auto residual = [&](const double *values, double *r)
  { return backward_error_of(matrix.trilinos_matrix(), b, values, n, MPI_COMM_SELF, r); };
  if (!lu.single_precision())
    backward_error = residual(result.data(), nullptr);
  else
  {
    // Single factors: C and the solves are single-precision accurate, so the update formula is
    // applied to the residual of A1 (in double), as SparseDirect::solve refines (refine()). Each
    // step: two solves with the single factors, C's factors reused (tilted seal, 1.05e6
    // unknowns, 50 columns: 2.7e-7 from the formula, then 1.2e-11, 2.7e-16).
    auto correct = [&](double *r)
    {
      // r = A0^-1 (r - U C^-1 E^T A0^-1 r)
      dealii::Vector<double> s(k);
      if (k > 0)
      {
        std::vector<double> z(r, r + n);
        lu.solve_block(z, 1);
        for (std::size_t p = 0; p < k; ++p)
          s(p) = z[columns[p]];
        C.solve(s);
      }
      for (std::size_t q = 0; q < k; ++q)
        for (const auto &[i, value] : U[q])
          r[i] -= value * s(q);
      std::vector<double> correction(r, r + n);
      lu.solve_block(correction, 1);
      std::copy(correction.begin(), correction.end(), r);
    };
    backward_error = refine(result.data(), n, residual, correct, lu.refinement_count);
  }
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
  // the rows' and columns' global indices once for all layers (a GID64 call per row and layer
  // was most of this function's time in the band rounds)
  std::vector<long long> row_gid(A.NumMyRows()), column_gid(A.NumMyCols());
  for (int row = 0; row < A.NumMyRows(); ++row)
    row_gid[row] = A.RowMap().GID64(row);
  for (int c = 0; c < A.NumMyCols(); ++c)
    column_gid[c] = A.ColMap().GID64(c);
  for (unsigned int layer = 0; layer < layers; ++layer)
  {
    std::vector<unsigned char> grown(marked);
    for (int row = 0; row < A.NumMyRows(); ++row)
    {
      if (!marked[row_gid[row]])
        continue;
      int n;
      double *values;
      int *columns;
      A.ExtractMyRowView(row, n, values, columns);
      for (int k = 0; k < n; ++k)
        grown[column_gid[columns[k]]] = 1;
    }
    unite(grown);
    marked.swap(grown);
  }
  return std::vector<bool>(marked.begin(), marked.end());
}

unsigned int solve_on_subset(const dealii::TrilinosWrappers::SparseMatrix &matrix,
                             const std::vector<bool> &subset,
                             const dealii::TrilinosWrappers::MPI::Vector &b,
                             dealii::TrilinosWrappers::MPI::Vector &x, const MPI_Comm replicas)
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
  lu.share_with(dealii::Utilities::MPI::n_mpi_processes(comm) > 1 ? comm : replicas);
  lu.factorize(sub);
  lu.solve(sub_b, sub_x);
  // every rank its own entries of x
  const Epetra_BlockMap &x_map = x.trilinos_vector().Map();
  for (unsigned int r = 0; r < n; ++r)
    if (const int lid = x_map.LID(global[r]); lid >= 0)
      x.trilinos_vector()[0][lid] = sub_x[r];
  return lu.workspace_retries();
}

} // namespace sealfe
