#include <sealfe/io/interrupt.h>

#include <signal.h>
#include <unistd.h>

namespace sealfe
{
namespace interrupt
{
namespace
{
// Written by the handler, read by the loop: only a sig_atomic_t is safe to share with a handler.
volatile std::sig_atomic_t received_signal = 0;
// Set when another rank's signal stopped this one (for the message only).
bool stopped_by_other_rank = false;

extern "C" void on_signal(const int signal)
{
  if (received_signal != 0)
    _exit(128 + signal); // the second signal: at once, nothing more written
  received_signal = signal;
  // write(2) is async-signal-safe; iostreams are not
  const char message[] = "\nsealfe: interrupted: finishing the current point/step, then writing "
                         "what is done (interrupt again to quit at once)\n";
  [[maybe_unused]] const auto written = ::write(STDERR_FILENO, message, sizeof(message) - 1);
}
// The signal that arrived while a HoldSignals existed (0: none); the first one is kept.
volatile std::sig_atomic_t held_signal = 0;

extern "C" void on_held_signal(const int signal)
{
  if (held_signal == 0)
    held_signal = signal;
}
} // namespace

StopOnSignal::StopOnSignal()
{
  struct sigaction action = {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART; // a read or write in progress goes on
  sigaction(SIGINT, &action, &old_int);
  sigaction(SIGTERM, &action, &old_term);
}

StopOnSignal::~StopOnSignal()
{
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
}

bool requested()
{
  return received_signal != 0;
}

bool requested(MPI_Comm comm)
{
  int mine = requested() ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm);
  stopped_by_other_rank = any != 0 && mine == 0;
  return any != 0;
}

std::string reason()
{
  const int signal = received_signal;
  if (signal == SIGINT)
    return "interrupted by SIGINT";
  if (signal == SIGTERM)
    return "interrupted by SIGTERM";
  if (stopped_by_other_rank)
    return "interrupted on another MPI rank";
  return "interrupted by signal " + std::to_string(signal);
}

HoldSignals::HoldSignals()
{
  held_signal = 0;
  struct sigaction action = {};
  action.sa_handler = on_held_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART; // a rename in progress goes on
  sigaction(SIGINT, &action, &old_int);
  sigaction(SIGTERM, &action, &old_term);
}

HoldSignals::~HoldSignals()
{
  sigaction(SIGINT, &old_int, nullptr);
  sigaction(SIGTERM, &old_term, nullptr);
  if (const int signal = held_signal; signal != 0)
    ::raise(signal); // to this thread, under the restored handler
}
} // namespace interrupt
} // namespace sealfe
