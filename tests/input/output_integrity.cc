// Nothing silent, nothing lost (issue 14): a run whose results are not finite numbers is refused
// with one `sealfe: error:` line and a non-zero exit status, for every sub-command, and leaves the
// output directory exactly as it was (a previous good run stays whole); an output directory that
// cannot be written is refused before any work, on every MPI rank.
#include "../sealfe_cli.h"

#include <sealfe/io/output.h>
#include <sealfe/numerics/polynomial.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

namespace fs = std::filesystem;

namespace
{
using sealfe::testing::CliResult;
using sealfe::testing::read_file;
using sealfe::testing::run_sealfe;

/// prm/<name>.prm without its Output directory line (the test sets its own).
std::string example(const std::string &name)
{
  std::istringstream in(read_file(fs::path(SEALFE_SOURCE_DIR) / "prm" / (name + ".prm")));
  std::string body;
  for (std::string line; std::getline(in, line);)
    if (line.find("set Output directory") == std::string::npos)
      body += line + "\n";
  return body;
}

/// Every file under `dir` (hidden ones included) with its content.
std::map<std::string, std::string> snapshot(const fs::path &dir)
{
  std::map<std::string, std::string> files;
  if (fs::exists(dir))
    for (const auto &e : fs::recursive_directory_iterator(dir))
      files[fs::relative(e.path(), dir).string()] =
          e.is_regular_file() ? read_file(e.path()) : std::string("<dir>");
  return files;
}

/// One error line, the last on stderr (a table prints its progress lines before it).
void expect_one_error_line(const CliResult &r, const std::string &needle,
                           const bool progress = false)
{
  EXPECT_NE(r.status, 0);
  const std::string tag = "sealfe: error: ";
  const std::size_t at = r.err.find(tag);
  EXPECT_EQ(at, r.err.rfind(tag)) << r.err;
  if (progress)
    EXPECT_TRUE(at == 0 || (at != std::string::npos && r.err[at - 1] == '\n')) << r.err;
  else
    EXPECT_EQ(at, 0u) << r.err;
  EXPECT_EQ(r.err.find('\n', at), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find(needle, at), std::string::npos) << r.err;
}

/// A good run of `command` fills out/; the bad run is refused and changes nothing there.
void expect_refused_and_untouched(const std::string &name, const std::string &command,
                                  const std::string &good, const std::string &bad,
                                  const std::string &needle)
{
  SCOPED_TRACE(name);
  const fs::path d = sealfe::testing::fresh_directory("sealfe_output_integrity_" + name);
  const CliResult g = run_sealfe(d, command, good);
  ASSERT_EQ(g.status, 0) << g.err;
  ASSERT_TRUE(fs::exists(d / "out" / "summary.json"));
  const auto before = snapshot(d / "out");
  const CliResult r = run_sealfe(d, command, good + bad);
  expect_one_error_line(r, needle, command == "table");
  EXPECT_EQ(r.out, "") << "a refused run prints no results";
  EXPECT_TRUE(snapshot(d / "out") == before) << "the output directory changed";
}

const std::string small_mesh = "subsection Discretization\n  set Radial cells = 2\n"
                               "  set Circumferential cells = 16\nend\n";
} // namespace

TEST(OutputIntegrity, NonFiniteSolveIsRefused)
{
  // mu = 1e308: the shear and squeeze terms overflow; the loads were written as null
  expect_refused_and_untouched("solve", "solve", small_mesh,
                               "subsection Operating conditions\n  set Viscosity = 1e308\nend\n",
                               "Viscosity");
}

TEST(OutputIntegrity, NonFiniteCoefficientsAreRefused)
{
  expect_refused_and_untouched("coefficients", "coefficients", small_mesh,
                               "subsection Operating conditions\n  set Viscosity = 1e308\nend\n",
                               "Viscosity");
}

TEST(OutputIntegrity, NonFiniteStabilityIsRefused)
{
  // k_s = 1e308: every eigenvalue was null and the verdict "stable": false
  const std::string good = example("stability") + "subsection Stability\n  set Speed points = 41\n"
                                                  "  set Second parameter = none\nend\n";
  expect_refused_and_untouched("stability", "stability", good,
                               "subsection Seal dynamics\n  subsection Rotor ring\n"
                               "    set Support stiffness = 1e308\n  end\nend\n",
                               "Support stiffness");
}

TEST(OutputIntegrity, NonFiniteResponseIsRefused)
{
  // a polar inertia of 1e308 truncated response.csv to 0 bytes next to the old summary
  const std::string good = example("response") +
                           "subsection Forced response\n  set Speed points = 20\n"
                           "  set Plot = false\nend\n";
  expect_refused_and_untouched("response", "response", good,
                               "subsection Seal dynamics\n  subsection Rotor ring\n"
                               "    set Polar inertia = 1e308\n  end\nend\n",
                               "Polar inertia");
}

TEST(OutputIntegrity, NonFiniteAnnularIsRefused)
{
  const std::string good = example("annular") +
                           "subsection Annular seal\n  subsection Lambda sweep\n"
                           "    set Points = 0\n  end\nend\n";
  expect_refused_and_untouched("annular", "annular", good,
                               "subsection Annular seal\n  set Diameter = 1e308\nend\n",
                               "Diameter");
}

TEST(OutputIntegrity, TableWhoseEveryPointFailsKeepsTheGoodTable)
{
  const std::string good = example("table") + small_mesh +
                           "subsection Table\n  set Rotor speed = 0, 1000\n"
                           "  set Clearance = 1e-6, 1.25e-6\n  set Held-out points = 0\nend\n";
  expect_refused_and_untouched("table", "table", good,
                               "subsection Table\n  set Viscosity = 1e308, 1.5e308\nend\n",
                               "every grid point failed");
}

