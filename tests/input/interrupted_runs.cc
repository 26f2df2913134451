// Interrupted and resumed runs (issue 14, item 7): SIGINT/SIGTERM part-way through a table keeps
// the finished rows in a table whose summary.json says complete = false (exit 1); `Resume = true`
// computes only the rest and ends with the same table as an uninterrupted run; a resume with a
// changed parameter, and a table whose every point fails, are refused and change nothing; a
// second SIGINT ends the run at once (130); an interrupted transient keeps its rows; a signal
// that arrives while a run publishes its files waits for the last rename, whichever thread the
// kernel gives it to.
#include "../sealfe_cli.h"

#include <sealfe/io/interrupt.h>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <pthread.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace
{
using sealfe::testing::CliResult;
using sealfe::testing::read_file;

// The coarse mesh of every table here (about 10 ms a point).
const std::string coarse_mesh = R"(subsection Discretization
  set Polynomial degree     = 1
  set Radial cells          = 4
  set Circumferential cells = 32
  set Error estimate        = false
end
)";

// A table of 2 x 120 + 1 points: long enough to be interrupted part-way, short enough to be
// computed whole in a test.
const std::string table_body = R"(subsection Table
  set Rotor speed     = 0 : 4000 : 120
  set Clearance       = 1e-6, 1.25e-6
  set Held-out points = 1
  set Interpolation   = linear
end
)" + coarse_mesh;
const std::string resume = "subsection Table\n  set Resume = true\nend\n";

nlohmann::json summary(const fs::path &dir)
{
  return nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
}

/// The data rows of a table (the header line apart).
std::vector<std::string> rows(const fs::path &csv)
{
  std::istringstream in(read_file(csv));
  std::vector<std::string> out;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line))
    out.push_back(line);
  return out;
}

/// Every numeric field of every row finite, status ok.
void expect_finite_rows(const std::vector<std::string> &lines)
{
  for (const std::string &line : lines)
  {
    std::vector<std::string> fields;
    std::istringstream row(line);
    for (std::string f; std::getline(row, f, ',');)
      fields.push_back(f);
    ASSERT_GT(fields.size(), 3u);
    EXPECT_EQ(fields.back(), "ok") << line;
    for (std::size_t i = 2; i + 1 < fields.size(); ++i)
      EXPECT_TRUE(std::isfinite(std::stod(fields[i]))) << line;
  }
}

std::map<std::string, std::string> snapshot(const fs::path &dir)
{
  std::map<std::string, std::string> files;
  for (const auto &e : fs::recursive_directory_iterator(dir))
    files[fs::relative(e.path(), dir).string()] =
        e.is_regular_file() ? read_file(e.path()) : std::string("<dir>");
  return files;
}

/// The last line of stderr is the one error line; it contains `needle`.
void expect_error_line(const CliResult &r, const std::string &needle)
{
  const std::string tag = "sealfe: error: ";
  const std::size_t at = r.err.find(tag);
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_EQ(at, r.err.rfind(tag)) << r.err;
  EXPECT_EQ(r.err.find('\n', at), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find(needle, at), std::string::npos) << r.err;
}

/// Starts the table in `dir` and sends `signal` once `points` progress lines are on stderr.
CliResult interrupted_table(const fs::path &dir, const std::string &body, const int signal,
                            const unsigned int points)
{
  const pid_t pid = sealfe::testing::start_sealfe(dir, "table", body);
  EXPECT_TRUE(sealfe::testing::wait_for_text(dir / "stderr", ": ok (", points, pid, 60))
      << read_file(dir / "stderr");
  kill(pid, signal);
  return sealfe::testing::wait_sealfe(dir, pid, 60);
}

TEST(InterruptedRuns, TableKeepsItsFinishedRowsMarkedIncomplete)
{
  const fs::path d = sealfe::testing::fresh_directory("sealfe_interrupted_table");
  const CliResult r = interrupted_table(d, table_body, SIGINT, 5);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.out, "");
  expect_error_line(r, "interrupted by SIGINT after ");
  ASSERT_TRUE(fs::exists(d / "out" / "summary.json")) << r.err;
  const auto s = summary(d);
  EXPECT_EQ(s["complete"], false);
  EXPECT_EQ(s["stop_reason"], "interrupted by SIGINT");
  EXPECT_EQ(s["points_total"], 241);
  EXPECT_EQ(s["resumed_points"], 0);
  const unsigned int done = s["points_done"];
  EXPECT_GE(done, 5u);
  EXPECT_LT(done, 241u);
  const auto lines = rows(d / "out" / "coefficients.csv");
  ASSERT_EQ(lines.size(), done);
  expect_finite_rows(lines);
  // serial: the finished points are the first ones, in order
  for (unsigned int i = 0; i < done; ++i)
    EXPECT_EQ(lines[i].substr(0, lines[i].find(',')), std::to_string(i));
  // the CSV is a plain table (no marker line): the mark is in summary.json
  EXPECT_EQ(read_file(d / "out" / "coefficients.csv").find('#'), std::string::npos);
  for (const auto &e : fs::directory_iterator(d / "out"))
    EXPECT_NE(e.path().filename().string().rfind(".sealfe-partial-", 0), 0u) << e.path();
}

