#include <sealfe/numerics/substructured_lu.h>

#include <deal.II/base/mpi.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <dmumps_c.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sealfe::numerics
{
namespace
{
/// home of a separator unknown (the interiors are numbered by rank)
constexpr int in_separator = -1;
} // namespace

/// This rank's part: the split (the same on every rank), its MUMPS instance with the Schur
/// option, and the dense complement.
class SubstructuredLU::Part
{
public:
  int n = 0, rank = 0, ranks = 1;
  /// rank of the interior of each unknown, or in_separator
  std::vector<int> home;
  /// the separator's unknowns, ascending
  std::vector<int> separator;
  /// every rank's interior unknowns, rank after rank, each ascending; rank r's from
  /// interior_offsets[r]
  std::vector<int> interiors, interior_offsets;
  /// positions in `separator` of this rank's Schur unknowns (its local unknowns after its
  /// interior)
  std::vector<int> my_separator;
  int n_local = 0, n_interior = 0;
  /// this rank's entries: 1-based local indices and the caller's entry (-1: an added zero
  /// diagonal, so that every Schur unknown has an entry on every rank)
  std::vector<int> local_row, local_column;
  std::vector<long long> entry_of;
  std::vector<double> local_values, schur_term, complement_sum;
  std::vector<int> schur_list;
  dealii::LAPACKFullMatrix<double> complement;
  DMUMPS_STRUC_C id{};
  bool mumps_made = false;
  unsigned int retries = 0;

  ~Part()
  {
    if (mumps_made)
    {
      id.job = -2;
      dmumps_c(&id);
    }
  }
};

SubstructuredLU::SubstructuredLU(const MPI_Comm team_in)
{
  // its own communicator: its collective calls never pair with the caller's
  const int ierr = MPI_Comm_dup(team_in, &team);
  AssertThrowMPI(ierr);
}

SubstructuredLU::~SubstructuredLU()
{
  part.reset();
  MPI_Comm_free(&team);
}

std::size_t SubstructuredLU::separator_size() const
{
  return part ? part->separator.size() : 0;
}

unsigned int SubstructuredLU::workspace_retries() const
{
  return part ? part->retries : 0;
}

namespace
{
/// Every rank throws if `status` (a MUMPS INFOG(1)) is negative on any: the ranks then leave the
/// collective calls together.
void agree_on(const int status, const int detail, const MPI_Comm team, const char *what)
{
  int worst = status;
  const int ierr = MPI_Allreduce(&status, &worst, 1, MPI_INT, MPI_MIN, team);
  AssertThrowMPI(ierr);
  if (worst >= 0)
    return;
  if (status == -10)
    throw std::runtime_error(std::string("Reynolds solver: MUMPS ") + what +
                             " failed (singular matrix) in a substructured factorisation");
  if (status == -1)
    throw std::runtime_error(std::string("Reynolds solver: the ") + what +
                             " of a substructured factorisation failed on this rank (out of "
                             "memory?)");
  if (status < 0)
    throw std::runtime_error(
        std::string("Reynolds solver: MUMPS ") + what +
        " failed in a substructured factorisation (INFOG(1) = " + std::to_string(status) +
        ", INFOG(2) = " + std::to_string(detail) + ")");
  throw std::runtime_error(std::string("Reynolds solver: MUMPS ") + what +
                           " failed on another rank of a substructured factorisation");
}

/// values summed over the team on its first rank (the others' copies untouched)
void sum_on_first_rank(std::vector<double> &values, const MPI_Comm team)
{
  const int rank = dealii::Utilities::MPI::this_mpi_process(team);
  if (values.size() > std::size_t(std::numeric_limits<int>::max()))
    throw std::runtime_error("SubstructuredLU: separator too large for MPI counts");
  const int ierr =
      MPI_Reduce(rank == 0 ? MPI_IN_PLACE : values.data(), rank == 0 ? values.data() : nullptr,
                 static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM, 0, team);
  AssertThrowMPI(ierr);
}

/// Every rank throws `message` if the first rank's `status` is negative (its work that the others
/// wait for). Collective.
void first_rank_decides(int status, const MPI_Comm team, const char *message)
{
  const int ierr = MPI_Bcast(&status, 1, MPI_INT, 0, team);
  AssertThrowMPI(ierr);
  if (status < 0)
    throw std::runtime_error(message);
}

/// `work()` on this rank alone, its status (a MUMPS INFOG(1), or -1 for an exception) for
/// agree_on, so that a failure on one rank does not leave the others in a collective call
template <class Work>
int run_locally(Work &&work)
{
  try
  {
    return work();
  }
  catch (...)
  {
    return -1;
  }
}
} // namespace

bool SubstructuredLU::analyse(const int n, const std::vector<int> &row,
                              const std::vector<int> &column,
                              const std::vector<long long> &block_start)
{
  part.reset();
  std::unique_ptr<Part> p = split(n, row, column, block_start);
  if (!p)
    return false;
  // (Parts of equal size can differ in their factorisation's flops by 1.5x: the tilted seal's
  // Jacobian at 1.05e6 dofs, 3.0e10 against 2.1e10 for 526 080 unknowns each. Resizing the blocks
  // by the analyses' estimates and splitting again was tried: the cut went back to the same
  // cheapest place, for 0.7-0.9 s of a second split and analysis.)
  part = std::move(p);
  return true;
}

std::unique_ptr<SubstructuredLU::Part>
SubstructuredLU::split(const int n, const std::vector<int> &row, const std::vector<int> &column,
                       const std::vector<long long> &block_start) const
{
  auto p = std::make_unique<Part>();
  p->n = n;
  p->rank = dealii::Utilities::MPI::this_mpi_process(team);
  p->ranks = dealii::Utilities::MPI::n_mpi_processes(team);
  const int ranks = p->ranks, rank = p->rank;
  if (row.size() != column.size() || block_start.size() != std::size_t(ranks) + 1 ||
      block_start.front() != 0 || block_start.back() != n)
    throw std::logic_error("SubstructuredLU::analyse: entries or blocks do not fit the matrix");
  for (int r = 0; r < ranks; ++r)
    if (block_start[r + 1] < block_start[r])
      throw std::logic_error("SubstructuredLU::analyse: blocks not ascending");
  const std::size_t entries = row.size();
  // Each boundary between blocks moved, within a tenth of a block, to where the split costs
  // least (below) with the fewest unknowns coupled across it: unknown i is coupled across a
  // boundary at k (i < k) if its largest coupled index reaches k, so the counts for every k follow
  // from one pass over the entries. On a distributed film mesh the dofs are numbered in the order
  // of p4est's cells, and an equal range of that numbering cuts the annulus along a staircase of
  // cells (the tilted seal's Jacobian at 5.3e5 dofs on two ranks: a separator of 2425 unknowns, its
  // dense complement 0.30 s; with the cut moved 1662 unknowns and 0.10 s).
  std::vector<long long> starts(block_start);
  {
    std::vector<int> reach(n);
    for (int i = 0; i < n; ++i)
      reach[i] = i;
    for (std::size_t e = 0; e < entries; ++e)
    {
      const int i = row[e], j = column[e];
      if (i < 0 || i >= n || j < 0 || j >= n)
        throw std::logic_error("SubstructuredLU::analyse: an entry outside the matrix");
      reach[std::min(i, j)] = std::max(reach[std::min(i, j)], std::max(i, j));
    }
    // crossing[k]: the unknowns i < k with reach[i] >= k
    std::vector<int> crossing(n + 1, 0);
    for (int i = 0; i < n; ++i)
      if (reach[i] > i)
      {
        ++crossing[i + 1];
        --crossing[reach[i] + 1]; // (reach[i] <= n - 1)
      }
    for (int k = 1; k <= n; ++k)
      crossing[k] += crossing[k - 1];
    // The cost of a boundary at k between blocks of a and b unknowns, in flops: the larger
    // part's sparse factorisation, ~88 m^1.5 (m/(a+b)/2)^2 (MUMPS with AMD on the tilted seal's
    // Jacobian at 5.3e5 dofs: 1.36e10 for 288 512 unknowns, 9.07e9 for 238 300: about the square
    // of the size near the balance), against the dense complement, (2/3) s^3 at ~2.5x MUMPS's
    // rate: 0.27 s^3 (s: the unknowns crossing k before thinning)
    const auto cost = [&](const long long k, const long long first, const long long end)
    {
      const double a = double(k - first), b = double(end - k), m = 0.5 * (a + b),
                   larger = std::max(a, b), s = crossing[k];
      return 88 * larger * larger / std::sqrt(m) + 0.27 * s * s * s;
    };
    for (int r = 1; r < ranks && move_cuts; ++r)
    {
      const long long width = (block_start[r + 1] - block_start[r - 1]) / 20,
                      low = std::max(starts[r - 1] + 1, block_start[r] - width),
                      high = std::min(block_start[r + 1] - 1, block_start[r] + width);
      long long best = block_start[r];
      for (long long k = low; k <= high; ++k)
        if (cost(k, starts[r - 1], block_start[r + 1]) <
            cost(best, starts[r - 1], block_start[r + 1]))
          best = k;
      starts[r] = best;
    }
  }
  std::vector<int> block(n);
  for (int r = 0; r < ranks; ++r)
    std::fill(block.begin() + starts[r], block.begin() + starts[r + 1], r);
  // the separator: unknowns of a block coupled to a later block (either direction of the entry)
  std::vector<char> separating(n, 0);
  for (std::size_t e = 0; e < entries; ++e)
  {
    const int i = row[e], j = column[e];
    if (i < 0 || i >= n || j < 0 || j >= n)
      throw std::logic_error("SubstructuredLU::analyse: an entry outside the matrix");
    if (block[i] < block[j])
      separating[i] = 1;
    else if (block[j] < block[i])
      separating[j] = 1;
  }
  // Thinning: a separator unknown whose other neighbours all lie in one interior joins that
  // interior. On a Q2 mesh the one-sided separator is two or three node lines where one line of
  // cell edges separates (tests/validation/sparse_direct.cc, SubstructuredLU); on a Q2 grid
  // matrix of 1.05e6 unknowns a separator of that one line (METIS's, 1026 unknowns against the
  // one-sided 1539) took the costlier part's factorisation from 3.6e10 to 2.5e10 flops. Of two such
  // unknowns coupled to each other but bound for different interiors the larger index stays in
  // the separator (the smaller may stay too, by another pair: valid either way).
  constexpr int no_neighbour = -2, several = -3;
  std::vector<int> bound_for(n, no_neighbour);
  auto note = [&](const int s, const int interior_block)
  {
    int &b = bound_for[s];
    if (b == no_neighbour)
      b = interior_block;
    else if (b != interior_block)
      b = several;
  };
  for (std::size_t e = 0; e < entries; ++e)
  {
    const int i = row[e], j = column[e];
    if (separating[i] && !separating[j])
      note(i, block[j]);
    if (separating[j] && !separating[i])
      note(j, block[i]);
  }
  std::vector<char> stays(n, 0);
  for (std::size_t e = 0; e < entries; ++e)
  {
    const int i = row[e], j = column[e];
    if (i != j && separating[i] && separating[j] && bound_for[i] >= 0 && bound_for[j] >= 0 &&
        bound_for[i] != bound_for[j])
      stays[std::max(i, j)] = 1;
  }
  p->home.resize(n);
  for (int i = 0; i < n; ++i)
    p->home[i] = !separating[i]                     ? block[i]
                 : (bound_for[i] >= 0 && !stays[i]) ? bound_for[i]
                                                    : in_separator;
  // the split must separate: no entry couples two interiors
  for (std::size_t e = 0; e < entries; ++e)
  {
    const int hi = p->home[row[e]], hj = p->home[column[e]];
    if (hi != in_separator && hj != in_separator && hi != hj)
      throw std::logic_error("SubstructuredLU::analyse: the split couples two interiors");
  }
  p->interior_offsets.assign(ranks + 1, 0);
  for (int i = 0; i < n; ++i)
    if (p->home[i] == in_separator)
      p->separator.push_back(i);
    else
      ++p->interior_offsets[p->home[i] + 1];
  for (int r = 0; r < ranks; ++r)
    p->interior_offsets[r + 1] += p->interior_offsets[r];
  const std::size_t s = p->separator.size();
  for (int r = 0; r < ranks; ++r)
    if (p->interior_offsets[r + 1] == p->interior_offsets[r])
      return nullptr;
  if (s > max_separator || 8 * s > std::size_t(n) || s == 0)
    return nullptr;
  p->interiors.resize(n - s);
  {
    std::vector<int> next(p->interior_offsets.begin(), p->interior_offsets.end() - 1);
    for (int i = 0; i < n; ++i)
      if (p->home[i] != in_separator)
        p->interiors[next[p->home[i]]++] = i;
  }

  // This rank's unknowns: its interior, then the separator unknowns coupled to it (on the first
  // rank all of them, which also takes A_SS)
  std::vector<int> local(n, -1);
  p->n_interior = p->interior_offsets[rank + 1] - p->interior_offsets[rank];
  int next_local = 0;
  for (int k = p->interior_offsets[rank]; k < p->interior_offsets[rank + 1]; ++k)
    local[p->interiors[k]] = next_local++;
  std::vector<char> touches(s, rank == 0);
  std::vector<int> separator_position(n, -1);
  for (std::size_t k = 0; k < s; ++k)
    separator_position[p->separator[k]] = k;
  for (std::size_t e = 0; e < entries; ++e)
  {
    const int i = row[e], j = column[e];
    if (p->home[i] == rank && p->home[j] == in_separator)
      touches[separator_position[j]] = 1;
    if (p->home[j] == rank && p->home[i] == in_separator)
      touches[separator_position[i]] = 1;
  }
  for (std::size_t k = 0; k < s; ++k)
    if (touches[k])
    {
      p->my_separator.push_back(k);
      p->schur_list.push_back(next_local + 1);
      local[p->separator[k]] = next_local++;
    }
  p->n_local = next_local;
  for (std::size_t e = 0; e < entries; ++e)
  {
    const int i = row[e], j = column[e], hi = p->home[i], hj = p->home[j];
    const bool mine = (hi == rank && local[j] >= 0) || (hj == rank && local[i] >= 0) ||
                      (rank == 0 && hi == in_separator && hj == in_separator);
    if (!mine)
      continue;
    p->local_row.push_back(local[i] + 1);
    p->local_column.push_back(local[j] + 1);
    p->entry_of.push_back(static_cast<long long>(e));
  }
  if (rank != 0)
    for (const int l : p->schur_list)
    {
      p->local_row.push_back(l);
      p->local_column.push_back(l);
      p->entry_of.push_back(-1);
    }
  p->local_values.assign(p->entry_of.size(), 0.0);
  const std::size_t m = p->my_separator.size();
  // (an interior that no separator unknown touches: a matrix of disconnected parts, which the
  // ranks would not share; the same answer on every rank)
  int fewest = static_cast<int>(m);
  const int ierr = MPI_Allreduce(MPI_IN_PLACE, &fewest, 1, MPI_INT, MPI_MIN, team);
  AssertThrowMPI(ierr);
  if (fewest == 0)
    return nullptr;
  p->schur_term.assign(m * m, 0.0);

  // MUMPS on this rank alone, with the settings of SparseDirect (AMD, MUMPS's column permutation
  // and scaling, 20 % workspace margin) and the Schur complement by columns (ICNTL(19) = 3)
  DMUMPS_STRUC_C &id = p->id;
  id.comm_fortran = static_cast<MUMPS_INT>(MPI_Comm_c2f(MPI_COMM_SELF));
  id.par = 1;
  id.sym = 0;
  id.job = -1;
  dmumps_c(&id);
  p->mumps_made = id.infog[0] >= 0;
  agree_on(id.infog[0], id.infog[1], team, "initialisation");
  for (const int stream : {0, 1, 2, 3})
    id.icntl[stream] = -1;
  id.icntl[5] = 7;
  id.icntl[6] = 0;
  id.icntl[7] = 7;
  id.icntl[13] = 20;
  id.icntl[18] = 3;
  // Null pivots detected and counted (ICNTL(24) = 1, INFOG(28)), refused in factorize(). A front
  // whose parent is the Schur complement may not delay a pivot to it: MUMPS then takes the pivot
  // it has, and one below u in size is replaced by +-u and only counted (INFOG(25)). So a part
  // with an exactly zero pivot came back without an error, and the shared solve of a singular
  // matrix gave 4.5e15 (b / u) for that unknown, with a normwise backward error small enough to
  // pass SparseDirect's check because |x| is that large
  // (SparseDirect.SingularMatrixSharedOnSeveralRanksIsRefusedOnEveryRank), where one rank's MUMPS
  // of the whole matrix says it is singular. A row and column whose entries outside the
  // separator are all below MUMPS's threshold (CNTL(3) = 0: u sqrt(depth of the tree) times the
  // norm of the scaled matrix) are counted as null; that includes an interior unknown coupled
  // only to separator unknowns (SparseDirect.SingularPartOnSeveralRanks...), a part singular where
  // the whole matrix need not be. Either count refuses the part; SparseDirect then factorises the
  // whole matrix.
  id.icntl[23] = 1;
  id.n = p->n_local;
  id.nnz = static_cast<MUMPS_INT8>(p->local_row.size());
  id.irn = p->local_row.data();
  id.jcn = p->local_column.data();
  id.size_schur = static_cast<MUMPS_INT>(m);
  id.listvar_schur = p->schur_list.data();
  id.schur = p->schur_term.data();
  id.schur_lld = static_cast<MUMPS_INT>(m);
  id.nprow = id.npcol = 1; // (the complement on this one process)
  id.mblock = id.nblock = 64;
  id.job = 1;
  dmumps_c(&id);
  agree_on(id.infog[0], id.infog[1], team, "analysis");
  return p;
}

void SubstructuredLU::factorize(const double *values)
{
  if (!part)
    throw std::logic_error("SubstructuredLU::factorize: no pattern analysed");
  Part &p = *part;
  DMUMPS_STRUC_C &id = p.id;
  // this rank's part (a failure here, MUMPS's or an exception, is agreed on below)
  const int local = run_locally(
      [&]()
      {
        for (std::size_t k = 0; k < p.entry_of.size(); ++k)
          p.local_values[k] = p.entry_of[k] >= 0 ? values[p.entry_of[k]] : 0.0;
        id.a = p.local_values.data();
        // a workspace estimate that falls short (numerical pivoting) is retried with twice the
        // margin, three times, as in SparseDirect
        for (int attempt = 0;; ++attempt)
        {
          id.job = 2;
          dmumps_c(&id);
          if (!(id.infog[0] == -8 || id.infog[0] == -9) || attempt == 3)
            break;
          id.icntl[13] *= 2;
          ++p.retries;
        }
        // a null pivot (INFOG(28)) or a pivot replaced by +-u (INFOG(25); static pivoting is
        // off, so these are the pivots a front next to the separator could not delay): this part,
        // or the whole matrix, is singular (MUMPS's "numerically singular", -10; SparseDirect
        // then tries the whole matrix)
        if (id.infog[0] >= 0 && (id.infog[27] > 0 || id.infog[24] > 0))
          return -10;
        return id.infog[0];
      });
  agree_on(local, id.infog[1], team, "factorisation");
  // The complement, A_SS (in the first rank's term) less every rank's A_Sr A_rr^-1 A_rS, summed
  // and factorised on the first rank only, which also solves with it: one copy, so that every
  // rank gets the same bits whatever its LAPACK (the others would only wait for it)
  const std::size_t s = p.separator.size(), m = p.my_separator.size();
  int status = run_locally(
      [&]()
      {
        // (kept with the part: fresh memory at every factorisation costs page faults)
        std::vector<double> &complement = p.complement_sum;
        complement.assign(s * s, 0.0);
        for (std::size_t c = 0; c < m; ++c)
          for (std::size_t r = 0; r < m; ++r)
            complement[p.my_separator[c] * s + p.my_separator[r]] += p.schur_term[c * m + r];
        return 0;
      });
  agree_on(status, 0, team, "Schur complement");
  sum_on_first_rank(p.complement_sum, team);
  if (p.rank == 0)
    status = run_locally(
        [&]()
        {
          p.complement.reinit(s, s);
          for (std::size_t c = 0; c < s; ++c)
            for (std::size_t r = 0; r < s; ++r)
              p.complement(r, c) = p.complement_sum[c * s + r];
          // (a zero pivot throws in deal.II)
          p.complement.compute_lu_factorization();
          return 0;
        });
  first_rank_decides(status, team,
                     "Reynolds solver: the Schur complement of a substructured factorisation is "
                     "singular");
}

void SubstructuredLU::solve(double *X, const int m)
{
  if (!part)
    throw std::logic_error("SubstructuredLU::solve: no factorisation");
  Part &p = *part;
  const std::size_t n = p.n, s = p.separator.size(), ms = p.my_separator.size(),
                    n_local = p.n_local;
  DMUMPS_STRUC_C &id = p.id;
  // MUMPS's solve settings back to a plain solve after each phase, and no pointers left to the
  // buffers of this call, whatever happens
  struct PlainSolveAfterwards
  {
    DMUMPS_STRUC_C &id;
    ~PlainSolveAfterwards()
    {
      id.icntl[25] = 0;
      id.nrhs = 1;
      id.rhs = id.redrhs = nullptr;
    }
  } restore{id};
  // condensation on this rank: its interior's right-hand sides, zero on its separator unknowns
  std::vector<double> rhs, reduced, separator_rhs;
  int status = run_locally(
      [&]()
      {
        rhs.assign(n_local * m, 0.0);
        reduced.assign(ms * m, 0.0);
        const int *mine = p.interiors.data() + p.interior_offsets[p.rank];
        for (int c = 0; c < m; ++c)
          for (int k = 0; k < p.n_interior; ++k)
            rhs[c * n_local + k] = X[c * n + mine[k]];
        id.nrhs = m;
        id.lrhs = static_cast<MUMPS_INT>(n_local);
        id.rhs = rhs.data();
        id.redrhs = reduced.data();
        id.lredrhs = static_cast<MUMPS_INT>(ms);
        id.icntl[25] = 1;
        id.job = 3;
        dmumps_c(&id);
        if (id.infog[0] >= 0)
        {
          separator_rhs.assign(s * m, 0.0);
          for (int c = 0; c < m; ++c)
            for (std::size_t k = 0; k < ms; ++k)
              separator_rhs[c * s + p.my_separator[k]] += reduced[c * ms + k];
        }
        return id.infog[0];
      });
  agree_on(status, id.infog[1], team, "condensation");
  // the separator's right-hand side b_S - sum_r A_Sr A_rr^-1 b_r on the first rank, which solves
  // the complement system and sends x_S to all
  sum_on_first_rank(separator_rhs, team);
  std::vector<double> &x_separator = separator_rhs;
  if (p.rank == 0)
    status = run_locally(
        [&]()
        {
          dealii::LAPACKFullMatrix<double> x(s, m);
          for (int c = 0; c < m; ++c)
            for (std::size_t k = 0; k < s; ++k)
              x(k, c) = separator_rhs[c * s + k] + X[c * n + p.separator[k]];
          p.complement.solve(x);
          for (int c = 0; c < m; ++c)
            for (std::size_t k = 0; k < s; ++k)
              x_separator[c * s + k] = x(k, c);
          return 0;
        });
  first_rank_decides(status, team,
                     "Reynolds solver: the dense Schur complement solve of a substructured "
                     "factorisation failed");
  int ierr = MPI_Bcast(x_separator.data(), static_cast<int>(s * m), MPI_DOUBLE, 0, team);
  AssertThrowMPI(ierr);
  // expansion: x_r = A_rr^-1 (b_r - A_rS x_S), from the condensation's state in `rhs`
  std::vector<int> counts(p.ranks), offsets(p.ranks);
  std::vector<double> my_interior, all;
  status = run_locally(
      [&]()
      {
        for (int c = 0; c < m; ++c)
          for (std::size_t k = 0; k < ms; ++k)
            reduced[c * ms + k] = x_separator[c * s + p.my_separator[k]];
        id.icntl[25] = 2;
        id.job = 3;
        dmumps_c(&id);
        if (id.infog[0] < 0)
          return id.infog[0];
        for (int r = 0; r < p.ranks; ++r)
        {
          const long long count =
                              (long long)(p.interior_offsets[r + 1] - p.interior_offsets[r]) * m,
                          offset = (long long)p.interior_offsets[r] * m;
          if (offset + count > std::numeric_limits<int>::max())
            throw std::runtime_error("too many right-hand sides for MPI counts");
          counts[r] = static_cast<int>(count);
          offsets[r] = static_cast<int>(offset);
        }
        my_interior.resize(std::size_t(p.n_interior) * m);
        all.resize((n - s) * m);
        for (int c = 0; c < m; ++c)
          std::copy(rhs.begin() + c * n_local, rhs.begin() + c * n_local + p.n_interior,
                    my_interior.begin() + std::size_t(c) * p.n_interior);
        return 0;
      });
  agree_on(status, id.infog[1], team, "expansion");
  // every rank's interior values to every rank
  ierr = MPI_Allgatherv(my_interior.data(), counts[p.rank], MPI_DOUBLE, all.data(), counts.data(),
                        offsets.data(), MPI_DOUBLE, team);
  AssertThrowMPI(ierr);
  for (int r = 0; r < p.ranks; ++r)
  {
    const int first = p.interior_offsets[r], size = p.interior_offsets[r + 1] - first;
    for (int c = 0; c < m; ++c)
      for (int k = 0; k < size; ++k)
        X[c * n + p.interiors[first + k]] = all[offsets[r] + std::size_t(c) * size + k];
  }
  for (int c = 0; c < m; ++c)
    for (std::size_t k = 0; k < s; ++k)
      X[c * n + p.separator[k]] = x_separator[c * s + k];
}

} // namespace sealfe::numerics
