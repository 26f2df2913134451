// ActiveSetKrylov: GMRES for the Jacobian of a fixed JFO active set, preconditioned
// block-triangularly in (full-film, cavitated) order (doc/performance.md, issue 13, session 13).
#pragma once

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

class Epetra_CrsMatrix;
class Epetra_Map;
class Epetra_Vector;

namespace sealfe
{
/// The Jacobian J of a fixed active set takes column j from P A (the pressure flow) where node j
/// keeps its pressure (the set F) and from G (the Couette transport of the void content) where
/// it is cavitated (C). In (F, C) order J = [P A_FF, G_FC; P A_CF, G_CC]: P A_FF is the full-film
/// operator with Dirichlet conditions at the cavity (symmetric positive definite: AMG), G_CC a
/// transport operator (upwind: ILU in the dof order, which runs along theta). The preconditioner
/// is the block lower (or upper) triangle of J with those two approximate block solves; GMRES
/// (right-preconditioned, so its tolerance is on the true residual) handles the coupling at the
/// cavity boundary. One rank.
class ActiveSetKrylov
{
public:
  using VectorType = dealii::TrilinosWrappers::MPI::Vector;
  enum class FullFilmSolver
  {
    amg,   // one ML smoothed-aggregation V-cycle (the settings of FilmLinearSolver's cg-amg)
    direct // MUMPS factorisation of P A_FF (the ideal block solve, for measurements)
  };
  enum class TransportSolver
  {
    ilu,   // Ifpack ILU(0)
    ilut,  // Ifpack ILUT (fill 2, drop 1e-6)
    direct // KLU/MUMPS factorisation of G_CC (for measurements)
  };
  struct Options
  {
    FullFilmSolver full_film = FullFilmSolver::amg;
    TransportSolver transport = TransportSolver::ilu;
    /// Lower: z_F = P A_FF^-1 r_F, then z_C = G_CC^-1 (r_C - P A_CF z_F); upper: C first.
    bool lower = true;
    unsigned int degree = 2;
    unsigned int restart = 100;
  };

  ActiveSetKrylov();
  ~ActiveSetKrylov();

  /// Split `matrix` (one rank) by `full_film` (per row; constrained rows belong to F) and set
  /// up the two block solvers. `x`, `y`: support points of the dofs (AMG aggregation).
  void setup(const dealii::TrilinosWrappers::SparseMatrix &matrix,
             const std::vector<char> &full_film, const std::vector<double> &x,
             const std::vector<double> &y, const Options &options);
  /// The preconditioner: dst = M^-1 src.
  void vmult(VectorType &dst, const VectorType &src) const;
  /// GMRES from x (its start) to |b - J x| <= target; returns the iterations, or
  /// numeric_limits<unsigned int>::max() if `max_iterations` did not reach it (x: the last
  /// iterate).
  unsigned int solve(const VectorType &b, VectorType &x, double target,
                     unsigned int max_iterations) const;

  double full_film_setup_seconds = 0, transport_setup_seconds = 0, split_seconds = 0;
  std::size_t n_full_film() const { return F.size(); }
  std::size_t n_cavitated() const { return C.size(); }

private:
  struct BlockSolver;
  const dealii::TrilinosWrappers::SparseMatrix *matrix = nullptr;
  Options options;
  std::vector<unsigned int> F, C; // dof indices of the two blocks
  // coupling rows in compressed form: the C rows' entries in F columns (lower) or the F rows'
  // entries in C columns (upper); columns by dof index
  std::vector<std::size_t> coupling_start;
  std::vector<unsigned int> coupling_column;
  std::vector<double> coupling_value;
  std::unique_ptr<Epetra_Map> map_F, map_C;
  std::unique_ptr<Epetra_CrsMatrix> J_FF, J_CC;
  std::unique_ptr<BlockSolver> solve_FF, solve_CC;
  mutable std::unique_ptr<Epetra_Vector> r_F, z_F, r_C, z_C;
};

/// Stage-1 measurement (doc/performance.md, session 13), with SEALFE_JFO_KRYLOV_PROBE set: solve
/// the active-set system (matrix, rhs) of a global round, whose direct solution `direct` took
/// `direct_seconds`, by ActiveSetKrylov with the variants the variable lists (comma separated,
/// each "ff:cc:tri", e.g. "amg:ilu:lower"; "1": amg:ilu:lower) to the relative tolerances 1e-6,
/// 1e-8, 1e-10, and print per variant and tolerance the iterations, the seconds, the largest
/// difference to `direct`, and how many nodes' flip decision (base + w < -1e-12) differs from the
/// direct one.
void probe_active_set_round(const dealii::TrilinosWrappers::SparseMatrix &matrix,
                            const dealii::TrilinosWrappers::MPI::Vector &rhs,
                            const dealii::TrilinosWrappers::MPI::Vector &direct,
                            const std::vector<char> &full_film,
                            const std::vector<char> &constrained,
                            const std::vector<double> &base_value, const std::vector<double> &x,
                            const std::vector<double> &y, unsigned int degree, double flow_scale,
                            double direct_seconds, unsigned int round, const std::string &variants,
                            std::ostream &out);

} // namespace sealfe
