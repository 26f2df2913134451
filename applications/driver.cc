#include "driver.h"
#include "version.h"

#include <sealfe/film/film_thickness.h>
#include <sealfe/film/operating_conditions.h>
#include <sealfe/io/output.h>
#include <sealfe/numerics/blas_kernels.h>

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace sealfe::applications
{
using namespace dealii;

std::string one_line(const std::exception &e)
{
  std::string text;
  if (const auto *d = dynamic_cast<const ExceptionBase *>(&e))
  {
    std::ostringstream s;
    d->print_info(s);
    text = s.str();
  }
  else
    text = e.what();
  std::string line;
  bool space = false;
  for (const char c : text)
  {
    if (std::isspace(static_cast<unsigned char>(c)))
      space = !line.empty();
    else
    {
      if (space)
        line += ' ';
      line += c;
      space = false;
    }
  }
  return line;
}

namespace
{
void declare_common(ParameterHandler &prm, const SubCommand &command)
{
  // One directory per sub-command, so that one run never replaces another's summary.json.
  prm.declare_entry("Output directory", "sealfe-output/" + command.name, Patterns::Anything(),
                    "Directory for summary.json, used_parameters.prm and the field/table files "
                    "(created if needed). Default: sealfe-output/<sub-command>.");
  if (command.face_seal)
  {
    FilmThickness::declare_parameters(prm);
    OperatingConditions::declare_parameters(prm);
  }
  command.declare(prm);
}

/// deal.II mangles entry names in its JSON output (non-alphanumerics as _XX hex).
std::string demangle(const std::string &s)
{
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s[i] == '_' && i + 2 < s.size() + 0 && std::isxdigit(s[i + 1]) && std::isxdigit(s[i + 2]))
    {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    }
    else
      out += s[i];
  return out;
}

/// `--print-parameters`: every entry in prm syntax with its default value, pattern and
/// documentation (deal.II's own styles print either the defaults or the patterns, not both).
void print_parameters(const ParameterHandler &prm, std::ostream &out)
{
  std::ostringstream json_text;
  prm.print_parameters(json_text, ParameterHandler::JSON);
  const auto json = nlohmann::json::parse(json_text.str());
  std::function<void(const nlohmann::json &, const std::string &)> print =
      [&](const nlohmann::json &node, const std::string &indent)
  {
    // entries first, then subsections; aliases (old entry names) are not printed
    for (const auto &[key, value] : node.items())
      if (value.contains("value"))
      {
        out << indent << "# " << value.value("documentation", std::string()) << "\n"
            << indent << "#   default: " << value.value("default_value", std::string())
            << "   pattern: " << value.value("pattern_description", std::string()) << "\n"
            << indent << "set " << demangle(key) << " = "
            << value.value("default_value", std::string()) << "\n\n";
      }
    for (const auto &[key, value] : node.items())
      if (!value.contains("value") && !value.contains("alias"))
      {
        out << indent << "subsection " << demangle(key) << "\n";
        print(value, indent + "  ");
        out << indent << "end\n\n";
      }
  };
  print(json, "");
}

/// Sends std::cout to a buffer while it exists.
class CoutRedirect
{
public:
  explicit CoutRedirect(std::ostringstream &buffer) : console(std::cout.rdbuf(buffer.rdbuf())) {}
  ~CoutRedirect() { std::cout.rdbuf(console); }
  CoutRedirect(const CoutRedirect &) = delete;
  CoutRedirect &operator=(const CoutRedirect &) = delete;

private:
  std::streambuf *console;
};

/// Nothing non-finite is published: the summary (nlohmann::json writes nan as null) and the data
/// rows of every staged CSV file.
void check_results(const nlohmann::json &summary, const std::string &staging)
{
  output::check_finite(summary);
  std::vector<std::string> tables;
  for (const auto &entry : std::filesystem::directory_iterator(staging))
    if (entry.path().extension() == ".csv")
      tables.push_back(entry.path().string());
  std::sort(tables.begin(), tables.end());
  for (const std::string &table : tables)
    output::check_finite_csv(table);
}

/// File names in the summary name the published files, not the staged ones.
void publish_paths(nlohmann::json &node)
{
  if (node.is_string())
    node = output::published_name(node.get<std::string>());
  else if (node.is_structured())
    for (auto &value : node)
      publish_paths(value);
}

/// --timings: the stages a sub-command reports in summary.json (stage_wall_time, e.g. the film
/// solver's setup, assembly, linear solve, loads, error estimate), one per line.
void print_stage_times(const nlohmann::json &stages, const std::string &prefix = "")
{
  for (const auto &[name, value] : stages.items())
    if (value.is_object())
      print_stage_times(value, prefix + name + "/");
    else if (value.is_number())
      std::cout << "  " << std::left << std::setw(40) << prefix + name << std::right
                << std::setw(12) << std::setprecision(4) << value.get<double>() << " s\n";
}

void print_usage(std::ostream &out, const std::vector<SubCommand> &commands)
{
  out << "usage: sealfe [--timings] <sub-command> [file.prm]\n"
         "       sealfe --print-parameters [sub-command]\n"
         "       sealfe --version\n\nsub-commands:\n";
  for (const auto &c : commands)
    out << "  " << std::left << std::setw(14) << c.name << c.purpose << "\n";
}
} // namespace

