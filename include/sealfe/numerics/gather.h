// Every rank's values, gathered in rank order: the one MPI_Allgatherv that the band solve of the
// JFO polish and the row gathering of `sealfe table` share.
#pragma once

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <limits>
#include <vector>

namespace sealfe::numerics
{
/// Every rank's `mine`, on every rank, one after the other in rank order (one MPI_Allgatherv;
/// deal.II's all_gather packs and compresses, which is measurable at a band's 1e5 entries).
/// Collective; T is a type deal.II knows an MPI type of (char, int, double, ...).
template <typename T>
std::vector<T> gather_on_every_rank(const MPI_Comm comm, const std::vector<T> &mine)
{
  const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
  std::vector<int> counts(n_ranks), offsets(n_ranks + 1, 0);
  AssertThrow(mine.size() <= std::size_t(std::numeric_limits<int>::max()),
              dealii::ExcMessage("gather: more entries on one rank than MPI counts"));
  const int my_count = static_cast<int>(mine.size());
  int ierr = MPI_Allgather(&my_count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  AssertThrowMPI(ierr);
  for (unsigned int rank = 0; rank < n_ranks; ++rank)
  {
    AssertThrow(std::size_t(offsets[rank]) + counts[rank] <=
                    std::size_t(std::numeric_limits<int>::max()),
                dealii::ExcMessage("gather: more entries than MPI counts"));
    offsets[rank + 1] = offsets[rank] + counts[rank];
  }
  std::vector<T> all(offsets.back());
  const MPI_Datatype type =
      dealii::Utilities::MPI::internal::MPIDataTypes::mpi_type_id(mine.data());
  ierr = MPI_Allgatherv(mine.data(), my_count, type, all.data(), counts.data(), offsets.data(),
                        type, comm);
  AssertThrowMPI(ierr);
  return all;
}
} // namespace sealfe::numerics
