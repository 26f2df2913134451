// SubstructuredLU: a sparse LU that the ranks of a team share by a vertex separator, each rank
// factorising its own part with MUMPS and the first rank the dense Schur complement on it.
// The direct solver of the cavitation models' Newton systems on several ranks.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <memory>
#include <vector>

namespace sealfe::numerics
{
/// With the unknowns split into interiors I_r, one per rank r of the team, and a separator S such
/// that no entry couples two different interiors, A x = b is
///   A_rr x_r + A_rS x_S = b_r (every r),   sum_r A_Sr x_r + A_SS x_S = b_S,
/// so x_S solves the Schur complement system (A_SS - sum_r A_Sr A_rr^-1 A_rS) x_S = b_S - sum_r
/// A_Sr A_rr^-1 b_r and then x_r = A_rr^-1 (b_r - A_rS x_S). Rank r factorises [A_rr A_rS; A_Sr
/// 0] with MUMPS (on MPI_COMM_SELF) and hands back its term of the Schur complement (MUMPS's
/// Schur option, ICNTL(19)); the terms are summed on the first rank, which factorises the dense
/// |S| x |S| complement (LAPACK). A solve is one condensation on each rank (ICNTL(26) = 1), the
/// dense solve on the first rank, whose x_S goes to all, one expansion on each (ICNTL(26) = 2).
/// Exact algebra: the answer is that of one factorisation of A up to round-off, and the same bits
/// on every rank. A failure on any rank (MUMPS's status, or an exception in this rank's part of
/// the work) throws on every rank; the collective calls run on a communicator of its own.
///
/// The split follows the caller's blocks of unknowns (an index range per rank): the separator is
/// the unknowns of a block coupled to a later block, thinned where an unknown touches one
/// interior only, with the boundaries between blocks moved to cheaper cuts. On 2D film meshes
/// whose blocks are sectors of the annulus it is about two radial lines of nodes. Each interior
/// is 1/P of the matrix, so each rank's factorisation costs about 1/P of the whole one or less,
/// where MUMPS's own parallel factorisation of the whole matrix gains little on two ranks
/// (doc/performance.md "Session 27"). No fallback here: a singular part throws (SparseDirect then
/// factorises the whole matrix), or it may come back without an error and a wrong answer (an
/// interior unknown coupled only to separator unknowns): SparseDirect checks every answer.
class SubstructuredLU
{
public:
  /// Separators larger than this are refused by analyse(): the dense complement (|S|^3 flops)
  /// would cost more than it saves.
  static inline std::size_t max_separator = 4000;
  /// The boundaries between the caller's blocks are moved to cheaper cuts (analyse()); false
  /// keeps them where given (tests of the separator).
  static inline bool move_cuts = true;

  /// `team`: the ranks that share the factorisation; every one of them passes the same matrix.
  explicit SubstructuredLU(MPI_Comm team);
  ~SubstructuredLU();
  SubstructuredLU(const SubstructuredLU &) = delete;
  SubstructuredLU &operator=(const SubstructuredLU &) = delete;

  /// The split and each rank's symbolic analysis of an n x n pattern given as entries (row[e],
  /// column[e]), 0-based, in any order, structurally symmetric (the pattern of a finite element
  /// matrix); `block_start`: P + 1 ascending offsets, rank r's block the unknowns [block_start[r],
  /// block_start[r + 1]). The same arguments on every rank. Returns false, keeping nothing, where
  /// the split does not pay: an empty interior, or a separator over max_separator or over an
  /// eighth of n (the caller then factorises the whole matrix). Collective.
  bool analyse(int n, const std::vector<int> &row, const std::vector<int> &column,
               const std::vector<long long> &block_start);
  /// The numeric factorisation of the values of the analysed entries (values[e] that of entry e).
  /// Throws on every rank if it fails on any (a singular part or complement). Collective.
  void factorize(const double *values);
  /// X (n x m values, column by column, the same on every rank) overwritten by A^-1 X on every
  /// rank. Collective.
  void solve(double *X, int m);

  /// |S|, the separator's unknowns (0 before analyse()).
  std::size_t separator_size() const;
  /// MUMPS factorisations of this rank's part repeated with twice the workspace margin.
  unsigned int workspace_retries() const;

private:
  class Part;
  /// The split from the blocks `block_start` and this rank's analysis; null where refused.
  std::unique_ptr<Part> split(int n, const std::vector<int> &row, const std::vector<int> &column,
                              const std::vector<long long> &block_start) const;
  MPI_Comm team;
  std::unique_ptr<Part> part;
};

} // namespace sealfe::numerics
