// Test support: run the sealfe binary on a prm body in a fresh directory and read what it wrote.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

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
} // namespace sealfe::testing
