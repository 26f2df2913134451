// `sealfe transient` and `sealfe equilibrium` refuse impossible cases with one `sealfe: error:`
// line naming the problem and a non-zero exit, without writing a summary; a run the integrator
// cannot finish keeps its rows and says it is incomplete.
#include "../sealfe_cli.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>

using namespace sealfe::testing;

namespace
{
/// Runs `sealfe <command>` on the body; expects exit != 0, one error line containing `names`,
/// and no summary.json.
void expect_refused(const std::string &command, const std::string &body, const std::string &names)
{
  const fs::path dir = fresh_directory("sealfe_transient_input");
  const CliResult r = run_sealfe(dir, command, body);
  EXPECT_NE(r.status, 0) << body;
  EXPECT_NE(r.err.find("sealfe: error:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(names), std::string::npos) << "expected '" << names << "' in: " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "summary.json")) << body;
}
} // namespace

TEST(TransientInput, ImpossibleCasesAreRefused)
{
  expect_refused("transient", "subsection Ramps\n set Speed t1 = 5\n set Speed t2 = 4\nend\n",
                 "t1 <= t2 <= t3");
  expect_refused("transient", "subsection Thermal coning\n set Time constant = -1\nend\n",
                 "Time constant");
  expect_refused("equilibrium", "subsection Closing force\n set Balance ratio = 1.5\nend\n",
                 "Balance ratio");
  expect_refused("transient", "subsection Stator ring\n set Mass = 0\nend\n", "Mass");
  expect_refused("transient", "subsection Cavitation\n set Model = jfo\nend\n",
                 "closed-form film (level 0) gives none or half-sommerfeld");
  expect_refused("transient", "subsection Transient\n set Film level = table\nend\n",
                 "needs Transient/Table file");
  expect_refused("transient",
                 "subsection Transient\n set Film level = finite element\nend\n"
                 "subsection Contact\n set Model = gw-ceb\nend\n",
                 "Contact/Model must be none");
}

// A step-size collapse (here forced by a smallest allowed step larger than the contact transient
// admits) stops the run: exit != 0, the rows so far in transient.csv, summary.json with
// complete = false and the reason.
TEST(TransientInput, AnUnfinishedRunIsMarkedIncomplete)
{
  const fs::path dir = fresh_directory("sealfe_transient_incomplete");
  const CliResult r = run_sealfe(dir, "transient",
                                 "subsection Transient\n set End time = 0.05\n"
                                 " set Minimum step = 1e-3\n set Plot = false\nend\n");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("sealfe: error:"), std::string::npos) << r.err;
  ASSERT_TRUE(fs::exists(dir / "out" / "summary.json")) << r.err;
  const auto s = nlohmann::json::parse(read_file(dir / "out" / "summary.json"));
  EXPECT_FALSE(s.at("complete").get<bool>());
  EXPECT_NE(s.at("stop_reason").get<std::string>().find("stopped at t ="), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "out" / "transient.csv"));
}