TEST(OutputIntegrity, ChecksOfTheResults)
{
  using sealfe::output::check_finite;
  nlohmann::json s = {{"loads", {{"force_z", 1.0}, {"moments", {0.0, NAN}}}}};
  try
  {
    check_finite(s);
    ADD_FAILURE() << "nan accepted";
  }
  catch (const std::runtime_error &e)
  {
    EXPECT_NE(std::string(e.what()).find("loads.moments[1] = nan"), std::string::npos) << e.what();
  }
  s["loads"]["moments"][1] = 2.0;
  s["none"] = nullptr; // a documented "not applicable" is not a result
  EXPECT_NO_THROW(check_finite(s));
  s["x"] = -INFINITY;
  EXPECT_THROW(check_finite(s), std::runtime_error);

  const fs::path d = sealfe::testing::fresh_directory("sealfe_output_integrity_csv");
  auto csv = [&](const std::string &text)
  {
    std::ofstream(d / "t.csv") << text;
    return (d / "t.csv").string();
  };
  using sealfe::output::check_finite_csv;
  EXPECT_NO_THROW(check_finite_csv(csv("# nan in a comment\na,b,err_K,status\n1,2,nan,ok\n"
                                       "3,nan,nan,failed: reason\n4,,5,ok\n")));
  EXPECT_THROW(check_finite_csv(csv("a,b\n1,2\n3,-nan\n")), std::runtime_error);
  EXPECT_THROW(check_finite_csv(csv("a,b\n1,inf\n")), std::runtime_error);
}

TEST(OutputIntegrity, UnwritableOutputDirectoryIsRefusedFirst)
{
  // a file where the directory should be: refused at once (before the solve), one line
  const fs::path d = sealfe::testing::fresh_directory("sealfe_output_integrity_unwritable");
  std::ofstream(d / "out") << "a file\n";
  const CliResult r = run_sealfe(d, "solve", small_mesh);
  expect_one_error_line(r, "Output directory");
  EXPECT_EQ(read_file(d / "out"), "a file\n");
  // an empty name
  const fs::path prm = d / "empty.prm";
  std::ofstream(prm) << "set Output directory =\n";
  const std::string cmd = std::string(SEALFE_BINARY) + " solve " + prm.string() + " > " +
                          (d / "stdout").string() + " 2> " + (d / "stderr").string();
  EXPECT_NE(std::system(cmd.c_str()), 0);
  EXPECT_NE(read_file(d / "stderr").find("Output directory is empty"), std::string::npos);
}

TEST(OutputIntegrity, UnwritableOutputDirectoryEndsEveryMpiRank)
{
  // mpirun -np 2: rank 0 found the error while rank 1 waited for it, forever
  const fs::path d = sealfe::testing::fresh_directory("sealfe_output_integrity_mpi");
  std::ofstream(d / "out") << "a file\n";
  // env -i: the test itself is an MPI process; mpirun must not inherit its environment
  const CliResult r =
      run_sealfe(d, "solve", small_mesh,
                 "env -i PATH=/usr/local/bin:/usr/bin:/bin OMPI_ALLOW_RUN_AS_ROOT=1 "
                 "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 "
                 "timeout 120 mpirun -np 2 ");
  EXPECT_NE(r.status, 124) << "timed out: a rank hangs";
  EXPECT_NE(r.status, 0);
  // one error line (mpirun adds its own report of the exit status)
  const std::string line = "sealfe: error: Output directory";
  EXPECT_NE(r.err.find(line), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(line), r.err.rfind(line)) << r.err;
}

TEST(OutputIntegrity, GoodRunLeavesNoStagingBehind)
{
  const fs::path d = sealfe::testing::fresh_directory("sealfe_output_integrity_good");
  const CliResult r = run_sealfe(d, "solve", small_mesh);
  ASSERT_EQ(r.status, 0) << r.err;
  for (const auto &e : fs::directory_iterator(d / "out"))
    EXPECT_EQ(e.path().filename().string().find(".sealfe-partial"), std::string::npos);
  EXPECT_NE(r.out.find("force_z"), std::string::npos);
  const auto s = nlohmann::json::parse(read_file(d / "out" / "summary.json"));
  EXPECT_EQ(s.dump().find(".sealfe-partial"), std::string::npos);
}

TEST(OutputIntegrity, NoHeldOutPointClaimsNoError)
{
  // held_out_error: [] beside max_held_out_error: 0.0 claimed a perfect interpolation
  const fs::path d = sealfe::testing::fresh_directory("sealfe_output_integrity_held_out");
  const CliResult r =
      run_sealfe(d, "table",
                 example("table") + small_mesh +
                     "subsection Table\n  set Rotor speed = 0, 1000\n"
                     "  set Clearance = 1e-6, 1.25e-6\n  set Held-out points = 0\nend\n");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto s = nlohmann::json::parse(read_file(d / "out" / "summary.json"));
  EXPECT_TRUE(s["held_out_error"].empty());
  EXPECT_TRUE(s["max_held_out_error"]["stiffness"].is_null()) << s["max_held_out_error"];
  EXPECT_TRUE(s["max_held_out_error"]["damping"].is_null());
}

TEST(OutputIntegrity, NanNeverReachesLapack)
{
  // LAPACK's DGEBAL stops the whole program (exit 0, no summary) on a nan in the matrix
  EXPECT_THROW(sealfe::real_polynomial_roots({1.0, NAN, 1.0}), std::runtime_error);
  EXPECT_EQ(sealfe::real_polynomial_roots({-1.0, 0.0, 1.0}).size(), 2u);
}
