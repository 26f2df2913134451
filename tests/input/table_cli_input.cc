// `sealfe table` and `sealfe coefficients` through the command line: bad input is refused with one
// line on stderr naming the entry, a non-zero exit status and no summary.json.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace
{
struct Result
{
  int status;
  std::string out, err;
};

fs::path work_dir(const std::string &name)
{
  const fs::path d = fs::temp_directory_path() / ("sealfe_table_cli_input_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string read(const fs::path &f)
{
  std::ifstream in(f);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs `sealfe <command> case.prm` in `dir` with the prm body (Output directory set).
Result run(const fs::path &dir, const std::string &command, const std::string &body)
{
  const fs::path prm = dir / "case.prm";
  {
    std::ofstream out(prm);
    out << "set Output directory = " << (dir / "out").string() << "\n" << body;
  }
  const std::string cmd = std::string(SEALFE_BINARY) + " " + command + " " + prm.string() + " > " +
                          (dir / "stdout").string() + " 2> " + (dir / "stderr").string();
  const int raw = std::system(cmd.c_str());
  return {WEXITSTATUS(raw), read(dir / "stdout"), read(dir / "stderr")};
}
} // namespace

TEST(TableCli, BadInputIsRefusedWithOneLine)
{
  auto refused = [](const std::string &command, const std::string &body, const std::string &what)
  {
    const fs::path d = work_dir("bad");
    const Result r = run(d, command, body);
    EXPECT_NE(r.status, 0);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(d / "out" / "summary.json"));
  };
  refused("table", "subsection Table\n  set Rotor speed = 1 : 2\nend\n", "'Rotor speed'");
  refused("table", "subsection Table\n  set Clearance = 1e-6, abc\nend\n", "'Clearance'");
  refused("table", "subsection Table\n  set Coning = 1e-3 : 2e-3 : 2.5\nend\n", "'Coning'");
  refused("table", "subsection Table\n  set Output file = ../x.csv\nend\n", "'Output file'");
  refused("coefficients", "subsection Coefficients\n  set Relative step = -1\nend\n",
          "'Relative step'");
  refused("coefficients", "subsection Coefficients\n  set Method = secant\nend\n", "Method");
  refused("coefficients", "subsection Geometry\n  set Clearance = 0\nend\n", "Clearance");
}
