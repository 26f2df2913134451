// `sealfe table` and `sealfe coefficients` through the command line: bad input is refused with one
// line on stderr naming the entry, a non-zero exit status and no summary.json.
#include "../sealfe_cli.h"

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
using Result = sealfe::testing::CliResult;
using sealfe::testing::read_file;
using sealfe::testing::run_sealfe;

fs::path work_dir(const std::string &name)
{
  return sealfe::testing::fresh_directory("sealfe_table_cli_input_" + name);
}

} // namespace

TEST(TableCli, BadInputIsRefusedWithOneLine)
{
  auto refused = [](const std::string &command, const std::string &body, const std::string &what)
  {
    const fs::path d = work_dir("bad");
    const Result r = run_sealfe(d, command, body);
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
