// Interrupt: SIGINT / SIGTERM ask a long loop (the points of a table, the output steps of a
// transient) to stop at its next check, so that the finished work is published as an incomplete
// run instead of being lost; and signals held while a run's files are renamed into place.
#pragma once

#include <mpi.h>

#include <csignal>
#include <string>

namespace sealfe
{
namespace interrupt
{
/// While it exists, the first SIGINT or SIGTERM only sets a flag (and says so on stderr) that the
/// loop polls with requested() between units of work; a second one ends the process at once with
/// status 128 + signal (130 for SIGINT), the previous run's files untouched. The previous
/// handlers are restored when it ends. Without one, the signals keep their default action (runs
/// with no loop to stop end at once, publishing nothing).
class StopOnSignal
{
public:
  StopOnSignal();
  ~StopOnSignal();
  StopOnSignal(const StopOnSignal &) = delete;
  StopOnSignal &operator=(const StopOnSignal &) = delete;

private:
  struct sigaction old_int, old_term;
};

/// Whether a stop was asked for (a signal caught by a StopOnSignal of this process).
bool requested();

/// The same, combined over `comm` (collective; MPI max): every rank gets the same answer, so that
/// all ranks stop after the same round of work.
bool requested(MPI_Comm comm);

/// Why the run stopped, for messages and summary.json: "interrupted by SIGINT" (or SIGTERM), or
/// "interrupted on another MPI rank".
std::string reason();

/// While it exists, SIGINT and SIGTERM are held: a signal that arrives is only recorded, and
/// raised again on this thread when it ends, under the handlers it found (the default action
/// ends the process; a StopOnSignal's sets its flag): a sequence of renames that publishes a run
/// is never cut half-way. Held by a handler for the whole process, not by this thread's signal
/// mask alone: the kernel gives a signal to any thread that does not block it, and the threads
/// of deal.II's task scheduler (TBB) and MPI do not.
class HoldSignals
{
public:
  HoldSignals();
  ~HoldSignals();
  HoldSignals(const HoldSignals &) = delete;
  HoldSignals &operator=(const HoldSignals &) = delete;

private:
  struct sigaction old_int, old_term;
};
} // namespace interrupt
} // namespace sealfe
