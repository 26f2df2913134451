#include <sealfe/coefficients/coefficient_solver.h>
#include <sealfe/coefficients/table_resume.h>
#include <sealfe/coefficients/table_sweep.h>
#include <sealfe/io/csv.h>
#include <sealfe/io/interrupt.h>
#include <sealfe/io/output.h>
#include <sealfe/io/python_plot.h>
#include <sealfe/numerics/gather.h>
#include <sealfe/numerics/number_lists.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace sealfe
{
using namespace dealii;

SweepPlan SweepPlan::make(const OperatingPoint &base, const std::vector<Axis> &axes_in,
                          const unsigned int n_check)
{
  SweepPlan plan;
  for (const Axis &a : axes_in)
    if (!a.values.empty())
      plan.axes.push_back(a);
  // Grid: nested loops, last axis fastest.
  std::vector<unsigned int> counter(plan.axes.size(), 0);
  while (true)
  {
    OperatingPoint p = base;
    for (unsigned int a = 0; a < plan.axes.size(); ++a)
      p.set(plan.axes[a].name, plan.axes[a].values[counter[a]]);
    plan.points.push_back(p);
    int a = static_cast<int>(plan.axes.size()) - 1;
    for (; a >= 0; --a)
      if (++counter[a] < plan.axes[a].values.size())
        break;
      else
        counter[a] = 0;
    if (a < 0)
      break;
  }
  plan.n_grid = plan.points.size();
  // Held-out points: the centre of a grid cell, cells spread along the diagonal of the grid.
  bool any_cell = false;
  for (const Axis &a : plan.axes)
    any_cell = any_cell || a.values.size() > 1;
  if (any_cell)
    for (unsigned int k = 0; k < n_check; ++k)
    {
      OperatingPoint p = base;
      for (const Axis &a : plan.axes)
      {
        const unsigned int n = a.values.size();
        if (n == 1)
        {
          p.set(a.name, a.values[0]);
          continue;
        }
        const unsigned int cell =
            std::min<unsigned int>(n - 2, std::floor((k + 0.5) * (n - 1) / n_check));
        p.set(a.name, 0.5 * (a.values[cell] + a.values[cell + 1]));
      }
      plan.points.push_back(p);
    }
  return plan;
}

namespace table
{
namespace
{
/// prm entry name (FilmSettings::set) and OperatingPoint column of every quantity a table can be
/// swept over.
const std::vector<std::pair<std::string, std::string>> &sweepable()
{
  static const std::vector<std::pair<std::string, std::string>> s = {
      {"Rotor speed", "rotor_speed"},
      {"Stator speed", "stator_speed"},
      {"Clearance", "clearance"},
      {"Coning", "coning"},
      {"Tilt", "tilt"},
      {"Pressure difference", "pressure_difference"},
      {"Viscosity", "viscosity"}};
  return s;
}

/// Shortest text that reads back to the same double (so that every rank count writes the same
/// file and the reader sees the exact values).
std::string number(const double v)
{
  return csv::number(v);
}

std::string describe(const OperatingPoint &p, const SweepPlan &plan)
{
  std::ostringstream s;
  s.precision(6);
  for (unsigned int a = 0; a < plan.axes.size(); ++a)
    s << (a ? ", " : "") << plan.axes[a].name << " = " << p.get(plan.axes[a].name);
  return s.str();
}

/// The start of point i's CSV row: index, role and operating point, with a trailing comma.
std::string row_prefix(const unsigned int i, const SweepPlan &plan)
{
  std::string line = std::to_string(i) + (plan.is_check(i) ? ",check" : ",grid");
  for (const auto &[name, unit] : OperatingPoint::columns())
    line += "," + number(plan.points[i].get(name));
  return line + ",";
}

/// One CSV row (no newline) of point i: its result, or NaNs and the failure.
std::string row(const unsigned int i, const SweepPlan &plan, const CoefficientResult *result,
                const bool with_errors, const std::string &failure)
{
  std::string line = row_prefix(i, plan);
  line.pop_back();
  const auto columns = coefficient_table_format::output_columns(with_errors);
  if (!result)
  {
    for (unsigned int c = 0; c < columns.size(); ++c)
      line += ",nan";
    return line + ",failed: " + coefficient_table_format::sanitize(failure);
  }
  // A point whose result is not finite is a failed point, not a row of NaNs marked ok.
  auto finite = [](const double v)
  {
    if (!std::isfinite(v))
      throw std::runtime_error("the result is not a finite number (an input is beyond what the "
                               "model can represent in double precision)");
    return number(v);
  };
  const FilmLoads &l = result->loads;
  for (const double v : {l.force_z, l.moment_x, l.moment_y, l.moment_restoring, l.moment_transverse,
                         l.leakage_inner, l.leakage_outer, l.friction_torque, l.min_film,
                         l.max_pressure, l.min_pressure, l.cavitated_fraction})
    line += "," + finite(v);
  for (const auto *m : {&result->coefficients.stiffness, &result->coefficients.damping})
    for (const auto &r : *m)
      for (const double v : r)
        line += "," + finite(v);
  if (with_errors)
    for (const auto *m : {&result->stiffness_error, &result->damping_error})
      for (const auto &r : *m)
        for (const double v : r)
          line += "," + number(result->has_error_estimate ? v : std::nan(""));
  return line + "," + std::to_string(result->dofs) + ",ok";
}

/// Every rank's text, concatenated in rank order (numerics::gather_on_every_rank: the text is a
/// few rows per rank, so every rank may as well receive it).
std::string gather_text(const std::string &mine, MPI_Comm comm)
{
  const std::vector<char> all =
      numerics::gather_on_every_rank(comm, std::vector<char>(mine.begin(), mine.end()));
  return std::string(all.begin(), all.end());
}
} // namespace

void declare_parameters(ParameterHandler &prm)
{
  CoefficientSolver::declare_parameters(prm);
  prm.enter_subsection("Table");
  struct Entry
  {
    std::string name, value, unit;
  };
  const std::vector<Entry> entries = {
      {"Rotor speed", "0 : 4000 : 5", "rad/s"},
      {"Stator speed", "", "rad/s"},
      {"Clearance", "0.8e-6, 1e-6, 1.25e-6, 1.6e-6", "m"},
      {"Coning", "", "rad"},
      {"Tilt", "", "rad, at the Geometry's Tilt angle"},
      {"Pressure difference", "", "Pa, po - pi with pi of the Operating conditions"},
      {"Viscosity", "", "Pa s"}};
  for (const auto &[name, value, unit] : entries)
    prm.declare_entry(name, value, Patterns::Anything(),
                      "Values of " + name + " (" + unit +
                          "): a list 'a, b, c' or a range 'start : stop : count' (both ends "
                          "included). Empty: not swept, the Geometry / Operating conditions "
                          "value is used.");
  prm.declare_entry("Output file", "coefficients.csv", Patterns::Anything(),
                    "CSV file (in the Output directory) of the table: one header line naming "
                    "every column with its unit, one row per operating point.");
  prm.declare_entry("Held-out points", "2", Patterns::Integer(0, 1000),
                    "Extra points at the centres of grid cells (role 'check' in the CSV), not "
                    "used by the interpolation: the interpolation error of the table is "
                    "reported against them in summary.json.");
  prm.declare_entry("Interpolation", "cubic", Patterns::Selection("cubic|linear"),
                    "Interpolation used for the held-out error report (the reader offers both): "
                    "cubic Lagrange on 4 nodes per axis (O(h^4)) or multilinear (O(h^2)).");
  prm.declare_entry("Resume", "false", Patterns::Bool(),
                    "Take over the finished rows of the previous table in the Output directory "
                    "(e.g. one stopped by Ctrl-C, summary.json: complete = false) and compute only "
                    "the other points. Refused, naming the entry, if any parameter differs from "
                    "the previous run's (summary.json: parameters). Without a previous run, every "
                    "point is computed.");
  prm.declare_entry("Plot", "true", Patterns::Bool(),
                    "When the table sweeps Rotor speed: draw the stiffness, damping, force and "
                    "leakage against it beside the CSV (<Output file stem>.png, "
                    "scripts/plot_table.py), if python3 with matplotlib is found (else one line "
                    "on stderr).");
  prm.leave_subsection();
}

nlohmann::json run(ParameterHandler &prm, const std::string &directory, MPI_Comm comm)
{
  const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
  // From here to the end of the sweep a signal only asks to stop (checked before each round of
  // points): one during the set-up ends the run before any point, publishing nothing.
  auto stop_on_signal = std::make_unique<interrupt::StopOnSignal>();

  FilmSettings base;
  base.parse_parameters(prm);
  CoefficientSettings coefficient_settings;
  coefficient_settings.parse_parameters(prm);
  std::vector<SweepPlan::Axis> axes;
  prm.enter_subsection("Table");
  for (const auto &[entry, column] : sweepable())
    axes.push_back({column, numerics::parse_number_list(prm.get(entry), "Table: '" + entry + "'")});
  const std::string file = prm.get("Output file");
  const unsigned int n_check = prm.get_integer("Held-out points");
  const bool resume = prm.get_bool("Resume");
  const bool want_plot = prm.get_bool("Plot");
  const auto interpolation = prm.get("Interpolation") == "linear"
                                 ? CoefficientTable::Interpolation::linear
                                 : CoefficientTable::Interpolation::cubic;
  prm.leave_subsection();
  if (file.empty() || file.find('/') != std::string::npos)
    throw std::runtime_error("Table: 'Output file' must be a file name inside the Output "
                             "directory (got '" +
                             file + "')");

  const SweepPlan plan =
      SweepPlan::make(OperatingPoint::of(base.geometry, base.conditions), axes, n_check);
  const unsigned int n_points = plan.points.size();
  const bool with_errors = base.estimate_error;
  const std::string header = coefficient_table_format::header(with_errors);
  const nlohmann::json parameters = recorded_parameters(prm);

  // Resume: rank 0 takes over the finished rows of the previous run (refused in one line if its
  // parameters differ); every rank learns which points are left.
  PreviousTable previous;
  std::string refusal;
  std::vector<unsigned int> finished;
  if (resume && rank == 0)
  {
    try
    {
      std::vector<std::string> prefixes;
      for (unsigned int i = 0; i < n_points; ++i)
        prefixes.push_back(row_prefix(i, plan));
      previous =
          read_previous(output::published_name(directory), file, parameters, header, prefixes);
    }
    catch (std::exception &e)
    {
      refusal = e.what();
    }
    for (const auto &[i, line] : previous.rows)
      finished.push_back(i);
  }
  refusal = Utilities::MPI::broadcast(comm, refusal, 0);
  if (!refusal.empty())
    throw std::runtime_error(refusal);
  finished = Utilities::MPI::broadcast(comm, finished, 0);
  std::vector<unsigned int> todo;
  {
    std::vector<bool> done(n_points, false);
    for (const unsigned int i : finished)
      done[i] = true;
    for (unsigned int i = 0; i < n_points; ++i)
      if (!done[i])
        todo.push_back(i);
  }

  // Every rank solves its own points on its own: one solver per rank (its mesh is reused while
  // the swept quantities leave the discretisation unchanged).
  CoefficientSolver solver(base, coefficient_settings, MPI_COMM_SELF);
  if (rank == 0)
  {
    std::cerr << "sealfe table: " << plan.n_grid << " grid points + " << n_points - plan.n_grid
              << " held-out points on " << n_ranks << " rank(s)" << std::endl;
    if (resume)
      std::cerr << "sealfe table: Resume: "
                << (previous.found
                        ? std::to_string(finished.size()) + " of " + std::to_string(n_points) +
                              " points taken over from the previous run"
                        : "no previous run in " + output::published_name(directory) +
                              ", every point is computed")
                << std::endl;
  }

  // Round-robin over the points left (they cost about the same), one point per rank and round.
  // Before each round the ranks agree (MPI max) whether a signal asked to stop, so that all stop
  // after the same round with whole rows.
  std::string my_rows;
  double my_time = 0;
  unsigned int my_points = 0;
  bool stopped = false;
  {
    for (std::size_t first = 0; first < todo.size(); first += n_ranks)
    {
      if (interrupt::requested(comm))
      {
        stopped = true;
        break;
      }
      if (first + rank >= todo.size())
        continue;
      const unsigned int i = todo[first + rank];
      const auto start = std::chrono::steady_clock::now();
      // The point's film problem: the swept quantities set by their prm names.
      FilmSettings point = base;
      for (const auto &[entry, column] : sweepable())
        point.set(entry, plan.points[i].get(column));
      std::string line, failure;
      try
      {
        const CoefficientResult r = solver.compute(point.geometry, point.conditions);
        line = row(i, plan, &r, with_errors, "");
      }
      catch (std::exception &e)
      {
        failure = e.what();
      }
      catch (...)
      {
        failure = "unknown error";
      }
      if (line.empty())
        line = row(i, plan, nullptr, with_errors, failure.empty() ? "unknown error" : failure);
      my_rows += line + "\n";
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      my_time += seconds;
      ++my_points;
      // time left: this rank's mean time per point times the rounds still to come
      const std::size_t rounds_left =
          (todo.size() - std::min(todo.size(), first + n_ranks) + n_ranks - 1) / n_ranks;
      const double left = my_time / my_points * rounds_left;
      std::ostringstream progress;
      progress.precision(3);
      progress << "sealfe table: point " << i + 1 << "/" << plan.points.size()
               << (plan.is_check(i) ? " (held-out)" : "") << " [rank " << rank << "] "
               << describe(plan.points[i], plan) << ": "
               << (failure.empty() ? "ok"
                                   : "FAILED: " + coefficient_table_format::sanitize(failure))
               << " (" << seconds << " s";
      if (rounds_left > 0)
        progress << ", ~" << std::setprecision(2) << left << " s left";
      progress << ")\n";
      std::cerr << progress.str() << std::flush;
    }
  }
  stop_on_signal.reset();
  const std::string stop_reason = stopped ? interrupt::reason() : std::string();

  const std::string all_rows = gather_text(my_rows, comm);
  const double total_time = Utilities::MPI::sum(my_time, comm);
  const double max_rank_time = Utilities::MPI::max(my_time, comm);
  nlohmann::json summary;
  bool complete = false;
  if (rank == 0)
  {
    // Rows in point order, whatever rank (or the previous run) computed them.
    std::vector<std::pair<unsigned int, std::string>> lines(previous.rows.begin(),
                                                            previous.rows.end());
    std::istringstream in(all_rows);
    std::string line;
    while (std::getline(in, line))
      lines.emplace_back(std::stoul(line.substr(0, line.find(','))), line);
    std::sort(lines.begin(), lines.end());
    const unsigned int computed = lines.size() - previous.rows.size();
    complete = lines.size() == n_points;
    std::string csv = header + "\n";
    nlohmann::json failures = nlohmann::json::array();
    unsigned int grid_ok = 0;
    for (const auto &[i, l] : lines)
    {
      csv += l + "\n";
      const auto status = l.find(",failed: ");
      if (status != std::string::npos)
        failures.push_back({{"index", i},
                            {"role", plan.is_check(i) ? "check" : "grid"},
                            {"message", l.substr(status + 9)}});
      else if (!plan.is_check(i))
        ++grid_ok;
    }
    // Nothing is published then: a previous good table stays.
    if (stopped && computed == 0)
      refusal = "Table: " + stop_reason +
                " before any point finished; nothing was written (the output directory is as it "
                "was)";
    else if (grid_ok == 0 && !failures.empty())
      refusal = std::string("Table: every ") + (complete ? "" : "finished ") +
                "grid point failed, nothing was written (the first: " +
                failures.front()["message"].get<std::string>() + ")";
    else if (grid_ok == 0)
      refusal = "Table: " + stop_reason + " before any grid point finished; nothing was written";
    if (refusal.empty())
    {
      output::make_directory(directory);
      output::write_file_atomically(directory, file, csv);

      summary["table"] = file;
      summary["complete"] = complete;
      summary["points_done"] = lines.size();
      summary["points_total"] = n_points;
      summary["resumed_points"] = previous.rows.size();
      if (!complete)
        summary["stop_reason"] = stop_reason;
      summary["grid_points"] = plan.n_grid;
      summary["held_out_points"] = n_points - plan.n_grid;
      summary["failed_points"] = failures.size();
      summary["failures"] = failures;
      nlohmann::json ax = nlohmann::json::object();
      for (const auto &a : plan.axes)
        ax[a.name] = a.values;
      summary["axes"] = ax;
      nlohmann::json columns = nlohmann::json::array();
      std::istringstream header_columns(header);
      for (std::string c; std::getline(header_columns, c, ',');)
        columns.push_back(c);
      summary["columns"] = columns;
      // s, one point on one rank (those computed by this run)
      summary["time_per_point"] = computed ? total_time / computed : 0.0;
      summary["sweep_wall_time"] = max_rank_time;
      // what a resumed run compares (table_resume.h)
      summary["parameters"] = parameters;

      // Read the file back (the reader the dynamics module uses) and report the interpolation
      // error at the held-out points; an incomplete table has holes, and no such report.
      if (complete)
      {
        const CoefficientTable table(directory + "/" + file, interpolation);
        nlohmann::json held = nlohmann::json::array();
        double worst_k = 0, worst_d = 0;
        for (const auto &e : table.held_out_errors())
        {
          nlohmann::json point = nlohmann::json::object();
          for (const auto &a : plan.axes)
            point[a.name] = e.point.get(a.name);
          held.push_back({{"point", point},
                          {"stiffness", e.stiffness},
                          {"damping", e.damping},
                          {"columns", e.columns}});
          worst_k = std::max(worst_k, e.stiffness);
          worst_d = std::max(worst_d, e.damping);
        }
        summary["interpolation"] =
            interpolation == CoefficientTable::Interpolation::linear ? "linear" : "cubic";
        summary["held_out_error"] = held;
        // no held-out point, no claim: null, not a perfect 0
        const nlohmann::json none = nullptr;
        summary["max_held_out_error"] = {
            {"stiffness", held.empty() ? none : nlohmann::json(worst_k)},
            {"damping", held.empty() ? none : nlohmann::json(worst_d)},
            {"definition", "max_ij |K~ - K| / max_ij |K| of diag(1, 1/ro, 1/ro) K diag(1, 1/ro, "
                           "1/ro); the same for D"}};
      }
      // coefficients against speed: only a table that sweeps the rotor speed has a curve to draw
      const auto speed_axis =
          std::find_if(plan.axes.begin(), plan.axes.end(),
                       [](const SweepPlan::Axis &a) { return a.name == "rotor_speed"; });
      summary["plot"] = nullptr;
      if (want_plot && speed_axis != plan.axes.end() && speed_axis->values.size() > 1)
      {
        const std::string png = file.substr(0, file.rfind('.')) + ".png";
        const PlotResult plot =
            run_plot_script("plot_table.py", {directory + "/" + file, directory + "/" + png},
                            directory + "/" + png);
        if (plot.made)
          summary["plot"] = png;
        else
        {
          summary["plot_note"] = plot.note;
          report_skipped_plot("sealfe table", plot);
        }
      }
      std::cerr << "sealfe table: wrote " << output::published_name(directory + "/" + file) << " ("
                << lines.size() << " of " << n_points << " rows, " << failures.size() << " failed, "
                << previous.rows.size() << " taken over from the previous run)" << std::endl;
    }
  }
  refusal = Utilities::MPI::broadcast(comm, refusal, 0);
  if (!refusal.empty())
    throw std::runtime_error(refusal);
  if (stopped)
    // published with complete = false by the driver, then reported (exit 1)
    throw output::IncompleteRun(
        "Table: " + stop_reason + " after " +
            std::to_string(summary.is_object() ? summary.value("points_done", 0u) : 0u) + " of " +
            std::to_string(n_points) + " points; the finished rows are in " + directory + "/" +
            file +
            ", summary.json says complete = false (set Resume = true in subsection "
            "Table to compute the rest)",
        summary);
  return summary;
}
} // namespace table

} // namespace sealfe
