#include <sealfe/film/line_stencil_matrix.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <Epetra_Map.h>

#include <algorithm>
#include <cstdlib>

namespace sealfe
{
using namespace dealii;

namespace
{
/// y_q += v_q x_{q + e} for q0 <= q < q1: one slot of a line (x: its neighbouring line, e: the
/// slot's position offset). On x86-64 with GCC compiled for the CPU's vector width too (GCC's
/// function multiversioning; the loader picks the clone once): with AVX2 or AVX-512 the
/// float-to-double conversions and products go 4 or 8 at a time (a product at 1.05e6 Q2 dofs,
/// stand-alone: 6.6 ms against 10.3 ms with SSE2, doc/performance.md).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("default", "avx2", "arch=x86-64-v4")))
#endif
void add_slot(const float *__restrict v, const double *__restrict x, const int e,
              double *__restrict y, const int q0, const int q1)
{
  for (int q = q0; q < q1; ++q)
    y[q] += double(v[q]) * x[q + e];
}
} // namespace

void LineStencilMatrix::initialize(const MatrixType &A, const std::vector<unsigned int> &line_start)
{
  const Epetra_CrsMatrix &E = A.trilinos_matrix();
  const unsigned int n_owned = E.NumMyRows();
  AssertThrow(!line_start.empty() && line_start.front() == 0 && line_start.back() == n_owned &&
                  std::is_sorted(line_start.begin(), line_start.end()),
              ExcMessage("LineStencilMatrix: the lines must cover the owned rows in order"));
  start = line_start;
  n_rows = A.m();
  const unsigned int n_lines = start.size() - 1;
  std::vector<unsigned int> line_of(n_owned);
  for (unsigned int k = 0; k < n_lines; ++k)
    std::fill(line_of.begin() + start[k], line_of.begin() + start[k + 1], k);
  // the owned row of each column (-1: not owned), looked up once per column
  std::vector<int> row_of_column(E.ColMap().NumMyElements());
  for (unsigned int c = 0; c < row_of_column.size(); ++c)
    row_of_column[c] = E.RowMap().LID(E.ColMap().GID(c));

  // The slot (a, d) of an entry of row i = start[k] + q at column c, if it has one: the
  // smallest |a| with line (k + a) mod n_lines holding column c at position q + d, |a|, |d| <=
  // max_reach.
  struct Slot
  {
    int a, d;
  };
  auto slot_of = [&](const unsigned int k, const unsigned int q, const int c, Slot &slot)
  {
    const int j = row_of_column[c];
    if (j < 0)
      return false;
    const unsigned int kj = line_of[j];
    int a = int(kj) - int(k); // the nearest way round the ring of lines
    if (2 * a > int(n_lines))
      a -= int(n_lines);
    else if (2 * a < -int(n_lines))
      a += int(n_lines);
    const int d = int(j - start[kj]) - int(q);
    if (std::abs(a) > max_reach || std::abs(d) > max_reach)
      return false;
    slot = {a, d};
    return true;
  };

  // Line by line, into a block of all (2 max_reach + 1)^2 slots: the line's reaches, or the
  // remainder; then the slots it reaches, appended. Ã_ij = float(A_ij) off the diagonal, Ã_ii =
  // A_ii + sum_j (A_ij - float(A_ij)), so that every row sums as A's does.
  constexpr int width = 2 * max_reach + 1;
  line_reach.assign(n_lines, 0);
  position_reach.assign(n_lines, 0);
  value_offset.assign(n_lines + 1, 0);
  values.clear();
  values.reserve(std::size_t(E.NumMyNonzeros()) * 3 / 2); // Q2: 20 slots per row, 16 entries
  diagonal.assign(n_owned, 0.0);
  stencil_rows = 0;
  unsigned int remainder_rows = 0;
  // zero between lines where the last line wrote (a 49-slot block per line would be zeroed 4
  // times over what Q2 fills)
  std::vector<float> block;
  for (unsigned int k = 0; k < n_lines; ++k)
  {
    const unsigned int length = start[k + 1] - start[k];
    if (block.size() < std::size_t(length) * width * width)
      block.assign(std::size_t(length) * width * width, 0.f);
    int ak = 0, rk = 0;
    for (unsigned int q = 0; q < length && ak >= 0; ++q)
    {
      const unsigned int i = start[k] + q;
      int count;
      double *row_values;
      int *columns;
      E.ExtractMyRowView(int(i), count, row_values, columns);
      double diagonal_sum = 0, rounding = 0;
      for (int e = 0; e < count; ++e)
      {
        if (row_values[e] == 0)
          continue; // zeros play no part
        if (row_of_column[columns[e]] == int(i))
        {
          diagonal_sum += row_values[e];
          continue;
        }
        Slot slot{0, 0};
        if (!slot_of(k, q, columns[e], slot))
        {
          ak = -1;
          break;
        }
        ak = std::max(ak, std::abs(slot.a));
        rk = std::max(rk, std::abs(slot.d));
        const float rounded = float(row_values[e]);
        block[std::size_t((slot.a + max_reach) * width + (slot.d + max_reach)) * length + q] +=
            rounded;
        rounding += row_values[e] - double(rounded);
      }
      diagonal[i] = diagonal_sum + rounding;
    }
    line_reach[k] = std::int8_t(ak);
    position_reach[k] = std::int8_t(rk);
    // the slots written: up to the row that did not fit, within the reaches met so far
    const int a_written = ak < 0 ? max_reach : ak, r_written = ak < 0 ? max_reach : rk;
    if (ak < 0)
    {
      std::fill(diagonal.begin() + start[k], diagonal.begin() + start[k + 1], 0.0);
      remainder_rows += length;
    }
    else
    {
      stencil_rows += length;
      for (int a = -ak; a <= ak; ++a)
      {
        const auto first =
            block.begin() + std::size_t((a + max_reach) * width + max_reach - rk) * length;
        values.insert(values.end(), first, first + std::size_t(2 * rk + 1) * length);
      }
    }
    for (int a = -a_written; a <= a_written; ++a)
    {
      const auto first =
          block.begin() + std::size_t((a + max_reach) * width + max_reach - r_written) * length;
      std::fill(first, first + std::size_t(2 * r_written + 1) * length, 0.f);
    }
    value_offset[k + 1] = values.size();
  }

  // The remainder: every entry of the lines that do not fit, in double, on A's maps. Made on
  // every rank where any rank has one (FillComplete is collective).
  remainder.reset();
  const MPI_Comm comm = A.get_mpi_communicator();
  if (Utilities::MPI::sum(remainder_rows, comm) > 0)
  {
    remainder = std::make_unique<Epetra_CrsMatrix>(Copy, E.RowMap(), E.ColMap(), 0);
    for (unsigned int k = 0; k < n_lines; ++k)
      if (line_reach[k] < 0)
        for (unsigned int i = start[k]; i < start[k + 1]; ++i)
        {
          int count;
          double *row_values;
          int *columns;
          E.ExtractMyRowView(int(i), count, row_values, columns);
          const int ierr = remainder->InsertMyValues(int(i), count, row_values, columns);
          AssertThrow(ierr >= 0, ExcTrilinosError(ierr));
        }
    const int ierr = remainder->FillComplete(E.DomainMap(), E.RangeMap());
    AssertThrow(ierr == 0, ExcTrilinosError(ierr));
    remainder_product.reinit(A.locally_owned_range_indices(), comm);
  }
}

/// The rows of line k: y_i = Ã_ii x_i + the stencil's entries, slot by slot (each slot a
/// contiguous run over the line's rows, add_slot), each over the rows whose
/// position q + d lies on that neighbouring line (nothing outside the neighbouring lines is read).
template <int A>
void LineStencilMatrix::line_product(const unsigned int k, const double *x, double *y) const
{
  const unsigned int n_lines = start.size() - 1, first = start[k];
  const int length = int(start[k + 1] - first);
  const double *__restrict d = diagonal.data() + first;
  const double *__restrict xk = x + first;
  double *__restrict yk = y + first;
  for (int q = 0; q < length; ++q)
    yk[q] = d[q] * xk[q];
  const float *v = values.data() + value_offset[k];
  const int r = position_reach[k];
  for (int a = -A; a <= A; ++a)
  {
    const unsigned int line = (k + a + 2 * n_lines) % n_lines;
    const double *xa = x + start[line];
    const int line_length = int(start[line + 1] - start[line]);
    for (int e = -r; e <= r; ++e, v += length)
      if (a != 0 || e != 0) // the diagonal's slot holds zeros
        add_slot(v, xa, e, yk, std::max(0, -e), std::min(length, line_length - e));
  }
}

void LineStencilMatrix::vmult(VectorType &dst, const VectorType &src) const
{
  const double *x = src.begin();
  double *y = dst.begin();
  // Each line writes its own rows only: the lines are split over deal.II's threads
  // (MultithreadInfo; one rank of a 2-core machine has two), with the same bits on any number.
  const auto lines = [this, x, y](const unsigned int first, const unsigned int last)
  {
    for (unsigned int k = first; k < last; ++k)
      switch (line_reach[k])
      {
      case 0:
        line_product<0>(k, x, y);
        break;
      case 1:
        line_product<1>(k, x, y);
        break;
      case 2:
        line_product<2>(k, x, y);
        break;
      case 3:
        line_product<3>(k, x, y);
        break;
      default:
        std::fill(y + start[k], y + start[k + 1], 0.0);
      }
  };
  // a grain of 16 lines: ~4000 rows of the 1.05e6-dof mesh, task overhead well below the work
  parallel::apply_to_subranges(0u, static_cast<unsigned int>(start.size() - 1), lines, 16);
  if (remainder)
  {
    const int ierr =
        remainder->Multiply(false, src.trilinos_vector(), remainder_product.trilinos_vector());
    AssertThrow(ierr == 0, ExcTrilinosError(ierr));
    const double *r = remainder_product.begin();
    for (unsigned int k = 0; k + 1 < start.size(); ++k)
      if (line_reach[k] < 0)
        for (unsigned int i = start[k]; i < start[k + 1]; ++i)
          y[i] += r[i];
  }
}

} // namespace sealfe
