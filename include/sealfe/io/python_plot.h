// Plots by the python scripts in scripts/: where to find a script (next to the executable or in
// the source tree it was built from) and one way to run it that reports why no plot was made.
#pragma once

#include <string>
#include <vector>

namespace sealfe
{
/// Path of scripts/<name>: the directory in $SEALFE_SCRIPT_DIR, then <executable>/../scripts,
/// <executable>/scripts and the source tree the program was built from. Empty if none has it.
std::string find_script(const std::string &name);

/// What became of a plot.
struct PlotResult
{
  bool made = false;
  std::string command; ///< the command that makes (or would make) the plot, to rerun by hand
  std::string note;    ///< why no plot was made (empty if made)
};

/// Runs `<python> <script> <arguments...>` and checks that `png` appeared. `script` empty: the
/// scripts/<script_name> that find_script finds. `python` empty: the first of /usr/bin/python3
/// and python3 that imports matplotlib. Output of the script is discarded.
PlotResult run_plot_script(const std::string &script_name,
                           const std::vector<std::string> &arguments, const std::string &png,
                           const std::string &python = "", const std::string &script = "");

/// One line on stderr for a plot that was not made: "<program>: <note>; to make it: <command>"
/// (a missing matplotlib is said, never skipped silently).
void report_skipped_plot(const std::string &program, const PlotResult &plot);

} // namespace sealfe
