// Work over a list of items (cells) whose results must be summed in the list's order: each batch
// of items is computed on deal.II's threads, then handed on one thread, in order, to whatever sums
// it, while the next batch computes. The sums are those of one loop over the items, so the result
// has the same bits on any number of threads.
#pragma once

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/thread_management.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <exception>
#include <functional>

namespace sealfe::numerics
{
/// For the items 0 .. n_items - 1 in batches of `batch_size`: compute(batch, first_item, begin,
/// end) fills the results of the items first_item + [begin, end) into `batch`, on any thread
/// (several calls per batch run at once, on disjoint ranges: a range is split while it is longer
/// than `grain` items); then
/// add(batch, first_item, count) takes the batch's `count` results on the calling thread, in the
/// order of the batches. Two batches alternate: the next one computes while `add` takes the
/// last. An exception from either is rethrown after the batch still running has ended (it refers
/// to the caller's objects).
template <typename Batch, typename Compute, typename Add>
void compute_in_batches_add_in_order(const std::size_t n_items, const std::size_t batch_size,
                                     std::array<Batch, 2> &batches, const std::size_t grain,
                                     const Compute &compute, const Add &add)
{
  AssertThrow(batch_size > 0, dealii::ExcMessage("compute_in_batches_add_in_order: empty batches"));
  auto compute_batch = [&](const std::size_t first_item, Batch &batch)
  {
    const std::size_t count = std::min(batch_size, n_items - first_item);
    dealii::parallel::apply_to_subranges(
        std::size_t(0), count,
        [&](const std::size_t begin, const std::size_t end)
        { compute(batch, first_item, begin, end); },
        grain);
  };
  dealii::Threads::Task<void> next; // the batch computed while the previous one is added
  // What the running batch threw. deal.II 9.4's Task<void>::join() does not rethrow it (its
  // TaskData::wait never calls the future's get() for void), so the batch keeps it here; one
  // batch runs at a time, joined before the next starts.
  std::exception_ptr batch_failure;
  auto start = [&](const std::size_t first_item, Batch &batch)
  {
    next = dealii::Threads::new_task(std::function<void()>(
        [&compute_batch, first_item, &batch, &batch_failure]()
        {
          try
          {
            compute_batch(first_item, batch);
          }
          catch (...)
          {
            batch_failure = std::current_exception();
          }
        }));
  };
  try
  {
    if (n_items > 0)
      start(0, batches[0]);
    for (std::size_t first_item = 0, b = 0; first_item < n_items;
         first_item += batch_size, b = 1 - b)
    {
      next.join();
      if (batch_failure)
        std::rethrow_exception(batch_failure);
      if (first_item + batch_size < n_items)
        start(first_item + batch_size, batches[1 - b]);
      add(static_cast<const Batch &>(batches[b]), first_item,
          std::min(batch_size, n_items - first_item));
    }
  }
  catch (...)
  {
    if (next.joinable())
      try
      {
        next.join();
      }
      catch (...)
      {
      }
    throw;
  }
}
} // namespace sealfe::numerics
