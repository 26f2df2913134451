#include <sealfe/film/line_jacobi.h>

#include <deal.II/base/parallel.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>

#include <algorithm>
#include <cstddef>

namespace sealfe
{
void RadialLines::index_by_position()
{
  at.resize(order.size());
  for (unsigned int i = 0; i < order.size(); ++i)
    at[order[i]] = i;
}

void LineJacobi::initialize(const MatrixType &A, const RadialLines &lines_in)
{
  lines = &lines_in;
  const Epetra_CrsMatrix &E = A.trilinos_matrix();
  const unsigned int n = lines->size();
  // the band and the factors are kept by line position (the owned index where the dofs are
  // numbered by lines; else the vectors are gathered into that order for the solve)
  const bool permuted = !lines->at.empty();
  if (permuted)
    work.resize(n);
  std::vector<unsigned int> line_of(n);
  for (unsigned int k = 0; k + 1 < lines->start.size(); ++k)
  {
    for (unsigned int p = lines->start[k]; p < lines->start[k + 1]; ++p)
      line_of[p] = k;
  }
  // the row of each column (-1: not owned), looked up once per column instead of per entry
  std::vector<int> row_of_column(E.ColMap().NumMyElements());
  for (unsigned int c = 0; c < row_of_column.size(); ++c)
    row_of_column[c] = E.RowMap().LID(E.ColMap().GID(c));
  // f(p, q, A_ij) for the entries of A that couple two dofs i, j of one line, at the line
  // positions p, q
  auto for_each_line_entry = [&](const auto &f)
  {
    for (unsigned int p = 0; p < n; ++p)
    {
      int count;
      double *values;
      int *columns;
      E.ExtractMyRowView(int(lines->index(p)), count, values, columns);
      for (int c = 0; c < count; ++c)
      {
        const int j = row_of_column[columns[c]];
        if (j < 0)
          continue;
        const unsigned int q = permuted ? lines->order[j] : unsigned(j);
        if (line_of[q] == line_of[p])
          f(p, q, values[c]);
      }
    }
  };
  // the half bandwidth of the line blocks (the element degree on the annulus)
  band_width = 0;
  for_each_line_entry([this](const unsigned int i, const unsigned int j, double)
                      { band_width = std::max(band_width, i > j ? i - j : j - i); });
  const unsigned int w = band_width + 1;
  band.assign(std::size_t(n) * w, 0.0); // band[p * w + d] = A(p, p - d)
  for_each_line_entry(
      [this, w](const unsigned int i, const unsigned int j, const double value)
      {
        if (j <= i)
          band[std::size_t(i) * w + (i - j)] += value;
      });
  // LDL^T of each line block, in place: band[p w] = 1 / D_p, band[p w + d] = L(p, p - d).
  for (unsigned int k = 0; k + 1 < lines->start.size(); ++k)
  {
    const unsigned int first = lines->start[k], last = lines->start[k + 1];
    for (unsigned int p = first; p < last; ++p)
    {
      double *row = &band[std::size_t(p) * w];
      const unsigned int reach = std::min(band_width, p - first);
      for (unsigned int d = reach; d >= 1; --d)
      {
        const unsigned int q = p - d; // L(p, q) = (A(p, q) - sum_m L(p, m) D_m L(q, m)) / D_q
        const double *row_q = &band[std::size_t(q) * w];
        double sum = row[d];
        for (unsigned int e = d + 1; e <= reach; ++e)
          sum -= row[e] * row_q[e - d] / band[std::size_t(p - e) * w];
        row[d] = sum * row_q[0];
      }
      double diagonal = row[0];
      for (unsigned int d = 1; d <= reach; ++d)
        diagonal -= row[d] * row[d] / band[std::size_t(p - d) * w];
      row[0] = 1 / diagonal; // D_p^-1
    }
  }
}

void LineJacobi::vmult(VectorType &dst, const VectorType &src) const
{
  // Each line is solved on its own: the lines are split over deal.II's threads (MultithreadInfo;
  // one rank of a 2-core machine has two), with the same bits on any number.
  const double *b = src.begin();
  double *x = dst.begin();
  const std::vector<unsigned int> &start = lines->start;
  const auto some_lines = [&](const unsigned int first, const unsigned int last)
  {
    if (lines->at.empty())
      solve(x, b, first, last);
    else
    {
      // in line order, then back (the same operations as on a level numbered by lines)
      for (unsigned int p = start[first]; p < start[last]; ++p)
        work[p] = b[lines->at[p]];
      solve(work.data(), work.data(), first, last);
      for (unsigned int p = start[first]; p < start[last]; ++p)
        x[lines->at[p]] = work[p];
    }
  };
  // a grain of 16 lines: ~4000 rows of the 1.05e6-dof mesh, task overhead well below the work
  dealii::parallel::apply_to_subranges(0u, static_cast<unsigned int>(start.size() - 1), some_lines,
                                       16);
}

void LineJacobi::solve(double *x, const double *b, const unsigned int first,
                       const unsigned int last) const
{
  switch (band_width)
  {
  case 1:
    solve<1>(x, b, first, last);
    break;
  case 2:
    solve<2>(x, b, first, last);
    break;
  case 3:
    solve<3>(x, b, first, last);
    break;
  default:
    solve<0>(x, b, first, last);
  }
}

/// x = (L D L^T)^-1 b line by line: L y = b forward, then x = D^-1 y - L^T x backward (the
/// scaling by D^-1 done in the backward sweep, the same operations in the same order as three
/// separate sweeps). B: the bandwidth as a constant (the rows past the first B of a line
/// have a full band, an unrolled loop); 0: `band_width` at run time. Each sweep is a chain of
/// dependent multiply-adds along the line, so lines of one length are swept `interleaved` at a
/// time, row by row, their chains side by side (each line's operations as alone: the same bits;
/// at 1.05e6 Q2 dofs a solve took 7 ms one line at a time, doc/performance.md).
template <unsigned int B>
void LineJacobi::solve(double *x, const double *b, const unsigned int first_line,
                       const unsigned int last_line) const
{
  const unsigned int width = B > 0 ? B : band_width, w = width + 1;
  const double *band_data = band.data();
  auto forward = [&](const unsigned int first, const unsigned int p) // row p of L y = b
  {
    const double *row = band_data + std::size_t(p) * w;
    double v = b[p];
    if (B > 0 && p - first >= B)
      for (unsigned int d = 1; d <= B; ++d)
        v -= row[d] * x[p - d];
    else
    {
      const unsigned int reach = std::min(width, p - first);
      for (unsigned int d = 1; d <= reach; ++d)
        v -= row[d] * x[p - d];
    }
    x[p] = v;
  };
  auto backward = [&](const unsigned int last, const unsigned int p) // x = D^-1 y - L^T x
  {
    double v = x[p] * band_data[std::size_t(p) * w];
    if (B > 0 && last - 1 - p >= B)
      for (unsigned int d = 1; d <= B; ++d)
        v -= band_data[std::size_t(p + d) * w + d] * x[p + d];
    else
    {
      const unsigned int reach = std::min(width, last - 1 - p);
      for (unsigned int d = 1; d <= reach; ++d)
        v -= band_data[std::size_t(p + d) * w + d] * x[p + d];
    }
    x[p] = v;
  };
  constexpr unsigned int interleaved = 4;
  const std::vector<unsigned int> &start = lines->start;
  for (unsigned int k = first_line; k < last_line;)
  {
    const unsigned int first = start[k], length = start[k + 1] - first;
    bool group = k + interleaved <= last_line;
    for (unsigned int g = 1; g < interleaved && group; ++g)
      group = start[k + g + 1] - start[k + g] == length;
    if (group)
    {
      for (unsigned int q = 0; q < length; ++q)
        for (unsigned int g = 0; g < interleaved; ++g)
          forward(first + g * length, first + g * length + q);
      for (unsigned int q = length; q-- > 0;)
        for (unsigned int g = 0; g < interleaved; ++g)
          backward(first + (g + 1) * length, first + g * length + q);
      k += interleaved;
    }
    else
    {
      for (unsigned int p = first; p < first + length; ++p)
        forward(first, p);
      for (unsigned int p = first + length; p-- > first;)
        backward(first + length, p);
      ++k;
    }
  }
}

} // namespace sealfe
