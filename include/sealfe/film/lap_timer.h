// LapTimer: wall time of the consecutive parts of a stage, added to named entries of a map (the
// finer breakdown of the setup and multigrid stages in summary.json, doc/performance.md).
#pragma once

#include <chrono>
#include <map>
#include <string>

namespace sealfe
{
/// lap("name") adds the seconds since the previous lap (or construction) to times["name"].
class LapTimer
{
public:
  explicit LapTimer(std::map<std::string, double> &times_in) : times(times_in) {}
  void operator()(const std::string &name)
  {
    const auto now = std::chrono::steady_clock::now();
    times[name] += std::chrono::duration<double>(now - last).count();
    last = now;
  }

private:
  std::map<std::string, double> &times;
  std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now();
};
} // namespace sealfe
