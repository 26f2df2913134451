// LevelTransfer: the multigrid prolongation between the levels of a globally refined mesh (the
// finite-element embedding, zero Dirichlet columns), built as Epetra matrices in one cell loop.
#pragma once

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/multigrid/mg_constrained_dofs.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>

#include <map>
#include <memory>
#include <vector>

namespace sealfe
{
/// Prolongation from each level to the next finer one by the finite-element embedding, with the
/// columns of the coarse level's boundary dofs zeroed (zero Dirichlet data): the matrices of
/// deal.II's MGTransferPrebuilt, built directly as Epetra matrices from one loop over the parent
/// cells instead of deal.II's generic path (a dynamic sparsity pattern, a FullMatrix copy per
/// child, set() through the Trilinos wrapper, and the copy indices between the active and level
/// numberings, which FilmMultigrid's V-cycle on the system's own numbering does not need: 0.6 s
/// at 1e6 Q2 dofs, doc/performance.md). Tested against MGTransferPrebuilt
/// (tests/validation/level_transfer.cc).
class LevelTransfer
{
public:
  using VectorType = dealii::TrilinosWrappers::MPI::Vector;

  /// Builds the prolongation into every level l >= 1 from level l - 1. Returns false where an
  /// owned row of a finer level is not reached from a parent cell this rank sees (possible on
  /// several ranks; every rank returns the same). fine_active: the finest level's rows are the
  /// active dofs of its cells (the system's numbering; every cell of that level is active on a
  /// globally refined mesh), its level dofs are not used. `comm`: the communicator of the
  /// vectors it acts on (the film solver's; a serial mesh's own is MPI_COMM_SELF).
  bool build(const dealii::DoFHandler<2> &dof_handler,
             const dealii::MGConstrainedDoFs &constrained_dofs, bool fine_active, MPI_Comm comm);

  /// dst (level l) += P src (level l - 1)
  void prolongate_and_add(unsigned int l, VectorType &dst, const VectorType &src);

  /// dst (level l - 1) += P^T src (level l)
  void restrict_and_add(unsigned int l, VectorType &dst, const VectorType &src);

private:
  std::vector<std::unique_ptr<Epetra_Map>> maps;
  std::vector<std::unique_ptr<Epetra_CrsMatrix>> prolongation; // [l]: level l - 1 -> l
  std::map<unsigned int, VectorType> scratch;
  VectorType &work(unsigned int l, const VectorType &like);
};

} // namespace sealfe
