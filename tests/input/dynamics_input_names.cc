// Old names in parameter files keep working: the speed sweep of `sealfe stability` was "Sweep
// from / Sweep to / Grid points" before it took `sealfe response`'s "Speed from / Speed to /
// Speed points".
#include <sealfe/dynamics/response_study.h>
#include <sealfe/dynamics/stability_study.h>

#include <deal.II/base/parameter_handler.h>

#include <gtest/gtest.h>

using namespace sealfe;

TEST(DynamicsInputNames, StabilityAcceptsTheFormerSweepNames)
{
  dealii::ParameterHandler prm;
  stability::declare_parameters(prm);
  prm.parse_input_from_string("subsection Stability\n  set Sweep from = -123\n"
                              "  set Sweep to = 456\n  set Grid points = 7\nend\n");
  prm.enter_subsection("Stability");
  EXPECT_EQ(prm.get_double("Speed from"), -123);
  EXPECT_EQ(prm.get_double("Speed to"), 456);
  EXPECT_EQ(prm.get_integer("Speed points"), 7);
  prm.leave_subsection();
}

TEST(DynamicsInputNames, StabilityAndResponseShareTheSweepNames)
{
  for (const std::string &section : {std::string("Stability"), std::string("Forced response")})
  {
    dealii::ParameterHandler prm;
    if (section == "Stability")
      stability::declare_parameters(prm);
    else
      response::declare_parameters(prm);
    prm.parse_input_from_string("subsection " + section +
                                "\n  set Speed from = 1\n  set Speed to = 2\n"
                                "  set Speed points = 3\nend\n");
    prm.enter_subsection(section);
    EXPECT_EQ(prm.get_double("Speed from"), 1) << section;
    EXPECT_EQ(prm.get_double("Speed to"), 2) << section;
    EXPECT_EQ(prm.get_integer("Speed points"), 3) << section;
    prm.leave_subsection();
  }
}
