// Test support: run the sealfe binary on a prm body in a fresh directory and read what it wrote.
#pragma once

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace sealfe::testing
{
namespace fs = std::filesystem;

/// Exit status, stdout and stderr of one run.
struct CliResult
{
  int status;
  std::string out, err;
};

/// An empty directory <tmp>/<name>, created afresh.
inline fs::path fresh_directory(const std::string &name)
{
  const fs::path d = fs::temp_directory_path() / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

inline std::string read_file(const fs::path &f)
{
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The columns of a CSV text with a header line (doc/csv.md), keyed by the name before " [unit]";
/// a field that is empty, missing at the end of a row or not a number is NaN, so that every
/// column has one entry per row.
inline std::map<std::string, std::vector<double>> read_csv(const std::string &text)
{
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::istringstream header(line);
  for (std::string cell; std::getline(header, cell, ',');)
    names.push_back(cell.substr(0, cell.find(" [")));
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line))
  {
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');)
      cells.push_back(cell);
    for (std::size_t i = 0; i < names.size(); ++i)
    {
      const char *begin = i < cells.size() ? cells[i].c_str() : "";
      char *end = nullptr;
      const double value = std::strtod(begin, &end);
      columns[names[i]].push_back(end == begin ? std::nan("") : value);
    }
  }
  return columns;
}

/// Runs `[launcher] sealfe <command> case.prm` in `dir` with the prm body; the Output directory
/// is dir/out.
inline CliResult run_sealfe(const fs::path &dir, const std::string &command,
                            const std::string &body, const std::string &launcher = "")
{
  const fs::path prm = dir / "case.prm";
  {
    std::ofstream out(prm);
    out << "set Output directory = " << (dir / "out").string() << "\n" << body;
  }
  const std::string cmd = launcher + std::string(SEALFE_BINARY) + " " + command + " " +
                          prm.string() + " > " + (dir / "stdout").string() + " 2> " +
                          (dir / "stderr").string();
  const int raw = std::system(cmd.c_str());
  return {WEXITSTATUS(raw), read_file(dir / "stdout"), read_file(dir / "stderr")};
}

/// Starts `sealfe <command> case.prm` in `dir` as run_sealfe does, without waiting (stdout and
/// stderr in dir/stdout, dir/stderr): for tests that signal the run part-way. Returns its pid.
inline pid_t start_sealfe(const fs::path &dir, const std::string &command, const std::string &body)
{
  const fs::path prm = dir / "case.prm";
  {
    std::ofstream out(prm);
    out << "set Output directory = " << (dir / "out").string() << "\n" << body;
  }
  const std::string out = (dir / "stdout").string(), err = (dir / "stderr").string();
  const pid_t pid = fork();
  if (pid == 0)
  {
    if (!std::freopen(out.c_str(), "w", stdout) || !std::freopen(err.c_str(), "w", stderr))
      _exit(127);
    execl(SEALFE_BINARY, SEALFE_BINARY, command.c_str(), prm.c_str(), static_cast<char *>(nullptr));
    _exit(127);
  }
  return pid;
}

/// Waits until `file` contains `needle` at least `count` times (true), the process `pid` ended or
/// `seconds` passed (false).
inline bool wait_for_text(const fs::path &file, const std::string &needle, const unsigned int count,
                          const pid_t pid, const double seconds)
{
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end)
  {
    const std::string text = read_file(file);
    unsigned int n = 0;
    for (std::size_t at = text.find(needle); at != std::string::npos;
         at = text.find(needle, at + needle.size()))
      ++n;
    if (n >= count)
      return true;
    siginfo_t info = {};
    if (waitid(P_PID, pid, &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid)
      return false; // ended (left to be reaped by wait_sealfe)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

/// Exit status of `pid` (128 + signal if a signal ended it), stdout and stderr; after `seconds`
/// the process is killed and the status is -1.
inline CliResult wait_sealfe(const fs::path &dir, const pid_t pid, const double seconds)
{
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int raw = 0, status = -1;
  while (true)
  {
    if (waitpid(pid, &raw, WNOHANG) == pid)
    {
      status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
      break;
    }
    if (std::chrono::steady_clock::now() > end)
    {
      kill(pid, SIGKILL);
      waitpid(pid, &raw, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return {status, read_file(dir / "stdout"), read_file(dir / "stderr")};
}
} // namespace sealfe::testing
