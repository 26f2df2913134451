#include <sealfe/io/output.h>
#include <sealfe/io/python_plot.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <system_error>

namespace fs = std::filesystem;

namespace sealfe
{
namespace
{
std::string quoted(const std::string &s)
{
  std::string q = "'";
  for (const char c : s)
    q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

bool is_file(const fs::path &p)
{
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}
} // namespace

std::string find_script(const std::string &name)
{
  std::vector<fs::path> directories;
  if (const char *dir = std::getenv("SEALFE_SCRIPT_DIR"))
    directories.emplace_back(dir);
  std::error_code ec;
  const fs::path executable = fs::read_symlink("/proc/self/exe", ec);
  if (!ec)
  {
    directories.push_back(executable.parent_path().parent_path() / "scripts");
    directories.push_back(executable.parent_path() / "scripts");
  }
#ifdef SEALFE_SOURCE_DIR
  directories.push_back(fs::path(SEALFE_SOURCE_DIR) / "scripts");
#endif
  for (const fs::path &d : directories)
    if (is_file(d / name))
      return (d / name).lexically_normal().string();
  return "";
}

PlotResult run_plot_script(const std::string &script_name,
                           const std::vector<std::string> &arguments, const std::string &png,
                           const std::string &python, const std::string &script)
{
  PlotResult result;
  const std::string path = script.empty() ? find_script(script_name) : script;
  std::string args;
  for (const std::string &a : arguments)
    args += " " + quoted(a);
  result.command = output::published_name(
      "python3 " + quoted(path.empty() ? "scripts/" + script_name : path) + args);
  if (path.empty() || !is_file(path))
  {
    result.note = "plot skipped: " + (path.empty() ? "scripts/" + script_name : path) +
                  " not found (set SEALFE_SCRIPT_DIR)";
    return result;
  }
  const std::vector<std::string> interpreters =
      python.empty() ? std::vector<std::string>{"/usr/bin/python3", "python3"}
                     : std::vector<std::string>{python};
  for (const std::string &py : interpreters)
  {
    const std::string probe = quoted(py) + " -c 'import matplotlib' > /dev/null 2>&1";
    if (std::system(probe.c_str()) != 0)
      continue;
    const std::string command = quoted(py) + " " + quoted(path) + args;
    // the files are staged while the run is in progress: the user reruns it on the published ones
    result.command = output::published_name(command);
    const std::string cmd = command + " > /dev/null 2>&1";
    if (std::system(cmd.c_str()) == 0 && is_file(png))
    {
      result.made = true;
      return result;
    }
    result.note = "plot failed: " + result.command;
    return result;
  }
  result.note = "plot skipped: no " + (python.empty() ? std::string("python3") : quoted(python)) +
                " with matplotlib (install python3-matplotlib or pip install matplotlib)";
  return result;
}

void report_skipped_plot(const std::string &program, const PlotResult &plot)
{
  std::cerr << program << ": " << plot.note << "; to make it: " << plot.command << std::endl;
}

} // namespace sealfe