TEST(InterruptedRuns, ResumeEndsWithTheTableOfAnUninterruptedRun)
{
  const fs::path d = sealfe::testing::fresh_directory("sealfe_interrupted_resume");
  const CliResult r = interrupted_table(d, table_body, SIGINT, 20);
  ASSERT_EQ(r.status, 1) << r.err;
  const unsigned int done = summary(d)["points_done"];
  ASSERT_LT(done, 241u);

  const CliResult resumed = sealfe::testing::run_sealfe(d, "table", table_body + resume);
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_NE(resumed.err.find(std::to_string(done) + " of 241 points taken over"), std::string::npos)
      << resumed.err;
  const auto s = summary(d);
  EXPECT_EQ(s["complete"], true);
  EXPECT_EQ(s["points_done"], 241);
  EXPECT_EQ(s["resumed_points"], done);
  EXPECT_FALSE(s.contains("stop_reason"));
  EXPECT_TRUE(s.contains("max_held_out_error"));

  const fs::path whole = sealfe::testing::fresh_directory("sealfe_interrupted_whole");
  const CliResult w = sealfe::testing::run_sealfe(whole, "table", table_body);
  ASSERT_EQ(w.status, 0) << w.err;
  // the same points computed by the same code: the same text, digit for digit
  EXPECT_EQ(read_file(d / "out" / "coefficients.csv"),
            read_file(whole / "out" / "coefficients.csv"));
  EXPECT_EQ(s["max_held_out_error"], summary(whole)["max_held_out_error"]);
}

TEST(InterruptedRuns, ResumeWithAChangedParameterIsRefused)
{
  const fs::path d = sealfe::testing::fresh_directory("sealfe_interrupted_changed");
  const std::string small = R"(subsection Table
  set Rotor speed     = 0, 1000
  set Clearance       = 1e-6, 1.25e-6
  set Held-out points = 0
  set Interpolation   = linear
end
)" + coarse_mesh;
  ASSERT_EQ(sealfe::testing::run_sealfe(d, "table", small).status, 0);
  const auto before = snapshot(d / "out");
  const CliResult r = sealfe::testing::run_sealfe(
      d, "table",
      small + resume + "subsection Operating conditions\n  set Viscosity = 2e-3\nend\n");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.out, "");
  // one line: nothing was computed, no progress
  EXPECT_EQ(r.err.find("sealfe: error: "), 0u) << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find("'Operating conditions/Viscosity'"), std::string::npos) << r.err;
  EXPECT_TRUE(snapshot(d / "out") == before) << "the output directory changed";

  // the same values written otherwise (0.000001 = 1e-6) are the same parameters: nothing left
  std::string same = small;
  same.replace(same.find("1e-6, 1.25e-6"), 13, "0.000001,1.25e-6");
  const CliResult again = sealfe::testing::run_sealfe(d, "table", same + resume);
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(summary(d)["resumed_points"], 4);
  EXPECT_EQ(read_file(d / "out" / "coefficients.csv"), before.at("coefficients.csv"));
}

TEST(InterruptedRuns, AllFailingTableLeavesThePreviousTable)
{
  const fs::path d = sealfe::testing::fresh_directory("sealfe_interrupted_all_fail");
  const std::string small = "subsection Table\n  set Rotor speed = 0, 1000\n  set Clearance = "
                            "1e-6\n  set Held-out points = 0\n  set Interpolation = linear\nend\n"
                            "subsection Discretization\n  set Polynomial degree = 1\n  set Radial "
                            "cells = 4\n  set Circumferential cells = 32\nend\n";
  ASSERT_EQ(sealfe::testing::run_sealfe(d, "table", small).status, 0);
  const auto before = snapshot(d / "out");
  // mu = 1e308: the film equation overflows at every point
  const CliResult r = sealfe::testing::run_sealfe(
      d, "table", small + "subsection Table\n  set Viscosity = 1e308, 1.5e308\nend\n");
  EXPECT_EQ(r.status, 1);
  expect_error_line(r, "every grid point failed");
  EXPECT_TRUE(snapshot(d / "out") == before) << "the output directory changed";
}

