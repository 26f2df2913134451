// Numbers and lists typed into a prm file (numerics/number_lists.h): what is accepted, what is
// refused with one line naming the entry, and prm defaults that read back exactly.
#include <sealfe/numerics/number_lists.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>

using namespace sealfe::numerics;

namespace
{
std::string refusal(const std::string &text)
{
  try
  {
    parse_number_list(text, "Table: 'Clearance'");
  }
  catch (const std::runtime_error &e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST(NumberLists, ListsAndRanges)
{
  EXPECT_EQ(parse_number_list(" 3, 1 ,2 ", "x"), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(parse_number_list("0 : 1 : 5", "x"), (std::vector<double>{0, 0.25, 0.5, 0.75, 1}));
  EXPECT_EQ(parse_number_list("2:2:1", "x"), (std::vector<double>{2}));
  EXPECT_TRUE(parse_number_list("  ", "x").empty());
  EXPECT_DOUBLE_EQ(parse_finite_number(" -1.5e-3 ", "x"), -1.5e-3);
}

TEST(NumberLists, RefusalsNameTheEntry)
{
  for (const char *bad :
       {"1, abc", "1 : 2", "1 : 2 : 2.5", "1 : 2 : 0", "1, 1", "1,,2", "1 : 2 : 1", "inf", "1e400"})
  {
    const std::string why = refusal(bad);
    EXPECT_NE(why.find("Table: 'Clearance'"), std::string::npos) << bad << ": " << why;
    EXPECT_EQ(why.find('\n'), std::string::npos) << why;
  }
  EXPECT_THROW(parse_finite_number("1.0x", "Clearance"), std::runtime_error);
}

TEST(NumberLists, PrmDefaultsReadBackExactly)
{
  for (const double v : {0.0355, 1e-6, 4e5, 1.2e-3, 0.1 + 0.2, -2.5e-300, 1e300, 0.0})
    EXPECT_EQ(std::strtod(to_prm_string(v).c_str(), nullptr), v) << to_prm_string(v);
  EXPECT_EQ(to_prm_string(1e-6), "1e-6");
  EXPECT_EQ(to_prm_string(4e5), "4e5");
  EXPECT_EQ(to_prm_string(0.0355), "0.0355");
}
