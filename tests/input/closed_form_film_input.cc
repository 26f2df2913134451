// The closed-form film level (Green & Etsion's narrow-seal coefficients) describes a coned,
// tilted flat face. A stability study of a face it cannot describe (surface features, waviness,
// a film formula) stops with one line that names what and the film level to use instead,
// rather than returning the coefficients of the plain face.
#include "../sealfe_cli.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

using namespace sealfe::testing;

namespace
{
void expect_refused(const std::string &name, const std::string &geometry, const std::string &named)
{
  const fs::path dir = fresh_directory("closed_form_film_input_" + name);
  const CliResult r =
      run_sealfe(dir, "stability",
                 "subsection Geometry\n" + geometry +
                     "end\nsubsection Seal dynamics\n  set Film model = closed form\nend\n");
  EXPECT_NE(r.status, 0) << name;
  EXPECT_NE(r.err.find(named), std::string::npos) << name << ": " << r.err;
  EXPECT_NE(r.err.find("Film model = finite element"), std::string::npos) << name;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << name << ": " << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "summary.json")) << name;
}
} // namespace

TEST(ClosedFormFilmInput, StabilityRefusesWhatGreenEtsionCannotDescribe)
{
  expect_refused("grooves",
                 "  subsection Surface features\n    subsection Spiral grooves\n"
                 "      set Number = 12\n      set Depth = 4e-6\n    end\n  end\n",
                 "surface features");
  expect_refused("waviness", "  set Wave amplitude = 1e-7\n  set Wave number = 3\n", "waviness");
  expect_refused("expression", "  set Film expression = 1e-7*cos(3*theta)\n", "film expression");
}