TEST(InterruptedRuns, SecondSigintEndsTheRunAtOnce)
{
  const fs::path d = sealfe::testing::fresh_directory("sealfe_interrupted_twice");
  // a finer mesh: a point (about 0.2 s) takes long enough for both signals to arrive within it
  std::string body = table_body;
  body.replace(body.find("set Circumferential cells = 32"), 30, "set Circumferential cells = 2048");
  const pid_t pid = sealfe::testing::start_sealfe(d, "table", body);
  ASSERT_TRUE(sealfe::testing::wait_for_text(d / "stderr", ": ok (", 1, pid, 60));
  kill(pid, SIGINT);
  ASSERT_TRUE(sealfe::testing::wait_for_text(d / "stderr", "interrupt again", 1, pid, 10));
  kill(pid, SIGINT);
  const CliResult r = sealfe::testing::wait_sealfe(d, pid, 30);
  EXPECT_EQ(r.status, 130) << r.err;
  EXPECT_FALSE(fs::exists(d / "out" / "summary.json"));
  EXPECT_FALSE(fs::exists(d / "out" / "coefficients.csv"));
}

TEST(InterruptedRuns, TransientKeepsItsRowsMarkedIncomplete)
{
  const fs::path d = sealfe::testing::fresh_directory("sealfe_interrupted_transient");
  // the Green 2002 cycle, made 100 times longer than the test waits
  const pid_t pid = sealfe::testing::start_sealfe(
      d, "transient", "subsection Transient\n  set End time = 900\n  set Plot = false\nend\n");
  ASSERT_TRUE(sealfe::testing::wait_for_text(d / "stderr", "sealfe transient: t = ", 1, pid, 60))
      << read_file(d / "stderr");
  kill(pid, SIGTERM);
  const CliResult r = sealfe::testing::wait_sealfe(d, pid, 60);
  EXPECT_EQ(r.status, 1) << r.err;
  expect_error_line(r, "interrupted by SIGTERM at t = ");
  ASSERT_TRUE(fs::exists(d / "out" / "summary.json"));
  const auto s = summary(d);
  EXPECT_EQ(s["complete"], false);
  const double end = s["end_time"];
  EXPECT_GT(end, 0.0);
  EXPECT_LT(end, 900.0);
  // the rows up to where it stopped, the last one at the end time the summary reports
  const auto lines = rows(d / "out" / "transient.csv");
  ASSERT_GE(lines.size(), 2u);
  EXPECT_DOUBLE_EQ(std::stod(lines.back().substr(0, lines.back().find(','))), end);
  EXPECT_EQ(read_file(d / "out" / "transient.csv").find("nan"), std::string::npos);
}
} // namespace

TEST(InterruptedRuns, SignalWhilePublishingWaitsForTheEnd)
{
  // StagedOutput::publish holds SIGINT and SIGTERM (interrupt::HoldSignals) while it renames. The
  // kernel gives a signal sent to the process to a thread that does not block it: here another
  // thread, as deal.II's task threads (TBB) and MPI's are, while the holding thread blocks it.
  // Held, the process lives on until the hold ends and then takes the default action; a hold by
  // the holding thread's signal mask alone would end it at once, before "held" is written.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(
      {
        std::atomic<bool> done{false};
        std::thread other(
            [&done]()
            {
              while (!done)
                std::this_thread::sleep_for(std::chrono::milliseconds(1));
            });
        sigset_t term;
        sigemptyset(&term);
        sigaddset(&term, SIGTERM);
        pthread_sigmask(SIG_BLOCK, &term, nullptr); // this thread only: `other` takes it
        {
          const sealfe::interrupt::HoldSignals hold;
          kill(getpid(), SIGTERM);
          std::this_thread::sleep_for(std::chrono::milliseconds(200));
          std::cerr << "held" << std::endl;
        } // raised again here, pending on this thread until it unblocks
        pthread_sigmask(SIG_UNBLOCK, &term, nullptr);
        done = true;
        other.join();
        std::exit(0); // not reached: SIGTERM's default action ends the process
      },
      ::testing::KilledBySignal(SIGTERM), "held");
}
