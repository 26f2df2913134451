// Small symmetric matrices numbered by lines of dofs (the layout of the annulus' radial lines),
// for the tests of the line smoother's kernels: LineJacobi (validation/line_jacobi.cc) and their
// threaded forms (validation/threaded_kernels.cc).
#pragma once

#include <sealfe/film/line_jacobi.h>

#include <deal.II/base/index_set.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <mpi.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <utility>
#include <vector>

namespace sealfe::testing
{
using Entries = std::map<std::pair<unsigned int, unsigned int>, double>;

/// Lines of these lengths, numbered one after the other.
inline RadialLines lines_of_lengths(const std::vector<unsigned int> &lengths)
{
  RadialLines lines;
  lines.start = {0};
  for (const unsigned int m : lengths)
    lines.start.push_back(lines.start.back() + m);
  lines.order.resize(lines.start.back()); // numbered by lines: the position is the index
  return lines;
}

/// The same lines with the dofs numbered otherwise, as deal.II numbers a multigrid level:
/// number[p] is the dof at line position p.
inline RadialLines permuted_lines(const RadialLines &by_lines,
                                  const std::vector<unsigned int> &number)
{
  RadialLines permuted;
  permuted.start = by_lines.start;
  permuted.order.resize(number.size());
  for (unsigned int p = 0; p < number.size(); ++p)
    permuted.order[number[p]] = p; // the line position of each dof
  permuted.index_by_position();
  return permuted;
}

/// A symmetric, strictly diagonally dominant matrix (so positive definite) numbered by lines:
/// within a line, entries at distances 1..w; each dof coupled to the dofs at the same and the
/// next position of the next line (cyclically); values not sums of round numbers.
inline Entries make_entries(const RadialLines &lines, const unsigned int w)
{
  Entries a;
  const unsigned int n_lines = lines.start.size() - 1;
  auto couple = [&](const unsigned int i, const unsigned int j, const double v)
  {
    a[{i, j}] = v;
    a[{j, i}] = v;
  };
  for (unsigned int k = 0; k < n_lines; ++k)
  {
    const unsigned int first = lines.start[k], last = lines.start[k + 1];
    for (unsigned int p = first; p < last; ++p)
    {
      for (unsigned int d = 1; d <= w && p + d < last; ++d)
        couple(p, p + d, -(1 + 0.3 * std::sin(0.7 * p + 1.3 * (p + d))));
      const unsigned int next = (k + 1) % n_lines, i = p - first;
      for (unsigned int s = 0; s < 2; ++s)
        if (i + s < lines.start[next + 1] - lines.start[next])
          couple(p, lines.start[next] + i + s, -(0.4 + 0.1 * std::cos(1.0 * p + s)));
    }
  }
  std::vector<double> row_sum(lines.size(), 0.0);
  for (const auto &[ij, v] : a)
    row_sum[ij.first] += std::abs(v);
  for (unsigned int i = 0; i < lines.size(); ++i)
    a[{i, i}] = row_sum[i] + 1 + 0.2 * std::sin(1.0 * i);
  return a;
}

/// The Trilinos matrix of `a` with dof i numbered number[i], on MPI_COMM_SELF.
inline void make_matrix(dealii::TrilinosWrappers::SparseMatrix &A, const Entries &a,
                        const std::vector<unsigned int> &number)
{
  const unsigned int n = number.size();
  dealii::DynamicSparsityPattern dsp(n, n);
  for (const auto &[ij, v] : a)
    dsp.add(number[ij.first], number[ij.second]);
  const dealii::IndexSet all = dealii::complete_index_set(n);
  A.reinit(all, all, dsp, MPI_COMM_SELF);
  for (const auto &[ij, v] : a)
    A.set(number[ij.first], number[ij.second], v);
  A.compress(dealii::VectorOperation::insert);
}
} // namespace sealfe::testing