int run_command_line(int argc, char **argv, const std::vector<SubCommand> &commands)
{
  const MPI_Comm comm = MPI_COMM_WORLD;
  const bool root = Utilities::MPI::this_mpi_process(comm) == 0;
  std::vector<std::string> args(argv + 1, argv + argc);
  // --timings may stand anywhere: deal.II's TimerOutput summary of the run's stages after the
  // headline
  const auto timings_flag = std::find(args.begin(), args.end(), "--timings");
  const bool print_timings = timings_flag != args.end();
  if (print_timings)
    args.erase(timings_flag);
  ConditionalOStream timer_stream(std::cout, root);
  TimerOutput timer(timer_stream, TimerOutput::never, TimerOutput::wall_times);
  try
  {
    if (args.empty() || args[0] == "--help" || args[0] == "-h")
    {
      if (root)
        print_usage(args.empty() ? std::cerr : std::cout, commands);
      return args.empty() ? 2 : 0;
    }
    if (args[0] == "--version")
    {
      if (root)
        std::cout << "sealfe " << version << " (git " << git_revision << ")\n";
      return 0;
    }
    auto find = [&](const std::string &name) -> const SubCommand &
    {
      for (const auto &c : commands)
        if (c.name == name)
          return c;
      throw std::runtime_error("unknown sub-command '" + name + "' (see sealfe --help)");
    };

    if (args[0] == "--print-parameters")
    {
      const SubCommand &command = find(args.size() > 1 ? args[1] : "solve");
      ParameterHandler prm;
      declare_common(prm, command);
      if (root)
        print_parameters(prm, std::cout);
      return 0;
    }

    const SubCommand &command = find(args[0]);
    if (args.size() > 2)
      throw std::runtime_error("too many arguments (usage: sealfe " + command.name +
                               " [file.prm])");
    const auto start = std::chrono::steady_clock::now();
    timer.enter_subsection("read parameters");
    ParameterHandler prm;
    declare_common(prm, command);
    if (args.size() == 2)
    {
      const std::string &file = args[1];
      if (std::filesystem::is_directory(file))
        throw std::runtime_error("parameter file '" + file + "' is a directory");
      std::ifstream probe(file);
      if (!probe)
        throw std::runtime_error("parameter file '" + file + "' is missing or unreadable");
      try
      {
        prm.parse_input(file, "", /*skip_undefined=*/false, /*assert_mandatory=*/false);
      }
      catch (std::exception &e)
      {
        // deal.II writes "Line <2> of file <case.prm: ..." for a subsection: close the bracket
        std::string message = one_line(e);
        const std::string open = "of file <" + file + ":";
        if (const auto at = message.find(open); at != std::string::npos)
          message.replace(at, open.size(), "of file <" + file + ">:");
        throw std::runtime_error("parameter file '" + file + "': " + message);
      }
    }
    const std::string directory = prm.get("Output directory");
    timer.leave_subsection();

    // The run writes into a staging directory inside the output directory, made before any work
    // (so an unwritable directory is refused at once) on rank 0; every rank of a distributed
    // command learns the outcome, so that no rank waits for one that gave up.
    std::unique_ptr<output::StagedOutput> staged;
    std::string staging, staging_error;
    if (root)
      try
      {
        staged = std::make_unique<output::StagedOutput>(directory, std::to_string(::getpid()));
        staging = staged->path();
      }
      catch (std::exception &e)
      {
        staging_error = one_line(e);
      }
    if (command.distributed)
    {
      staging = Utilities::MPI::broadcast(comm, staging, 0);
      staging_error = Utilities::MPI::broadcast(comm, staging_error, 0);
    }
    if (!staging_error.empty())
      throw std::runtime_error(staging_error);

    // The headline is held back until the results are checked: a failed run prints only its
    // error line.
    std::ostringstream headline;
    nlohmann::json summary;
    std::string incomplete;
    {
      const CoutRedirect redirect(headline);
      try
      {
        const TimerOutput::Scope scope(timer, "run " + command.name);
        if (command.distributed || root)
          summary = command.run(prm, staging, comm);
      }
      catch (output::IncompleteRun &e)
      {
        // published like a complete run (its summary says complete = false), then reported
        incomplete = output::published_name(e.what());
        summary = std::move(e.summary);
        summary["complete"] = false;
      }
    }
    timer.enter_subsection("write summary");
    if (root)
    {
      summary["sub_command"] = command.name;
      summary["version"] = version;
      summary["git_revision"] = git_revision;
      summary["mpi_ranks"] = Utilities::MPI::n_mpi_processes(comm);
      const numerics::BlasKernels blas = numerics::blas_kernels();
      summary["blas_kernels"] = {
          {"kernels", blas.kernels}, {"chosen_by", blas.chosen_by}, {"threads", blas.threads}};
      summary["wall_time"] =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      check_results(summary, staging);
      publish_paths(summary);
      output::write_used_parameters(staging, prm);
      output::write_summary(staging, summary);
      staged->publish();
    }
    timer.leave_subsection();
    if (root)
    {
      if (!incomplete.empty())
        throw std::runtime_error(incomplete);
      std::cout << output::published_name(headline.str());
      std::cout << "sealfe " << command.name << ": wrote " << directory << "/summary.json and "
                << directory << "/used_parameters.prm\n";
    }
    if (print_timings)
    {
      timer.print_summary();
      if (root && summary.contains("stage_wall_time"))
      {
        std::cout << "stages of run " << command.name << " (summary.json stage_wall_time):\n";
        print_stage_times(summary["stage_wall_time"]);
      }
    }
    return 0;
  }
  catch (std::exception &e)
  {
    if (root)
      std::cerr << "sealfe: error: " << one_line(e) << std::endl;
    return 1;
  }
}

} // namespace sealfe::applications
