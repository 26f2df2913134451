// BandRoundRule (include/sealfe/film/band_round_rule.h), the choice between band rounds and
// global rounds in the JFO active-set polish, on the sequences of flips it was made for. The
// first is the finest level of the tilted seal at 1.05e6 dofs traced round by round
// (doc/performance.md "Session 20"): band rounds from the start with falling flips, a global
// round flipping 46, then a cavity boundary creeping one node per round, a different node each
// time. The others are the cases the rule names: a set going back and forth, rising flips, the
// cap of band rounds in a row, too many flips for a band, and a global round flipping more than
// the one before it.
#include <sealfe/film/band_round_rule.h>

#include <gtest/gtest.h>

#include <vector>

using namespace sealfe;

namespace
{
/// 1.05e6 / 20: the polish's limit on the seeds of a band at that size
constexpr std::size_t max_band_seeds = 52531;

struct Round
{
  bool band;
  unsigned int flips, flips_back;
};

/// Whether each round is followed by a band round, for rounds of the kinds given (each round's
/// kind is the one given, whatever the rule said before: the test states both).
std::vector<bool> next_is_band(const std::vector<Round> &rounds)
{
  BandRoundRule rule(max_band_seeds);
  std::vector<bool> next;
  for (const Round &r : rounds)
    next.push_back(rule.next_is_band(r.band, r.flips, r.flips_back));
  return next;
}
} // namespace

TEST(BandRoundRule, BandRoundsFromTheStartGoOnWhileTheirFlipsFall)
{
  // the trace's first two counts, then illustrative ones (the trace gives "1257, 591, ..., 1, 0")
  EXPECT_EQ(next_is_band({{true, 1257, 0}, {true, 591, 0}, {true, 80, 0}, {true, 1, 0}}),
            (std::vector<bool>{true, true, true, true}));
  // none flipped: a global round checks the set
  EXPECT_EQ(next_is_band({{true, 1257, 0}, {true, 0, 0}}), (std::vector<bool>{true, false}));
}

TEST(BandRoundRule, ACreepingFrontStaysInBandRounds)
{
  // the global round flips 46, then one node per band round, each not flipped the round before
  EXPECT_EQ(
      next_is_band(
          {{false, 46, 0}, {true, 1, 0}, {true, 1, 0}, {true, 1, 0}, {true, 1, 0}, {true, 0, 0}}),
      (std::vector<bool>{true, true, true, true, true, false}));
}

TEST(BandRoundRule, ASetGoingBackAndForthGoesToAGlobalRound)
{
  // as many flips as the round before, but among them nodes that flipped in it
  EXPECT_EQ(next_is_band({{false, 46, 0}, {true, 3, 0}, {true, 3, 1}}),
            (std::vector<bool>{true, true, false}));
}

TEST(BandRoundRule, RisingFlipsGoToAGlobalRound)
{
  EXPECT_EQ(next_is_band({{false, 100, 0}, {true, 50, 0}, {true, 60, 0}}),
            (std::vector<bool>{true, true, false}));
}

TEST(BandRoundRule, AtMostTenBandRoundsInARow)
{
  std::vector<Round> rounds{{false, 5, 0}};
  for (unsigned int k = 0; k < BandRoundRule::max_in_a_row; ++k)
    rounds.push_back({true, 1, 0}); // a front creeping without end
  std::vector<bool> expected(rounds.size(), true);
  expected.back() = false; // after the tenth band round in a row
  EXPECT_EQ(next_is_band(rounds), expected);
  EXPECT_EQ(BandRoundRule::max_in_a_row, 10u);
  // the count starts again after the global round
  rounds.push_back({false, 1, 0});
  expected.push_back(true);
  EXPECT_EQ(next_is_band(rounds), expected);
}

TEST(BandRoundRule, TooManyFlipsForABandGoToAGlobalRound)
{
  EXPECT_EQ(next_is_band({{false, max_band_seeds, 0}}), std::vector<bool>{false});
  EXPECT_EQ(next_is_band({{false, max_band_seeds - 1, 0}}), std::vector<bool>{true});
}

TEST(BandRoundRule, AGlobalRoundFlippingMoreEndsTheBandRoundsOfThePolish)
{
  BandRoundRule rule(max_band_seeds);
  EXPECT_TRUE(rule.next_is_band(false, 40, 0));
  EXPECT_TRUE(rule.next_is_band(true, 10, 0));
  EXPECT_FALSE(rule.next_is_band(true, 0, 0));
  EXPECT_TRUE(rule.allows_band_rounds());
  EXPECT_FALSE(rule.next_is_band(false, 50, 0)); // more than the 40 of the global round before
  EXPECT_FALSE(rule.allows_band_rounds());
  EXPECT_FALSE(rule.next_is_band(false, 2, 0)); // global rounds only from now on
  // a global round flipping fewer than the one before keeps them
  EXPECT_EQ(next_is_band({{false, 40, 0}, {true, 0, 0}, {false, 20, 0}}),
            (std::vector<bool>{true, false, true}));
}
